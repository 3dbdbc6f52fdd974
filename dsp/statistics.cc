#include "dsp/statistics.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"

namespace spallkit::dsp {

TimeStatistics ComputeTimeStatistics(std::span<const double> x) {
  if (x.empty()) throw InputError("time statistics: record is empty");
  const size_t n = x.size();
  if (n > static_cast<size_t>(2147483647)) {
    throw InputError("time statistics: record longer than 2^31 - 1 samples");
  }
  double sum = 0, peak = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << "time statistics: sample " << i << " is not finite (" << x[i] << ")";
      throw InputError(os.str());
    }
    sum += x[i];
    peak = std::max(peak, std::abs(x[i]));
  }
  TimeStatistics s;
  s.count = static_cast<int>(n);
  s.mean = sum / n;
  s.peak = peak;
  // Second pass on deviations from the mean: no cancellation for records with a large offset.
  double m2 = 0, m3 = 0, m4 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double d = x[i] - s.mean;
    const double d2 = d * d;
    m2 += d2;
    m3 += d2 * d;
    m4 += d2 * d2;
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  s.rms = std::sqrt(m2 + s.mean * s.mean);
  s.crest_factor = s.rms > 0 ? s.peak / s.rms : 0.0;
  // A spread far below the rounding level of the mean is a constant record.
  if (m2 > 1e-28 * (s.mean * s.mean) && m2 > 0) {
    s.kurtosis = m4 / (m2 * m2);
    s.skewness = m3 / std::pow(m2, 1.5);
  }
  return s;
}

}  // namespace spallkit::dsp
