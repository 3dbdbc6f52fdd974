#include "identify/line_dft.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/constants.h"

namespace spallkit::identify {

std::complex<double> DftAt(std::span<const double> se, double mean, double rate_hz, double f_hz) {
  const int n = static_cast<int>(se.size());
  const std::complex<double> w = std::polar(1.0, -2.0 * kPi * f_hz / rate_hz);
  std::complex<double> z = 1.0, acc = 0.0;
  for (int i = 0; i < n; ++i) {
    acc += (se[i] - mean) * z;
    z *= w;
    if ((i & 1023) == 1023) z = std::polar(1.0, -2.0 * kPi * f_hz * (i + 1) / rate_hz);
  }
  return acc / static_cast<double>(std::max(1, n));
}

double RefineRate(std::span<const double> se,
                  double rate_hz,
                  double guess_hz,
                  double half_range_hz,
                  int orders,
                  int steps) {
  double mean = 0.0;
  for (double v : se) mean += v;
  mean /= std::max<size_t>(1, se.size());
  auto power = [&](double f) {
    double p = 0.0;
    for (int m = 1; m <= orders; ++m) p += std::norm(DftAt(se, mean, rate_hz, m * f)) / m;
    return p;
  };
  steps = std::max(3, steps);
  std::vector<double> f(steps), p(steps);
  int best = 0;
  for (int k = 0; k < steps; ++k) {
    f[k] = guess_hz - half_range_hz + 2.0 * half_range_hz * k / (steps - 1);
    p[k] = power(f[k]);
    if (p[k] > p[best]) best = k;
  }
  if (best == 0 || best == steps - 1) return f[best];
  const double den = p[best - 1] - 2.0 * p[best] + p[best + 1];
  const double shift = den < 0 ? 0.5 * (p[best - 1] - p[best + 1]) / den : 0.0;
  return f[best] + shift * (f[1] - f[0]);
}

}  // namespace spallkit::identify
