#include "dsp/kurtogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

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

int MaxLevelFor(int n) {
  return static_cast<int>(std::floor(std::log2(static_cast<double>(n)))) - 4;
}

}  // namespace

double Kurtogram::BandwidthHz(int row) const {
  const double level = levels.at(row);
  const int whole = static_cast<int>(std::floor(level + 1e-9));
  const bool ternary = level - whole > 1e-6;
  const double nodes = ternary ? 3.0 * std::ldexp(1.0, whole) : std::ldexp(1.0, whole);
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
    // M >= 2B - 1: |c|^4 spans +-2(B-1) bins, so the decimated moments are exact; M >= B:
    // critically sampled c, half the cost, moments estimated from every other such sample.
    row_m[r] = FftFriendlySize(options.exact_moments ? std::max(2 * widest - 1, 1) : widest);
    buffer_size = std::max(buffer_size, static_cast<size_t>(row_m[r]) * rows[r].nodes);
  }
  std::vector<std::complex<double>> buffer(buffer_size);

  for (size_t r = 0; r < rows.size(); ++r) {
    const int nodes = rows[r].nodes;
    const int m = row_m[r];
    // Ideal one-sided band-pass of each node, shifted to DC (weights as for an analytic signal;
    // the overall scale cancels in the kurtosis).
    for (int i = 0; i < nodes; ++i) {
      const int lo = FirstBin(i, nodes, n);
      const int hi = (i + 1 == nodes) ? bins : FirstBin(i + 1, nodes, n);
      std::complex<double>* dst = buffer.data() + static_cast<size_t>(i) * m;
      for (int k = lo; k < hi; ++k) {
        const bool edge = (k == 0) || (2 * k == n);
        dst[k - lo] = edge ? 0.5 * x[k] : x[k];
      }
      std::fill(dst + (hi - lo), dst + m, std::complex<double>(0.0));
    }
    ComplexFft fft(m, +1, nodes);
    fft.Execute(buffer.data(), buffer.data());

    std::vector<double> row(nodes);
    for (int i = 0; i < nodes; ++i) {
      const double* c = reinterpret_cast<const double*>(buffer.data() + static_cast<size_t>(i) * m);
      // Four partial sums let the compiler vectorise the reduction.
      double s2[4] = {0, 0, 0, 0}, s4[4] = {0, 0, 0, 0};
      int j = 0;
      for (; j + 4 <= m; j += 4) {
        for (int u = 0; u < 4; ++u) {
          const double p =
              c[2 * (j + u)] * c[2 * (j + u)] + c[2 * (j + u) + 1] * c[2 * (j + u) + 1];
          s2[u] += p;
          s4[u] += p * p;
        }
      }
      for (; j < m; ++j) {
        const double p = c[2 * j] * c[2 * j] + c[2 * j + 1] * c[2 * j + 1];
        s2[0] += p;
        s4[0] += p * p;
      }
      const double sum2 = (s2[0] + s2[1]) + (s2[2] + s2[3]);
      const double sum4 = (s4[0] + s4[1]) + (s4[2] + s4[3]);
      const double k = sum2 > 0 ? m * sum4 / (sum2 * sum2) - 2.0 : 0.0;
      row[i] = std::max(0.0, k);
    }
    out.levels.push_back(rows[r].level);
    out.kurtosis.push_back(std::move(row));
  }

  // Best node: highest kurtosis among nodes centred at or above min_center_hz; on a tie the
  // coarser level (wider band, listed first) wins.
  bool found = false;
  for (size_t r = 0; r < out.levels.size(); ++r) {
    const double bw = out.BandwidthHz(static_cast<int>(r));
    for (size_t i = 0; i < out.kurtosis[r].size(); ++i) {
      const double center = (i + 0.5) * bw;
      if (center < options.min_center_hz) continue;
      if (!found || out.kurtosis[r][i] > out.best.kurtosis) {
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
