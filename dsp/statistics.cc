#include "dsp/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "core/error.h"

namespace spallkit::dsp {

TimeStatistics ComputeTimeStatistics(std::span<const double> x) {
  if (x.empty()) throw InputError("time statistics: record is empty");
  const size_t n = x.size();
  if (n > static_cast<size_t>(2147483647)) {
    throw InputError("time statistics: record longer than 2^31 - 1 samples");
  }
  // Both passes with four-wide vector accumulators (GCC/Clang vector extension): plain loops are
  // serial chains of dependent additions (the compiler may not reassociate them), 4x slower.
  // Non-finite samples show as a NaN in the sum of x - x, and are then located for the message.
  typedef double D4 __attribute__((vector_size(32)));
  const double* p = x.data();
  D4 vsum = {0, 0, 0, 0}, vpeak = vsum, vcheck = vsum;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    D4 v;
    std::memcpy(&v, p + i, sizeof(v));
    vsum += v;
    vcheck += v - v;
    const D4 a = v < 0 ? -v : v;
    vpeak = a > vpeak ? a : vpeak;
  }
  double sum = (vsum[0] + vsum[1]) + (vsum[2] + vsum[3]);
  double check = (vcheck[0] + vcheck[1]) + (vcheck[2] + vcheck[3]);
  double peak = std::max(std::max(vpeak[0], vpeak[1]), std::max(vpeak[2], vpeak[3]));
  for (; i < n; ++i) {
    sum += p[i];
    check += p[i] - p[i];
    peak = std::max(peak, std::abs(p[i]));
  }
  if (check != 0.0) {
    for (size_t j = 0; j < n; ++j) {
      if (!std::isfinite(x[j])) {
        std::ostringstream os;
        os << "time statistics: sample " << j << " is not finite (" << x[j] << ")";
        throw InputError(os.str());
      }
    }
  }
  // Powers up to the 4th overflow (or underflow) for |x| beyond ~1e75: compute the moments of x /
  // peak (scale-free except mean, rms, peak) so that a 1e100 spike still gives finite numbers.
  if (peak > 1e60 || (peak > 0.0 && peak < 1e-60)) {
    std::vector<double> scaled(x.begin(), x.end());
    for (double& v : scaled) v /= peak;
    TimeStatistics t = ComputeTimeStatistics(scaled);
    t.mean *= peak;
    t.rms *= peak;
    t.peak = peak;
    return t;
  }
  TimeStatistics s;
  s.count = static_cast<int>(n);
  s.mean = sum / n;
  s.peak = peak;
  // Second pass on deviations from the mean: no cancellation for records with a large offset.
  const D4 mean4 = {s.mean, s.mean, s.mean, s.mean};
  D4 v2 = {0, 0, 0, 0}, v3 = v2, v4 = v2;
  for (i = 0; i + 4 <= n; i += 4) {
    D4 v;
    std::memcpy(&v, p + i, sizeof(v));
    const D4 d = v - mean4;
    const D4 d2 = d * d;
    v2 += d2;
    v3 += d2 * d;
    v4 += d2 * d2;
  }
  double m2 = (v2[0] + v2[1]) + (v2[2] + v2[3]);
  double m3 = (v3[0] + v3[1]) + (v3[2] + v3[3]);
  double m4 = (v4[0] + v4[1]) + (v4[2] + v4[3]);
  for (; i < n; ++i) {
    const double d = p[i] - s.mean;
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

double SumOfSquares(std::span<const double> v) {
  typedef double D4 __attribute__((vector_size(32)));
  const int count = static_cast<int>(v.size());
  D4 a = {0, 0, 0, 0}, b = a;
  int j = 0;
  for (; j + 8 <= count; j += 8) {
    D4 x, y;
    std::memcpy(&x, v.data() + j, sizeof(x));
    std::memcpy(&y, v.data() + j + 4, sizeof(y));
    a += x * x;
    b += y * y;
  }
  a += b;
  double total = (a[0] + a[1]) + (a[2] + a[3]);
  for (; j < count; ++j) total += v[j] * v[j];
  return total;
}

}  // namespace spallkit::dsp
