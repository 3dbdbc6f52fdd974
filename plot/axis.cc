#include "plot/axis.h"

#include "plot/ticks.h"

namespace spallkit::plot::internal {

std::vector<Tick> LinearTicks(double lo, double hi, int target) {
  std::vector<Tick> ticks;
  const std::vector<double> values = NiceTicks(lo, hi, target);
  const double step = values.size() >= 2 ? values[1] - values[0] : std::abs(hi - lo);
  for (double v : values) ticks.push_back({v, FormatTick(v, step)});
  return ticks;
}

namespace {

std::string DecadeLabel(int k) {
  if (k >= -3 && k <= 4) return FormatTick(std::pow(10.0, k), std::pow(10.0, k));
  return "1e" + std::to_string(k);
}

}  // namespace

std::vector<Tick> LogTicks(double lo, double hi) {
  std::vector<Tick> ticks;
  const int k0 = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  const int k1 = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  const bool few = k1 - k0 <= 2;
  for (int k = k0; k <= k1; ++k) {
    const double decade = std::pow(10.0, k);
    for (int m = 1; m <= 9; ++m) {
      const double v = m * decade;
      if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9)) continue;
      std::string label;
      if (m == 1)
        label = DecadeLabel(k);
      else if (few && (m == 2 || m == 5))
        label = FormatTick(v, decade);
      ticks.push_back({v, label});
    }
  }
  return ticks;
}

}  // namespace spallkit::plot::internal
