#include "dsp/kurtogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"

namespace spallkit::dsp {
namespace {

// log2(3) - 1: the offset of the ternary rows (1.585, 2.585, ...).
const double kTernaryOffset = std::log2(3.0) - 1.0;

struct Row {
  double level;
  int nodes;
};

std::vector<Row> RowsFor(int max_level) {
  std::vector<Row> rows{{0.0, 1}};
  for (int k = 1; k <= max_level; ++k) {
    rows.push_back({static_cast<double>(k), 1 << k});
    if (k < max_level) rows.push_back({k + kTernaryOffset, 3 << (k - 1)});
  }
  return rows;
}

// First FFT bin of node i of a row with `nodes` nodes over bins 0..n/2: ceil(i * n / (2 nodes)).
int FirstBin(int64_t i, int64_t nodes, int64_t n) {
  return static_cast<int>((i * n + 2 * nodes - 1) / (2 * nodes));
}

// sum p and sum p^2 with four-wide vector accumulators (GCC/Clang vector extension): a plain
// loop would be a serial chain of dependent additions, as the compiler may not reassociate.
void SumAndSumOfSquares(const double* p, int m, double* sum, double* sum_sq) {
  typedef double V4 __attribute__((vector_size(32)));
  V4 s = {0, 0, 0, 0}, q = {0, 0, 0, 0}, s1 = s, q1 = q;
  int j = 0;
  for (; j + 8 <= m; j += 8) {
    V4 a, b;
    std::memcpy(&a, p + j, sizeof(a));
    std::memcpy(&b, p + j + 4, sizeof(b));
    s += a;
    q += a * a;
    s1 += b;
    q1 += b * b;
  }
  s += s1;
  q += q1;
  double total = (s[0] + s[1]) + (s[2] + s[3]);
  double total_sq = (q[0] + q[1]) + (q[2] + q[3]);
  for (; j < m; ++j) {
    total += p[j];
    total_sq += p[j] * p[j];
  }
  *sum = total;
  *sum_sq = total_sq;
}

// Copies bins [lo, hi) of x, times `scale`, to single precision in out[0 .. hi-lo), with the
// analytic-signal weights (1 inside, 1/2 at DC and Nyquist), and returns the node's energy
// sum |w_k x_k|^2 (unscaled). Written with four-wide vectors (GCC/Clang extension): it streams
// the whole spectrum once per row, so it has to run at memory speed.
double FillNode(
    const std::complex<double>* x, int lo, int hi, int n, double scale, std::complex<float>* out) {
  typedef double V4 __attribute__((vector_size(32)));
  typedef float F4 __attribute__((vector_size(16)));
  const double* d = reinterpret_cast<const double*>(x + lo);
  float* f = reinterpret_cast<float*>(out);
  const int count = 2 * (hi - lo);  // doubles
  V4 s0 = {0, 0, 0, 0};
  const V4 k = {scale, scale, scale, scale};
  int j = 0;
  for (; j + 4 <= count; j += 4) {
    V4 a;
    std::memcpy(&a, d + j, sizeof(a));
    s0 += a * a;
    const F4 b = __builtin_convertvector(a * k, F4);
    std::memcpy(f + j, &b, sizeof(b));
  }
  double total = (s0[0] + s0[1]) + (s0[2] + s0[3]);
  for (; j < count; ++j) {
    total += d[j] * d[j];
    f[j] = static_cast<float>(d[j] * scale);
  }
  if (lo == 0) {
    total -= 0.75 * std::norm(x[0]);
    out[0] *= 0.5f;
  }
  if (2 * (hi - 1) == n) {
    total -= 0.75 * std::norm(x[hi - 1]);
    out[hi - 1 - lo] *= 0.5f;
  }
  return total;
}

// Per-thread node buffers, kept between calls and grown on demand: a 10 s record needs ~11 MB of
// them, and fresh allocations of that size cost page faults on every call (10 % of the run time).
struct NodeBuffers {
  size_t size = 0;
  FftwArray<std::complex<float>> filled, envelope;
  std::unique_ptr<double[]> power;
};

NodeBuffers& ThreadBuffers(size_t size) {
  thread_local NodeBuffers buffers;
  if (buffers.size < size) {
    buffers.filled = AllocateComplexF(size);
    buffers.envelope = AllocateComplexF(size);
    buffers.power = std::make_unique<double[]>(size);
    buffers.size = size;
  }
  return buffers;
}

int MaxLevelFor(int n) {
  return static_cast<int>(std::floor(std::log2(static_cast<double>(n)))) - 4;
}

}  // namespace

double Kurtogram::BandwidthHz(int row) const {
  const double level = levels.at(row);
  const int whole = static_cast<int>(std::floor(level + 1e-9));
  const bool ternary = level - whole > 1e-6;
  const double nodes = ternary ? 3.0 * std::ldexp(1.0, whole - 1) : std::ldexp(1.0, whole);
  return 0.5 * sample_rate_hz / nodes;
}

std::vector<KurtogramNode> Kurtogram::Nodes() const {
  std::vector<KurtogramNode> out;
  for (size_t r = 0; r < levels.size(); ++r) {
    const double bw = BandwidthHz(static_cast<int>(r));
    for (size_t i = 0; i < kurtosis[r].size(); ++i) {
      KurtogramNode node;
      node.level = levels[r];
      node.index = static_cast<int>(i);
      node.bandwidth_hz = bw;
      node.center_hz = (i + 0.5) * bw;
      node.kurtosis = kurtosis[r][i];
      out.push_back(node);
    }
  }
  return out;
}

Kurtogram FastKurtogram(const EnvelopeAnalyzer& analyzer, const KurtogramOptions& options) {
  const int n = analyzer.size();
  const double fs = analyzer.sample_rate_hz();
  const int limit = MaxLevelFor(n);
  int max_level = options.max_level;
  if (max_level == 0) max_level = std::clamp(limit - 3, 1, 9);
  if (max_level < 1 || max_level > limit) {
    std::ostringstream os;
    os << "kurtogram max_level " << options.max_level << ": expected 0 (auto) or 1.." << limit
       << " for a record of " << n << " samples";
    throw InputError(os.str());
  }
  if (!(options.min_center_hz < 0.5 * fs)) {
    std::ostringstream os;
    os << "kurtogram min_center_hz " << options.min_center_hz
       << ": expected below fs/2 = " << 0.5 * fs << " Hz";
    throw InputError(os.str());
  }

  const auto& x = analyzer.spectrum();
  const int bins = n / 2 + 1;
  const std::vector<Row> rows = RowsFor(max_level);

  Kurtogram out;
  out.sample_rate_hz = fs;
  out.max_level = max_level;

  // Size of each row's batch, and the largest, so one buffer serves every row.
  std::vector<int> row_m(rows.size());
  size_t buffer_size = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    int widest = 0;
    for (int i = 0; i < rows[r].nodes; ++i) {
      const int lo = FirstBin(i, rows[r].nodes, n);
      const int hi = (i + 1 == rows[r].nodes) ? bins : FirstBin(i + 1, rows[r].nodes, n);
      widest = std::max(widest, hi - lo);
    }
    // M >= 2B - 1: |c|^4 spans +-2(B-1) bins, so the decimated moments are exact. (Critical
    // sampling, M >= B, would halve the cost but misses envelope peaks: on impulsive test signals
    // its kurtosis was off by 27 % in nodes of 1000 bins and by 130 % in narrow ones.)
    row_m[r] = FftFastSize(std::max(2 * widest - 1, 1));
    buffer_size = std::max(buffer_size, static_cast<size_t>(row_m[r]));
  }
  // Node energies by Parseval (analytic weights). A node holding less than kEmptyNode of the
  // record's energy carries only rounding residue, whose kurtosis is meaningless: reported as 0.
  double total_energy = 0;
  for (int k = 0; k < bins; ++k) {
    const bool edge = (k == 0) || (2 * k == n);
    total_energy += (edge ? 0.25 : 1.0) * std::norm(x[k]);
  }
  const double scale = total_energy > 0 ? 1.0 / std::sqrt(total_energy / bins) : 1.0;
  constexpr double kEmptyNode = 1e-20;

  // Rows are independent: spread them over threads (dynamic, the widest rows first as listed).
  // Each row's arithmetic is the same whatever the thread count, so results are identical.
  std::vector<std::vector<double>> result(rows.size());
  const int row_count = static_cast<int>(rows.size());
#ifdef _OPENMP
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel num_threads(std::min(threads, row_count))
#endif
  {
    // Aligned node buffers, one set per thread, reused by every node (fill -> transform ->
    // moments while the node's data are in cache); out of place, as FFTW's in-place plans add
    // copy passes.
    NodeBuffers& buffers = ThreadBuffers(buffer_size);
    std::complex<float>* const filled = buffers.filled.get();
    std::complex<float>* const envelope = buffers.envelope.get();
    double* const power = buffers.power.get();
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
    for (int r = 0; r < row_count; ++r) {
      const int nodes = rows[r].nodes;
      const int m = row_m[r];
      ComplexFftF fft(m, +1);
      std::vector<double> row(nodes);
      for (int i = 0; i < nodes; ++i) {
        // Ideal one-sided band-pass of the node, shifted to DC (weights as for an analytic
        // signal, 1 inside and 1/2 at DC and Nyquist; the overall scale cancels in the kurtosis).
        const int lo = FirstBin(i, nodes, n);
        const int hi = (i + 1 == nodes) ? bins : FirstBin(i + 1, nodes, n);
        // Single precision from here, scaled to the record's RMS bin so the float range is never
        // an issue; the kurtosis needs ~6 significant digits and gets them.
        const double energy = FillNode(x.data(), lo, hi, n, scale, filled);
        if (!(energy > kEmptyNode * total_energy)) {
          row[i] = 0.0;
          continue;
        }
        std::fill(filled + (hi - lo), filled + m, std::complex<float>(0.0f));
        std::complex<float>* in = filled;
        fft.Execute(in, envelope);
        // |c|^2 first (an elementwise loop that vectorises), then two plain reductions.
        const float* c = reinterpret_cast<const float*>(envelope);
        double* p = power;
        for (int j = 0; j < m; ++j) {
          const double re = c[2 * j], im = c[2 * j + 1];
          p[j] = re * re + im * im;
        }
        double sum2 = 0, sum4 = 0;
        SumAndSumOfSquares(p, m, &sum2, &sum4);
        const double k = sum2 > 0 ? m * sum4 / (sum2 * sum2) - 2.0 : 0.0;
        row[i] = std::max(0.0, k);
      }
      result[r] = std::move(row);
    }
  }
  for (int r = 0; r < row_count; ++r) out.levels.push_back(rows[r].level);
  out.kurtosis = std::move(result);

  // Best node: highest kurtosis among nodes centred at or above min_center_hz; on a tie the
  // coarser level (wider band, listed first) wins; values within 1e-5 (single-precision rounding)
  // count as ties.
  bool found = false;
  for (size_t r = 0; r < out.levels.size(); ++r) {
    const double bw = out.BandwidthHz(static_cast<int>(r));
    for (size_t i = 0; i < out.kurtosis[r].size(); ++i) {
      const double center = (i + 0.5) * bw;
      if (center < options.min_center_hz) continue;
      if (!found || out.kurtosis[r][i] > out.best.kurtosis * (1 + 1e-5)) {
        found = true;
        out.best.level = out.levels[r];
        out.best.index = static_cast<int>(i);
        out.best.center_hz = center;
        out.best.bandwidth_hz = bw;
        out.best.kurtosis = out.kurtosis[r][i];
      }
    }
  }
  return out;
}

Kurtogram FastKurtogram(std::span<const double> x, double fs_hz, const KurtogramOptions& options) {
  const EnvelopeAnalyzer analyzer(x, fs_hz);
  return FastKurtogram(analyzer, options);
}

}  // namespace spallkit::dsp
