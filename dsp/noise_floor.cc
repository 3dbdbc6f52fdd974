#include "dsp/noise_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "core/error.h"

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

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

namespace {

// Splits src[0, len) into lo (values < pivot) and hi (the rest, NaN included), keeping the
// order; returns how many went to lo. lo and hi need room for len + 8 values (the vector path
// stores whole vectors). Branch-free: on a noise spectrum every comparison is a coin flip that a
// branch predictor loses, which is where std::nth_element spends its time.
int Partition(const double* src, int len, double pivot, double* lo, double* hi) {
  int nlo = 0, nhi = 0, i = 0;
#if defined(__AVX512F__)
  const __m512d pv = _mm512_set1_pd(pivot);
  for (; i + 8 <= len; i += 8) {
    const __m512d v = _mm512_loadu_pd(src + i);
    const __mmask8 less = _mm512_cmp_pd_mask(v, pv, _CMP_LT_OQ);
    // Compress into a register and store the whole vector (compress-to-memory is microcoded
    // and slow on some cores); the lanes past the count are overwritten by the next store.
    _mm512_storeu_pd(lo + nlo, _mm512_maskz_compress_pd(less, v));
    _mm512_storeu_pd(hi + nhi, _mm512_maskz_compress_pd(static_cast<__mmask8>(~less), v));
    const int count = __builtin_popcount(less);
    nlo += count;
    nhi += 8 - count;
  }
#endif
  for (; i < len; ++i) {
    const double v = src[i];
    lo[nlo] = v;
    hi[nhi] = v;
    const bool less = v < pivot;
    nlo += less;
    nhi += !less;
  }
  return nlo;
}

// k-th smallest (0-based) of data[0, n): the value std::nth_element returns (an order statistic
// is unique as a value), by quickselect with median-of-3 pivots over the branch-free partition
// above, ping-ponging between three scratch buffers of n + 8 values each; data is not modified.
double SelectKth(const double* data, int n, int k, double* scratch) {
  const int cap = n + 8;
  double* bufs[3] = {scratch, scratch + cap, scratch + 2 * cap};
  const double* src = data;
  int cur = -1;  // which buffer src is (-1: data)
  int len = n;
  for (int round = 0; len > 16 && round < 64; ++round) {
    const double x = src[0], y = src[len / 2], z = src[len - 1];
    const double pivot = std::max(std::min(x, y), std::min(std::max(x, y), z));
    double* lo = bufs[cur == 0 ? 1 : 0];
    double* hi = bufs[cur == 2 ? 1 : 2];
    const int nlo = Partition(src, len, pivot, lo, hi);
    if (k < nlo) {
      src = lo;
      len = nlo;
    } else if (nlo > 0) {
      src = hi;
      len -= nlo;
      k -= nlo;
    } else {
      break;  // nothing below the pivot (ties at the minimum): finish below
    }
    cur = src == bufs[0] ? 0 : (src == bufs[1] ? 1 : 2);
  }
  double* work = cur >= 0 ? bufs[cur] : bufs[0];
  if (cur < 0) std::copy(src, src + len, work);
  std::nth_element(work, work + k, work + len);
  return work[k];
}

}  // namespace

NormalizedSpectrum NormalizeSpectrumWindow(std::span<const double> power,
                                           double resolution_hz,
                                           int window_bins) {
  if (!(resolution_hz > 0.0)) throw InputError("detection: resolution must be > 0 Hz");
  const int n = static_cast<int>(power.size());
  const int w = window_bins;
  if (n < w + 1)
    throw InputError("detection: spectrum has " + std::to_string(n) + " bins, need more than " +
                     std::to_string(w) + " for the noise floor (record too short)");
  NormalizedSpectrum out;
  out.power.assign(power.begin(), power.end());
  out.resolution_hz = resolution_hz;
  out.effective_samples = w * std::numbers::ln2 * std::numbers::ln2;
  out.floor.assign(n, 0.0);
  out.z.assign(n, 0.0);

  // Median of the window [start, start + w) around anchor bins spaced `step` apart.
  const int step = std::max(1, w / 6);
  std::vector<int> anchors;
  for (int i = 1; i < n; i += step) anchors.push_back(i);
  if (anchors.back() != n - 1) anchors.push_back(n - 1);
  std::vector<double> anchor_floor(anchors.size());
  std::vector<double> scratch(3 * (w + 8));
  for (size_t a = 0; a < anchors.size(); ++a) {
    int start = anchors[a] - w / 2;
    start = std::clamp(start, 1, n - w);
    anchor_floor[a] = SelectKth(power.data() + start, w, w / 2, scratch.data()) / std::numbers::ln2;
  }
  // Linear interpolation between anchors, segment by segment (loops that vectorise; the same
  // arithmetic as a bin-by-bin walk). Bins up to the first anchor take its value.
  const double tiny = std::numeric_limits<double>::min();
  double* fl = out.floor.data();
  double* z = out.z.data();
  for (int i = 1; i <= anchors[0] && i < n; ++i) fl[i] = std::max(anchor_floor[0], tiny);
  for (size_t a = 0; a + 1 < anchors.size(); ++a) {
    const int i0 = anchors[a], i1 = anchors[a + 1];
    const double f0 = anchor_floor[a], f1 = anchor_floor[a + 1];
    const double span = double(i1 - i0);
    for (int i = i0 + 1; i <= i1; ++i) {
      const double t = double(i - i0) / span;
      fl[i] = std::max((1.0 - t) * f0 + t * f1, tiny);
    }
  }
  for (int i = 1; i < n; ++i) z[i] = power[i] / fl[i];
  out.floor[0] = out.floor.size() > 1 ? out.floor[1] : 1.0;
  out.z[0] = 0.0;
  return out;
}

}  // namespace spallkit::dsp
