#include "identify/cage_average.h"

#include <algorithm>
#include <cmath>

#include "core/constants.h"
#include "core/error.h"

namespace spallkit::identify {

double CageAverage::BinCenterRad(int i) const { return (i + 0.5) * 2.0 * kPi / bins(); }

CageAverage AverageOverCage(
    std::span<const double> se, double rate_hz, double cage_hz, int bins, int pool_bins) {
  SPALLKIT_CHECK(rate_hz > 0 && cage_hz > 0 && bins > 0, "bad cage average arguments");
  const int n = static_cast<int>(se.size());
  CageAverage avg;
  avg.cage_hz = cage_hz;
  avg.revolutions = n / rate_hz * cage_hz;
  avg.whole_revolutions = static_cast<int>(std::floor(avg.revolutions));
  const int revs = std::max(1, avg.whole_revolutions);
  std::vector<double> sum(bins, 0.0), sum2(bins, 0.0), count(bins, 0.0);
  std::vector<double> rev_sum(static_cast<size_t>(revs) * bins, 0.0);
  std::vector<double> rev_count(static_cast<size_t>(revs) * bins, 0.0);
  for (int i = 0; i < n; ++i) {
    const double turns = i / rate_hz * cage_hz;
    const double whole = std::floor(turns);
    const int b = std::min(bins - 1, static_cast<int>((turns - whole) * bins));
    sum[b] += se[i];
    sum2[b] += se[i] * se[i];
    count[b] += 1.0;
    const int r = static_cast<int>(whole);
    if (r < revs) {
      rev_sum[static_cast<size_t>(r) * bins + b] += se[i];
      rev_count[static_cast<size_t>(r) * bins + b] += 1.0;
    }
  }
  avg.mean.resize(bins);
  std::vector<double> var(bins, 0.0);
  for (int b = 0; b < bins; ++b) {
    if (!(count[b] > 0))
      throw InputError("cage average: " + std::to_string(bins) +
                       " bins exceed the samples per cage revolution");
    avg.mean[b] = sum[b] / count[b];
    if (avg.whole_revolutions >= 2) {
      // Variance of the mean over revolutions: scatter of the per-revolution bin means.
      double s = 0.0, s2 = 0.0, m = 0.0;
      for (int r = 0; r < revs; ++r) {
        const double c = rev_count[static_cast<size_t>(r) * bins + b];
        if (c <= 0) continue;
        const double x = rev_sum[static_cast<size_t>(r) * bins + b] / c;
        s += x;
        s2 += x * x;
        m += 1.0;
      }
      var[b] = m > 1 ? std::max(0.0, (s2 - s * s / m) / (m - 1.0)) / m : 0.0;
    } else {
      const double mu = avg.mean[b];
      var[b] = std::max(0.0, sum2[b] / count[b] - mu * mu) / count[b];
    }
  }
  avg.sigma.resize(bins);
  for (int b = 0; b < bins; ++b) {
    double v = 0.0;
    for (int j = -pool_bins; j <= pool_bins; ++j) v += var[((b + j) % bins + bins) % bins];
    avg.sigma[b] = std::sqrt(v / (2 * pool_bins + 1));
  }
  // A bin whose pooled scatter is zero (a constant record) would get infinite weight.
  const double floor = 1e-12 * (1.0 + *std::max_element(avg.mean.begin(), avg.mean.end()));
  for (double& s : avg.sigma) s = std::max(s, floor);
  return avg;
}

}  // namespace spallkit::identify
