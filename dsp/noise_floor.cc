#include "dsp/noise_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "core/error.h"
#include "dsp/order_statistic.h"

namespace spallkit::dsp {

double NormalizedSpectrum::BinTail(double z_value) const {
  if (z_value <= 0.0) return 1.0;
  // Lomax: E[exp(-t mu_hat / mu)] with mu_hat / mu ~ Gamma(n, 1/n).
  return std::exp(-effective_samples * std::log1p(z_value / effective_samples));
}

double NormalizedSpectrum::PairPValue(double z_value) const {
  const double q = BinTail(z_value);
  // 1 - (1 - q)^2 without cancellation for small q.
  return q * (2.0 - q);
}

NormalizedSpectrum NormalizeSpectrumWindow(std::span<const double> power,
                                           double resolution_hz,
                                           int window_bins,
                                           std::span<const double> shape) {
  if (!(resolution_hz > 0.0)) throw InputError("detection: resolution must be > 0 Hz");
  const int n = static_cast<int>(power.size());
  const int w = window_bins;
  if (n < w + 1)
    throw InputError("detection: spectrum has " + std::to_string(n) + " bins, need more than " +
                     std::to_string(w) + " for the noise floor (record too short)");
  SPALLKIT_CHECK(shape.empty() || static_cast<int>(shape.size()) == n,
                 "noise floor: shape of " << shape.size() << " values for " << n << " bins");
  NormalizedSpectrum out;
  out.power.assign(power.begin(), power.end());
  out.resolution_hz = resolution_hz;
  out.effective_samples = w * std::numbers::ln2 * std::numbers::ln2;
  out.floor.resize(n);
  // z holds the spectrum the median runs on (flattened by the shape, if any) until it is divided
  // by the floor at the end.
  out.z.resize(n);
  double* z = out.z.data();
  if (shape.empty()) {
    std::copy(power.begin(), power.end(), z);
  } else {
    for (int i = 0; i < n; ++i) z[i] = power[i] / shape[i];
  }

  // Median of the window [start, start + w) around anchor bins spaced `step` apart.
  const int step = std::max(1, w / 6);
  std::vector<int> anchors;
  for (int i = 1; i < n; i += step) anchors.push_back(i);
  if (anchors.back() != n - 1) anchors.push_back(n - 1);
  std::vector<int> starts(anchors.size());
  for (size_t a = 0; a < anchors.size(); ++a) starts[a] = std::clamp(anchors[a] - w / 2, 1, n - w);
  std::vector<double> anchor_floor(anchors.size());
  SlidingSelectKth(z, starts, w, w / 2, anchor_floor);
  for (double& f : anchor_floor) f /= std::numbers::ln2;
  // Linear interpolation between anchors, segment by segment (loops that vectorise; the same
  // arithmetic as a bin-by-bin walk). Bins up to the first anchor take its value. Every segment
  // but the last spans `step` bins: their positions t are divided out once.
  std::vector<double> t_step(step + 1);
  for (int j = 1; j <= step; ++j) t_step[j] = double(j) / double(step);
  const double tiny = std::numeric_limits<double>::min();
  double* fl = out.floor.data();
  for (int i = 1; i <= anchors[0] && i < n; ++i) fl[i] = std::max(anchor_floor[0], tiny);
  for (size_t a = 0; a + 1 < anchors.size(); ++a) {
    const int i0 = anchors[a], i1 = anchors[a + 1];
    const double f0 = anchor_floor[a], f1 = anchor_floor[a + 1];
    if (i1 - i0 == step) {
      const double* t = t_step.data();
      for (int j = 1; j <= step; ++j) fl[i0 + j] = std::max((1.0 - t[j]) * f0 + t[j] * f1, tiny);
    } else {
      const double span = double(i1 - i0);
      for (int i = i0 + 1; i <= i1; ++i) {
        const double t = double(i - i0) / span;
        fl[i] = std::max((1.0 - t) * f0 + t * f1, tiny);
      }
    }
  }
  for (int i = 1; i < n; ++i) z[i] /= fl[i];
  out.floor[0] = out.floor.size() > 1 ? out.floor[1] : 1.0;
  out.z[0] = 0.0;
  if (!shape.empty())
    for (int i = 0; i < n; ++i) fl[i] *= shape[i];
  return out;
}

}  // namespace spallkit::dsp
