#include "dsp/statistics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/multiversion.h"

namespace spallkit::dsp {

namespace {

typedef double D4 __attribute__((vector_size(32)));

// Both passes with four-wide vector accumulators (GCC/Clang vector extension): plain loops are
// serial chains of dependent additions (the compiler may not reassociate them), several times
// slower. The
// passes are multi-versioned (core/multiversion.h): the baseline instruction set splits the
// 256-bit vectors. Non-finite samples show as a NaN in the sum of x - x (*check != 0).
SPALLKIT_MULTIVERSION
void SumPeakCheck(const double* p, size_t n, double* sum_out, double* peak_out, double* check_out) {
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
  *sum_out = sum;
  *peak_out = peak;
  *check_out = check;
}

// Central moments sum (x - mean)^j, j = 2, 3, 4, on deviations from the mean: no cancellation
// for records with a large offset.
SPALLKIT_MULTIVERSION
void CentralMoments(
    const double* p, size_t n, double mean, double* m2_out, double* m3_out, double* m4_out) {
  const D4 mean4 = {mean, mean, mean, mean};
  D4 v2 = {0, 0, 0, 0}, v3 = v2, v4 = v2;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
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
    const double d = p[i] - mean;
    const double d2 = d * d;
    m2 += d2;
    m3 += d2 * d;
    m4 += d2 * d2;
  }
  *m2_out = m2;
  *m3_out = m3;
  *m4_out = m4;
}

}  // namespace

TimeStatistics ComputeTimeStatistics(std::span<const double> x) {
  if (x.empty()) throw InputError("time statistics: record is empty");
  const size_t n = x.size();
  if (n > static_cast<size_t>(2147483647)) {
    throw InputError("time statistics: record longer than 2^31 - 1 samples");
  }
  double sum = 0, peak = 0, check = 0;
  SumPeakCheck(x.data(), n, &sum, &peak, &check);
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
  double m2 = 0, m3 = 0, m4 = 0;
  CentralMoments(x.data(), n, s.mean, &m2, &m3, &m4);
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

SPALLKIT_MULTIVERSION
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
