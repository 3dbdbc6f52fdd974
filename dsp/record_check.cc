#include "dsp/record_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace spallkit::dsp {

RecordCheck CheckRecord(std::span<const double> x, const RecordCheckOptions& options) {
  if (x.empty()) throw InputError("diagnose: the record is empty");
  const size_t n = x.size();
  double lo = x[0], hi = x[0];
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) {
      char buf[160];
      std::snprintf(buf,
                    sizeof buf,
                    "diagnose: sample %zu is not finite (%g): the record cannot be analysed",
                    i,
                    x[i]);
      throw InputError(buf);
    }
    lo = std::min(lo, x[i]);
    hi = std::max(hi, x[i]);
  }
  // Constant: no spread beyond the rounding of the values themselves.
  if (!(hi - lo > 1e-12 * std::max(std::abs(hi), std::abs(lo))) || hi == lo) {
    char buf[160];
    std::snprintf(buf,
                  sizeof buf,
                  "diagnose: the record is constant (every sample = %g): no vibration to analyse",
                  x[0]);
    throw InputError(buf);
  }

  RecordCheck c;
  // Robust spread from a subsample (every 4th sample of long records: the median and MAD of a
  // 100k-sample subsample are within a percent of the full ones, at a quarter of the cost).
  const size_t stride = n > 400000 ? 4 : 1;
  std::vector<double> v;
  v.reserve(n / stride + 1);
  for (size_t i = 0; i < n; i += stride) v.push_back(x[i]);
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double median = v[mid];
  for (double& e : v) e = std::abs(e - median);
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  c.robust_sigma = 1.4826 * v[mid];
  char buf[256];
  if (c.robust_sigma > 0.0) {
    const double limit = options.outlier_sigmas * c.robust_sigma;
    double largest = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double d = std::abs(x[i] - median);
      if (d > limit) {
        ++c.outliers;
        if (d > largest) {
          largest = d;
          c.largest_outlier_index = static_cast<long>(i);
        }
      }
    }
    if (c.outliers > 0) {
      std::snprintf(buf,
                    sizeof buf,
                    "%d sample(s) beyond %.0f robust standard deviations (largest %g at sample "
                    "%ld): spikes or dropouts, which can make or hide a fault comb",
                    c.outliers,
                    options.outlier_sigmas,
                    x[c.largest_outlier_index],
                    c.largest_outlier_index);
      c.warnings.push_back(buf);
    }
  } else {
    // More than half the samples are one value: a mostly stuck channel.
    c.warnings.push_back(
        "more than half of the samples have the same value: a stuck or mostly silent channel");
  }
  // Clipping: runs of samples stuck at either extreme.
  for (const double rail : {hi, lo}) {
    int run = 0;
    for (size_t i = 0; i <= n; ++i) {
      if (i < n && x[i] == rail) {
        ++run;
      } else {
        if (run >= options.clip_run) ++c.clipped_runs;
        run = 0;
      }
    }
  }
  if (c.clipped_runs >= options.clip_runs) {
    std::snprintf(buf,
                  sizeof buf,
                  "clipped: %d runs of >= %d samples stuck at the extreme values (%g, %g): the "
                  "sensor or its amplifier saturated",
                  c.clipped_runs,
                  options.clip_run,
                  lo,
                  hi);
    c.warnings.push_back(buf);
  }
  return c;
}

}  // namespace spallkit::dsp
