#include "dsp/kurtogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numbers>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/multiversion.h"
#include "dsp/statistics.h"

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

// sum |v_j|^2 over count values, in double with four-wide vector accumulators.
double Energy(const std::complex<float>* v, int count) {
  typedef float F8 __attribute__((vector_size(32)));
  typedef double D4 __attribute__((vector_size(32)));
  const float* f = reinterpret_cast<const float*>(v);
  const int floats = 2 * count;
  D4 acc = {0, 0, 0, 0};
  int j = 0;
  for (; j + 8 <= floats; j += 8) {
    F8 a;
    std::memcpy(&a, f + j, sizeof(a));
    const F8 sq = a * a;
    acc += __builtin_convertvector(__builtin_shufflevector(sq, sq, 0, 1, 2, 3), D4) +
           __builtin_convertvector(__builtin_shufflevector(sq, sq, 4, 5, 6, 7), D4);
  }
  double total = (acc[0] + acc[1]) + (acc[2] + acc[3]);
  for (; j < floats; ++j) total += static_cast<double>(f[j]) * f[j];
  return total;
}

// One chain of rows in which each row's nodes are the halves of the previous (shallower) row's:
// the binary rows L, L-1, ..., 0 and the ternary rows L-0.4, ..., 1.6. Listed deepest first.
struct ChainRow {
  int row;    // index in the kurtogram's rows
  int nodes;  // nodes in the row
  int m;      // envelope samples per node; m of a parent = 2 m of its children
  bool keep;  // store the row's squared envelopes
};

// |c_j|^2 of a whole row (nodes * m samples) into out, in single precision.
void StoreSquaredEnvelopes(const std::complex<float>* env, size_t count, std::vector<float>* out) {
  out->resize(count);
  const float* c = reinterpret_cast<const float*>(env);
  float* o = out->data();
  for (size_t j = 0; j < count; ++j) o[j] = c[2 * j] * c[2 * j] + c[2 * j + 1] * c[2 * j + 1];
}

// e^{2 pi i j / m}, j < m, as a coarse step times a fine step, e^{2 pi i c F / m} e^{2 pi i f / m}
// with j = c F + f, F = floor(sqrt(m)): ~2 sqrt(m) sin/cos, and tables small enough to stay in
// cache (PlaceBins forms the products as it goes rather than writing and reading back a full table
// of m roots per row, which leaves the cache on the large rows). Error ~1e-7, the level of the
// single-precision transforms the roots feed.
struct UnitRoots {
  int m = 0, fine = 1;
  std::vector<float> fr, fi, cr, ci;  // fine steps f < F, coarse steps c < ceil(m / F)

  void Make(int size) {
    m = size;
    fine = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(m))));
    const int coarse = (m + fine - 1) / fine;
    fr.resize(fine);
    fi.resize(fine);
    for (int i = 0; i < fine; ++i) {
      fr[i] = static_cast<float>(std::cos(2 * std::numbers::pi * i / m));
      fi[i] = static_cast<float>(std::sin(2 * std::numbers::pi * i / m));
    }
    cr.resize(coarse);
    ci.resize(coarse);
    for (int c = 0; c < coarse; ++c) {
      const double angle = 2 * std::numbers::pi * static_cast<double>(c) * fine / m;
      cr[c] = static_cast<float>(std::cos(angle));
      ci[c] = static_cast<float>(std::sin(angle));
    }
  }
};

// Per-thread buffers, kept between calls and grown on demand: a 10 s record at 48 kHz needs
// ~20 MB of them, and fresh allocations of that size cost page faults on every call (10 % of the
// run time).
struct ChainBuffers {
  size_t row_size = 0, node_size = 0;
  FftwArray<std::complex<float>> child, parent;  // all envelopes of a row, node after node
  FftwArray<std::complex<float>> in, odd;        // one node's transform input and output
  UnitRoots row_roots;                           // the current row's e^{2 pi i j / m_p}
  std::unique_ptr<double[]> power;
};

ChainBuffers& ThreadBuffers(size_t row_size, size_t node_size) {
  thread_local ChainBuffers b;
  if (b.row_size < row_size) {
    b.child = AllocateComplexF(row_size);
    b.parent = AllocateComplexF(row_size);
    b.row_size = row_size;
  }
  if (b.node_size < node_size) {
    b.in = AllocateComplexF(node_size);
    b.odd = AllocateComplexF(node_size);
    b.power = std::make_unique<double[]>(node_size);
    b.node_size = node_size;
  }
  return b;
}

// max(0, <|c|^4>/<|c|^2>^2 - 2) over m envelope samples.
double EnvelopeKurtosis(const std::complex<float>* envelope, int m, double* power) {
  const float* c = reinterpret_cast<const float*>(envelope);
  for (int j = 0; j < m; ++j) {
    const double re = c[2 * j], im = c[2 * j + 1];
    power[j] = re * re + im * im;
  }
  double sum2 = 0, sum4 = 0;
  SumAndSumOfSquares(power, m, &sum2, &sum4);
  return sum2 > 0 ? std::max(0.0, m * sum4 / (sum2 * sum2) - 2.0) : 0.0;
}

// out[k mod m_out] = in[k - lo] * e^{2 pi i k / roots.m} for k in [lo, hi) (roots null: no
// factor), in runs where no index wraps and the coarse root is fixed, so the inner loops are
// contiguous. The complex products are written out: std::complex's operator* checks for NaN/inf
// and does not vectorise.
void PlaceBins(const std::complex<float>* in,
               int lo,
               int hi,
               int m_out,
               const UnitRoots* roots,
               std::complex<float>* out) {
  int k = lo;
  while (k < hi) {
    const int p = k % m_out;
    int run = std::min(hi - k, m_out - p);
    const float* v = reinterpret_cast<const float*>(in + (k - lo));
    float* o = reinterpret_cast<float*>(out + p);
    if (roots) {
      const int q = k % roots->m;
      const int c = q / roots->fine, f0 = q % roots->fine;
      run = std::min({run, roots->m - q, roots->fine - f0});
      const float cr = roots->cr[c], ci = roots->ci[c];
      const float* fr = roots->fr.data() + f0;
      const float* fi = roots->fi.data() + f0;
      for (int j = 0; j < run; ++j) {
        const float tr = cr * fr[j] - ci * fi[j], ti = cr * fi[j] + ci * fr[j];
        o[2 * j] = v[2 * j] * tr - v[2 * j + 1] * ti;
        o[2 * j + 1] = v[2 * j] * ti + v[2 * j + 1] * tr;
      }
    } else {
      std::memcpy(o, v, sizeof(float) * 2 * run);
    }
    k += run;
  }
}

// Zeroes the positions of out[0, m) that PlaceBins(lo, hi, m, ...) does not write (bins sit at
// k mod m, so they cover a circular run of hi - lo positions from lo mod m): a parent's bins
// fill about all of its half-size grid, so clearing the whole buffer first would be mostly wasted.
void ZeroOutsideBins(int lo, int hi, int m, std::complex<float>* out) {
  const int count = hi - lo;
  if (count >= m) return;
  const int start = (lo + count) % m;  // first position after the run
  const int zeros = m - count;
  const int first = std::min(zeros, m - start);
  std::fill(out + start, out + start + first, std::complex<float>(0.0f));
  std::fill(out, out + (zeros - first), std::complex<float>(0.0f));
}

// Kurtosis of every node of one chain, written to result[row].
//
// Every node's envelope is sampled on its row's grid of m points over the record, with each bin
// k placed at position k mod m (not shifted to DC: a frequency shift only rotates the phase of c,
// and this placement makes the rows add up). m >= 2B (B bins in a node) samples c twice per
// 1/(bandwidth), enough for |c|^4 to be alias-free, so the moments are exact.
// The deepest row is computed directly, one inverse FFT of size m per node. Each shallower row
// reuses its children: a parent has m_p = 2 m_c samples, and
//   even samples  c_p(2s)   = sum_k Y_k e^{2 pi i k s / m_c} = c_lo(s) + c_hi(s),
//   odd samples   c_p(2s+1) = IFFT_{m_c}(Y_k e^{2 pi i k / m_p})(s),
// so a parent costs one transform of half its size plus an addition: every row but the deepest
// costs half of a direct computation, for the same exact samples.
// Multi-versioned (core/multiversion.h): the shuffles and moment sums of the loops below are
// written for 256-bit vectors, which the baseline instruction set splits and spills.
SPALLKIT_MULTIVERSION
void ProcessChain(const std::complex<float>* xf,
                  int n,
                  double empty_energy,
                  const std::vector<ChainRow>& chain,
                  std::vector<std::vector<double>>* result,
                  std::vector<std::vector<float>>* squared_envelopes) {
  const int bins = n / 2 + 1;
  auto bounds = [&](int i, int nodes, int* lo, int* hi) {
    *lo = FirstBin(i, nodes, n);
    *hi = (i + 1 == nodes) ? bins : FirstBin(i + 1, nodes, n);
  };
  const ChainRow& deepest = chain.front();
  const size_t row_size = static_cast<size_t>(deepest.nodes) * deepest.m;
  const int m_top = chain.back().m;
  ChainBuffers& b = ThreadBuffers(row_size, m_top);
  std::complex<float>* child = b.child.get();
  std::complex<float>* parent = b.parent.get();
  std::complex<float>* in = b.in.get();
  // Node energies (Parseval), deepest row from the bins, each parent the sum of its children.
  std::vector<double> energy(deepest.nodes), parent_energy(deepest.nodes);

  {  // Deepest row, directly.
    const int m = deepest.m;
    ComplexFftF fft(m, +1);
    std::vector<double>& row = (*result)[deepest.row];
    row.assign(deepest.nodes, 0.0);
    for (int i = 0; i < deepest.nodes; ++i) {
      int lo, hi;
      bounds(i, deepest.nodes, &lo, &hi);
      std::complex<float>* env = child + static_cast<size_t>(i) * m;
      energy[i] = Energy(xf + lo, hi - lo);
      if (!(energy[i] > empty_energy)) {
        std::fill(env, env + m, std::complex<float>(0.0f));
        continue;
      }
      ZeroOutsideBins(lo, hi, m, in);
      PlaceBins(xf + lo, lo, hi, m, nullptr, in);
      fft.Execute(in, env);
      row[i] = EnvelopeKurtosis(env, m, b.power.get());
    }
    if (deepest.keep) StoreSquaredEnvelopes(child, row_size, &(*squared_envelopes)[deepest.row]);
  }
  if (chain.size() == 1) return;

  for (size_t level = 1; level < chain.size(); ++level) {
    const ChainRow& up = chain[level];
    const int mp = up.m, mc = up.m / 2;
    ComplexFftF fft(mc, +1);
    b.row_roots.Make(mp);  // e^{2 pi i j / m_p}
    std::vector<double>& row = (*result)[up.row];
    row.assign(up.nodes, 0.0);
    std::complex<float>* odd = in + mc;  // second half of the node buffer (size m_top >= 2 mc)
    for (int i = 0; i < up.nodes; ++i) {
      int lo, hi;
      bounds(i, up.nodes, &lo, &hi);
      std::complex<float>* env = parent + static_cast<size_t>(i) * mp;
      parent_energy[i] = energy[2 * i] + energy[2 * i + 1];
      if (!(parent_energy[i] > empty_energy)) {
        std::fill(env, env + mp, std::complex<float>(0.0f));
        continue;
      }
      SPALLKIT_CHECK(hi - lo <= mc, "kurtogram node of " << hi - lo << " bins, m " << mc);
      ZeroOutsideBins(lo, hi, mc, in);
      PlaceBins(xf + lo, lo, hi, mc, &b.row_roots, in);
      fft.Execute(in, odd);
      // Even samples: the sum of the children; interleaved with the odd ones.
      const float* lower = reinterpret_cast<const float*>(child + static_cast<size_t>(2 * i) * mc);
      const float* upper =
          reinterpret_cast<const float*>(child + static_cast<size_t>(2 * i + 1) * mc);
      const float* o = reinterpret_cast<const float*>(odd);
      float* e = reinterpret_cast<float*>(env);
      // Four samples of each at a time with vector shuffles (mc is a multiple of 64, see
      // FftFastSize), accumulating the moments on the way (|c|^2 in float, sums in double).
      typedef float F8 __attribute__((vector_size(32)));
      // The eight |c|^2 of a step are widened to doubles as one vector (a split into halves
      // made GCC spill them through the stack); lanes 0-3 and 4-7 are summed as two accumulators.
      typedef double D8 __attribute__((vector_size(64)));
      D8 acc2 = {0, 0, 0, 0, 0, 0, 0, 0}, acc4 = acc2;
      for (int s = 0; s < mc; s += 4) {
        F8 l, u, d;
        std::memcpy(&l, lower + 2 * s, sizeof(l));
        std::memcpy(&u, upper + 2 * s, sizeof(u));
        std::memcpy(&d, o + 2 * s, sizeof(d));
        const F8 sum = l + u;  // even samples 2s, 2s+2, 2s+4, 2s+6
        const F8 first = __builtin_shufflevector(sum, d, 0, 1, 8, 9, 2, 3, 10, 11);
        const F8 second = __builtin_shufflevector(sum, d, 4, 5, 12, 13, 6, 7, 14, 15);
        std::memcpy(e + 4 * s, &first, sizeof(first));
        std::memcpy(e + 4 * s + 8, &second, sizeof(second));
        const F8 a = sum * sum, c = d * d;
        const F8 power = __builtin_shufflevector(a, c, 0, 2, 4, 6, 8, 10, 12, 14) +
                         __builtin_shufflevector(a, c, 1, 3, 5, 7, 9, 11, 13, 15);
        const D8 wide = __builtin_convertvector(power, D8);
        acc2 += wide;
        acc4 += wide * wide;
      }
      const double sum2 =
          ((acc2[0] + acc2[4]) + (acc2[1] + acc2[5])) + ((acc2[2] + acc2[6]) + (acc2[3] + acc2[7]));
      const double sum4 =
          ((acc4[0] + acc4[4]) + (acc4[1] + acc4[5])) + ((acc4[2] + acc4[6]) + (acc4[3] + acc4[7]));
      row[i] = sum2 > 0 ? std::max(0.0, mp * sum4 / (sum2 * sum2) - 2.0) : 0.0;
    }
    if (up.keep)
      StoreSquaredEnvelopes(
          parent, static_cast<size_t>(up.nodes) * mp, &(*squared_envelopes)[up.row]);
    std::swap(child, parent);
    std::swap(energy, parent_energy);
  }
}

// out[k] = float(x[k] * scale), a loop that vectorises (multi-versioned: core/multiversion.h).
SPALLKIT_MULTIVERSION
void ScaleToFloat(const std::complex<double>* x,
                  int count,
                  double scale,
                  std::complex<float>* out) {
  const double* in = reinterpret_cast<const double*>(x);
  float* o = reinterpret_cast<float*>(out);
  for (int j = 0; j < 2 * count; ++j) o[j] = static_cast<float>(in[j] * scale);
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

void Kurtogram::NodeBins(int row, int index, int* lo, int* hi) const {
  const int nodes = static_cast<int>(kurtosis.at(row).size());
  *lo = FirstBin(index, nodes, samples);
  *hi = (index + 1 == nodes) ? samples / 2 + 1 : FirstBin(index + 1, nodes, samples);
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

  // Node energies by Parseval (analytic weights). A node holding less than kEmptyNode of the
  // record's energy carries only rounding residue, whose kurtosis is meaningless: reported as 0.
  // sum |X_k|^2, then the edge bins' analytic weights (1/4 of their energy) as corrections.
  double total_energy =
      SumOfSquares({reinterpret_cast<const double*>(x.data()), 2 * static_cast<size_t>(bins)});
  total_energy -= 0.75 * std::norm(x[0]);
  if (2 * (bins - 1) == n) total_energy -= 0.75 * std::norm(x[bins - 1]);
  const double scale = total_energy > 0 ? 1.0 / std::sqrt(total_energy / bins) : 1.0;
  constexpr double kEmptyNode = 1e-20;
  // The spectrum in single precision from here on, scaled to unit RMS bin (so the float range is
  // never an issue) and with the analytic-signal weights (1, and 1/2 at DC and Nyquist). Each row
  // streams it once; half the bytes of the double spectrum.
  // Per thread and kept between calls: a fresh 2 MB vector costs a zero fill and page faults.
  thread_local std::vector<std::complex<float>> xf;
  xf.resize(bins);
  ScaleToFloat(x.data(), bins, scale, xf.data());
  xf[0] *= 0.5f;
  if (2 * (bins - 1) == n) xf[bins - 1] *= 0.5f;
  const std::complex<float>* spectrum_f = xf.data();  // this thread's: the chains' threads read it
  const double empty_energy = kEmptyNode * total_energy * scale * scale;

  // The two chains: binary rows (L, ..., 1, 0) and ternary rows (L-0.4, ..., 1.6), deepest
  // first. The deepest row gets m >= 2B (B = most bins in a node; M >= 2B - 1 makes the moments
  // exact, and 2B keeps it so for the parents, whose B is at most twice their children's);
  // each parent doubles it. (Critical sampling, m >= B, would halve the cost but misses envelope
  // peaks: on impulsive test signals its kurtosis is off by 27 % in nodes of 1000 bins.)
  std::vector<std::vector<ChainRow>> chains(2);
  for (int r = static_cast<int>(rows.size()) - 1; r >= 0; --r) {
    const bool ternary = rows[r].level != std::floor(rows[r].level);
    const double width = 0.5 * fs / rows[r].nodes;
    const bool keep = width >= options.keep_envelopes_min_hz * (1 - 1e-12) &&
                      width <= options.keep_envelopes_max_hz * (1 + 1e-12);
    chains[ternary ? 1 : 0].push_back({r, rows[r].nodes, 0, keep});
  }
  if (chains[1].empty()) chains.pop_back();
  for (auto& chain : chains) {
    const int nodes = chain.front().nodes;
    int widest = 0;
    for (int i = 0; i < nodes; ++i) {
      const int lo = FirstBin(i, nodes, n);
      const int hi = (i + 1 == nodes) ? bins : FirstBin(i + 1, nodes, n);
      widest = std::max(widest, hi - lo);
    }
    int m = FftFastSize(2 * widest);
    for (auto& row : chain) {
      row.m = m;
      m *= 2;
    }
  }

  // The chains are independent: one thread each at most. The arithmetic is the same whatever
  // the thread count, so the results are identical.
  std::vector<std::vector<double>> result(rows.size());
  if (options.envelope_buffers) out.squared_envelopes = std::move(*options.envelope_buffers);
  out.squared_envelopes.resize(rows.size());
  // Rows not kept are emptied; kept rows keep their contents until overwritten, so that reused
  // buffers of the right size are not zero-filled first (resize only fills what it adds).
  std::vector<char> kept(rows.size(), 0);
  for (const auto& chain : chains)
    for (const auto& row : chain) kept[row.row] = row.keep;
  for (size_t r = 0; r < rows.size(); ++r)
    if (!kept[r]) out.squared_envelopes[r].clear();
  out.envelope_sizes.assign(rows.size(), 0);
  for (const auto& chain : chains)
    for (const auto& row : chain) out.envelope_sizes[row.row] = row.m;
  // xf = X * w * scale with the analytic weights w, and c_true = (2 / n) IFFT(X w): |c_true|^2 =
  // (2 / (n scale))^2 |c|^2.
  const double gain = 2.0 / (static_cast<double>(n) * scale);
  out.envelope_gain2 = gain * gain;
  out.samples = n;
  const int chain_count = static_cast<int>(chains.size());
#ifdef _OPENMP
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel for num_threads(std::min(threads, chain_count)) schedule(static, 1)
#endif
  for (int c = 0; c < chain_count; ++c) {
    ProcessChain(spectrum_f, n, empty_energy, chains[c], &result, &out.squared_envelopes);
  }
  for (const Row& row : rows) out.levels.push_back(row.level);
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
