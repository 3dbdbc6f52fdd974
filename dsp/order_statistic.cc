#include "dsp/order_statistic.h"

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SPALLKIT_AVX512_PARTITION 1
#endif

#include "core/error.h"

namespace spallkit::dsp {
namespace {

// Splits src[i, len) into lo (values < pivot) and hi (the rest, NaN included), keeping the
// order, after nlo / nhi values already placed; returns how many went to lo in all. Branch-free:
// on a noise spectrum every comparison is a coin flip that a branch predictor loses, which is
// where std::nth_element spends its time.
inline int PartitionTail(
    const double* src, int i, int len, double pivot, double* lo, double* hi, int nlo, int nhi) {
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

#ifdef SPALLKIT_AVX512_PARTITION
// Eight values at a time: compress into a register and store the whole vector (compress-to-
// memory is microcoded and slow on some cores); the lanes past the count are overwritten by the
// next store, so lo and hi need room for len + 8 values.
__attribute__((target("avx512f"))) int PartitionAvx512(
    const double* src, int len, double pivot, double* lo, double* hi) {
  int nlo = 0, nhi = 0, i = 0;
  const __m512d pv = _mm512_set1_pd(pivot);
  for (; i + 8 <= len; i += 8) {
    const __m512d v = _mm512_loadu_pd(src + i);
    const __mmask8 less = _mm512_cmp_pd_mask(v, pv, _CMP_LT_OQ);
    _mm512_storeu_pd(lo + nlo, _mm512_maskz_compress_pd(less, v));
    _mm512_storeu_pd(hi + nhi, _mm512_maskz_compress_pd(static_cast<__mmask8>(~less), v));
    const int count = __builtin_popcount(less);
    nlo += count;
    nhi += 8 - count;
  }
  return PartitionTail(src, i, len, pivot, lo, hi, nlo, nhi);
}

bool HasAvx512() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f");
}
#endif

// Counts the values of src[i, len) below lo_pivot and appends those in [lo_pivot, hi_pivot] to
// kept after nkept already there; returns the new kept count. Branch-free, as PartitionTail.
inline int BracketTail(const double* src,
                       int i,
                       int len,
                       double lo_pivot,
                       double hi_pivot,
                       double* kept,
                       int nkept,
                       int* below) {
  int nbelow = *below;
  for (; i < len; ++i) {
    const double v = src[i];
    kept[nkept] = v;
    nbelow += v < lo_pivot;
    nkept += (v >= lo_pivot) & (v <= hi_pivot);
  }
  *below = nbelow;
  return nkept;
}

#ifdef SPALLKIT_AVX512_PARTITION
// kept needs room for len + 8 values (whole-vector stores, as PartitionAvx512).
__attribute__((target("avx512f"))) int BracketAvx512(
    const double* src, int len, double lo_pivot, double hi_pivot, double* kept, int* below) {
  int nkept = 0, nbelow = 0, i = 0;
  const __m512d lo = _mm512_set1_pd(lo_pivot), hi = _mm512_set1_pd(hi_pivot);
  for (; i + 8 <= len; i += 8) {
    const __m512d v = _mm512_loadu_pd(src + i);
    const __mmask8 less = _mm512_cmp_pd_mask(v, lo, _CMP_LT_OQ);
    const __mmask8 in =
        _mm512_cmp_pd_mask(v, lo, _CMP_GE_OQ) & _mm512_cmp_pd_mask(v, hi, _CMP_LE_OQ);
    _mm512_storeu_pd(kept + nkept, _mm512_maskz_compress_pd(in, v));
    nbelow += __builtin_popcount(less);
    nkept += __builtin_popcount(in);
  }
  *below = nbelow;
  return BracketTail(src, i, len, lo_pivot, hi_pivot, kept, nkept, below);
}
#endif

int Bracket(
    const double* src, int len, double lo_pivot, double hi_pivot, double* kept, int* below) {
#ifdef SPALLKIT_AVX512_PARTITION
  static const bool avx512 = HasAvx512();
  if (avx512) return BracketAvx512(src, len, lo_pivot, hi_pivot, kept, below);
#endif
  *below = 0;
  return BracketTail(src, 0, len, lo_pivot, hi_pivot, kept, 0, below);
}

int Partition(const double* src, int len, double pivot, double* lo, double* hi) {
#ifdef SPALLKIT_AVX512_PARTITION
  static const bool avx512 = HasAvx512();
  if (avx512) return PartitionAvx512(src, len, pivot, lo, hi);
#endif
  return PartitionTail(src, 0, len, pivot, lo, hi, 0, 0);
}

}  // namespace

double SelectKth(const double* data, int n, int k, double* scratch) {
  SPALLKIT_CHECK(k >= 0 && k < n, "SelectKth: k " << k << " of " << n << " values");
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
  // A few values left: the one whose rank (values below it, and ties) holds k, counted without
  // branches on the data (a sort's comparisons here are coin flips as well).
  for (int i = 0; i < len; ++i) {
    int below = 0, ties = 0;
    for (int j = 0; j < len; ++j) {
      below += src[j] < src[i];
      ties += src[j] == src[i];
    }
    if (below <= k && k < below + ties) return src[i];
  }
  // Only NaN compares as neither: order them as std::nth_element does.
  double* work = cur >= 0 ? bufs[cur] : bufs[0];
  if (cur < 0) std::copy(src, src + len, work);
  std::nth_element(work, work + k, work + len);
  return work[k];
}

void SlidingSelectKth(
    const double* data, std::span<const int> starts, int w, int k, std::span<double> out) {
  SPALLKIT_CHECK(k >= 0 && k < w && out.size() >= starts.size(),
                 "SlidingSelectKth: k " << k << " of " << w << " values, " << out.size()
                                        << " outputs for " << starts.size() << " windows");
  std::vector<double> scratch(4 * (static_cast<size_t>(w) + 8));
  double* kept = scratch.data();
  double* select_scratch = kept + (w + 8);
  // The bracket's half-width as a fraction of the answer, steered towards keeping about
  // `target` values: wide enough that the answer's rank, which moves by a few in a step of a
  // running median, stays inside; narrow enough that the selection among them is cheap.
  const int target = std::max(16, w / 8);
  double fraction = 0.2;
  bool have_previous = false;
  double previous = 0.0;
  for (size_t a = 0; a < starts.size(); ++a) {
    const double* window = data + starts[a];
    if (have_previous) {
      const double half = fraction * std::abs(previous);
      int below = 0;
      const int nkept = Bracket(window, w, previous - half, previous + half, kept, &below);
      if (below <= k && k < below + nkept) {
        out[a] = previous = SelectKth(kept, nkept, k - below, select_scratch);
        fraction = std::clamp(fraction * target / std::max(nkept, 1), 1e-6, 1.0);
        continue;
      }
      fraction = std::min(2.0 * fraction, 1.0);
    }
    out[a] = previous = SelectKth(window, w, k, select_scratch);
    have_previous = std::isfinite(previous);
  }
}

double SelectKth(std::span<const double> data, int k) {
  const int n = static_cast<int>(data.size());
  std::vector<double> scratch(3 * (static_cast<size_t>(n) + 8));
  return SelectKth(data.data(), n, k, scratch.data());
}

}  // namespace spallkit::dsp
