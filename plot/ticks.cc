#include "plot/ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spallkit::plot {

std::vector<double> NiceTicks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  target = std::max(target, 1);
  const double raw = (hi - lo) / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / magnitude;
  // The nice step closest to the raw one (geometric midpoints 1.41, 3.16, 7.07).
  double step = 10 * magnitude;
  if (norm < 1.41)
    step = magnitude;
  else if (norm < 3.16)
    step = 2 * magnitude;
  else if (norm < 7.07)
    step = 5 * magnitude;
  const double eps = step * 1e-9;
  const double first = std::ceil((lo - eps) / step);
  for (double k = first;; k += 1) {
    double v = k * step;
    if (v > hi + eps) break;
    if (std::abs(v) < eps) v = 0;  // no "-0"
    ticks.push_back(v);
    if (ticks.size() > 1000) break;
  }
  return ticks;
}

std::string FormatTick(double value, double step) {
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) step = std::abs(value) > 0 ? std::abs(value) : 1;
  if (std::abs(value) < step * 1e-9) return "0";
  char buf[64];
  const double big = std::max(std::abs(value), step);
  if (big >= 1e6 || big < 1e-4) {
    // Exponent form with as many mantissa digits as the step needs.
    const int digits = std::clamp(
        static_cast<int>(std::floor(std::log10(std::abs(value))) - std::floor(std::log10(step))),
        0,
        10);
    std::snprintf(buf, sizeof buf, "%.*e", digits, value);
    // "1.5e+06" -> "1.5e6", "2e-05" -> "2e-5"
    std::string s = buf;
    const size_t e = s.find('e');
    std::string mant = s.substr(0, e);
    int exp = std::stoi(s.substr(e + 1));
    return mant + "e" + std::to_string(exp);
  }
  int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  // Steps like 0.25 or 2.5 need one more digit than their magnitude says.
  const double scaled = step * std::pow(10.0, decimals);
  if (std::abs(scaled - std::round(scaled)) > 1e-6 * scaled) ++decimals;
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), value);
  return buf;
}

}  // namespace spallkit::plot
