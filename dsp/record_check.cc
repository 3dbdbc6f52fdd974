#include "dsp/record_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/multiversion.h"
#include "dsp/order_statistic.h"

namespace spallkit::dsp {

namespace {

// Smallest and largest sample and whether every sample is finite, in one pass with vector
// accumulators (x - x is 0 for a finite sample and NaN otherwise; min and max are taken on
// values). Written with the GCC/Clang vector extension: the compiler does not vectorise
// floating-point reductions by itself (it may not reassociate them).
SPALLKIT_MULTIVERSION
bool FiniteRange(const double* x, size_t n, double* lo, double* hi) {
  typedef double D4 __attribute__((vector_size(32)));
  D4 check = {0, 0, 0, 0}, mn = {x[0], x[0], x[0], x[0]}, mx = mn;
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    D4 v;
    std::memcpy(&v, x + i, sizeof v);
    check += v - v;
    mn = v < mn ? v : mn;
    mx = v > mx ? v : mx;
  }
  double c = (check[0] + check[1]) + (check[2] + check[3]);
  double l = std::min(std::min(mn[0], mn[1]), std::min(mn[2], mn[3]));
  double h = std::max(std::max(mx[0], mx[1]), std::max(mx[2], mx[3]));
  for (; i < n; ++i) {
    c += x[i] - x[i];
    l = std::min(l, x[i]);
    h = std::max(h, x[i]);
  }
  *lo = l;
  *hi = h;
  return c == 0.0;
}

// Samples with |x - median| > limit (a count that vectorises; the scan for the largest one only
// runs when there is any).
SPALLKIT_MULTIVERSION
int CountBeyond(const double* x, size_t n, double median, double limit) {
  int count = 0;
  for (size_t i = 0; i < n; ++i) count += std::abs(x[i] - median) > limit;
  return count;
}

// Runs of >= run_length samples equal to hi, plus those equal to lo, in one pass: blocks with no
// sample at either rail (nearly all of them) are skipped with a test that vectorises, and a run
// is counted where it ends, so runs across block edges are counted once.
SPALLKIT_MULTIVERSION
int ClippedRuns(const double* x, size_t n, double lo, double hi, int run_length) {
  constexpr size_t kBlock = 256;
  int runs = 0, run_hi = 0, run_lo = 0;
  auto end_runs = [&] {
    runs += (run_hi >= run_length) + (run_lo >= run_length);
    run_hi = run_lo = 0;
  };
  for (size_t start = 0; start < n; start += kBlock) {
    const size_t stop = std::min(n, start + kBlock);
    int hits = 0;
    for (size_t i = start; i < stop; ++i) hits += (x[i] == hi) | (x[i] == lo);
    if (hits == 0) {
      end_runs();
      continue;
    }
    for (size_t i = start; i < stop; ++i) {
      if (x[i] == hi) {
        ++run_hi;
      } else {
        runs += run_hi >= run_length;
        run_hi = 0;
      }
      if (x[i] == lo) {
        ++run_lo;
      } else {
        runs += run_lo >= run_length;
        run_lo = 0;
      }
    }
  }
  end_runs();
  return runs;
}

}  // namespace

RecordCheck CheckRecord(std::span<const double> x, const RecordCheckOptions& options) {
  if (x.empty()) throw InputError("diagnose: the record is empty");
  const size_t n = x.size();
  double lo = x[0], hi = x[0];
  if (!FiniteRange(x.data(), n, &lo, &hi)) {
    for (size_t i = 0; i < n; ++i) {
      if (std::isfinite(x[i])) continue;
      char buf[160];
      std::snprintf(buf,
                    sizeof buf,
                    "diagnose: sample %zu is not finite (%g): the record cannot be analysed",
                    i,
                    x[i]);
      throw InputError(buf);
    }
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
  // Per-thread buffers kept between calls (fresh ones cost a zero fill and page faults).
  thread_local std::vector<double> v, scratch;
  v.resize((n + stride - 1) / stride);
  for (size_t i = 0, j = 0; i < n; i += stride, ++j) v[j] = x[i];
  const int count = static_cast<int>(v.size()), mid = count / 2;
  scratch.resize(3 * (static_cast<size_t>(count) + 8));
  const double median = SelectKth(v.data(), count, mid, scratch.data());
  for (double& e : v) e = std::abs(e - median);
  c.robust_sigma = 1.4826 * SelectKth(v.data(), count, mid, scratch.data());
  char buf[256];
  if (c.robust_sigma > 0.0) {
    const double limit = options.outlier_sigmas * c.robust_sigma;
    c.outliers = CountBeyond(x.data(), n, median, limit);
    double largest = 0.0;
    for (size_t i = 0; i < n && c.outliers > 0; ++i) {
      const double d = std::abs(x[i] - median);
      if (d > limit && d > largest) {
        largest = d;
        c.largest_outlier_index = static_cast<long>(i);
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
  c.clipped_runs = ClippedRuns(x.data(), n, lo, hi, options.clip_run);
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
