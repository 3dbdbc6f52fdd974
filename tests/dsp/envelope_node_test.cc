// The SES of a kurtogram node taken from the node's own squared envelope (KurtogramOptions::
// keep_envelopes_*, EnvelopeAnalyzer::SesPowerFromSquaredEnvelope: what the diagnosis does for
// every candidate band) against the double-precision SES of exactly the node's bins
// (EnvelopeAnalyzer::Compute): same bins, level^2 within a tolerance set by the noise floor, up to
// alpha = the node's width, on binary and ternary rows, at any record scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "dsp/envelope.h"
#include "dsp/kurtogram.h"
#include "tests/dsp/spectral_test_signals.h"

namespace spallkit::dsp {
namespace {

double Median(std::vector<double> v) {
  v.erase(v.begin());
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

void ExpectNodeSesMatches(double scale, double max_alpha_factor) {
  test_signals::BearingLikeSignal s;
  s.seconds = 2.0;
  std::vector<double> x = test_signals::MakeBearingLikeSignal(s);
  for (double& v : x) v *= scale;
  const double fs = 48000;
  EnvelopeAnalyzer analyzer(x, fs);
  KurtogramOptions kopt;
  kopt.max_level = 5;
  kopt.keep_envelopes_min_hz = 1000;  // rows 4.6, 4, 3.6, 3, 2.6: 1000 .. 4000 Hz
  kopt.keep_envelopes_max_hz = 4000;
  const Kurtogram k = FastKurtogram(analyzer, kopt);
  const double df = analyzer.resolution_hz();
  int rows_checked = 0;
  double best_peak = 0.0;
  for (size_t row = 0; row < k.levels.size(); ++row) {
    const double width = k.BandwidthHz(static_cast<int>(row));
    if (width < 1000 || width > 4000) {
      EXPECT_TRUE(k.squared_envelopes[row].empty()) << "row " << k.levels[row];
      continue;
    }
    const int m = k.envelope_sizes[row];
    const int nodes = static_cast<int>(k.kurtosis[row].size());
    ASSERT_EQ(k.squared_envelopes[row].size(), static_cast<size_t>(nodes) * m);
    ++rows_checked;
    for (int i = 1; i < nodes; ++i) {
      int lo = 0, hi = 0;
      k.NodeBins(static_cast<int>(row), i, &lo, &hi);
      ASSERT_EQ(lo, static_cast<int>(std::ceil(i * width / df - 1e-9)));
      const double max_alpha = max_alpha_factor * width;
      // Exactly the node's bins [lo, hi) (Compute takes both edges of the Hz band).
      const EnvelopeSpectrum ses =
          analyzer.Compute({lo * df, (hi - 1) * df}, {.max_alpha_hz = max_alpha});
      EnvelopeAnalyzer::SesWorkspace workspace;
      const std::vector<double> fast = analyzer.SesPowerFromSquaredEnvelope(
          std::span<const float>(k.squared_envelopes[row].data() + static_cast<size_t>(i) * m, m),
          k.envelope_gain2,
          max_alpha,
          &workspace);
      ASSERT_EQ(fast.size(), ses.level.size());
      std::vector<double> exact(ses.level.size());
      for (size_t j = 0; j < exact.size(); ++j) exact[j] = ses.level[j] * ses.level[j];
      const double floor = Median(exact);
      ASSERT_GT(floor, 0.0);
      double worst = 0.0, peak = 0.0;
      for (size_t j = 1; j < exact.size(); ++j) {
        worst = std::max(worst, std::abs(fast[j] - exact[j]) / std::max(exact[j], floor));
        peak = std::max(peak, exact[j] / floor);
      }
      EXPECT_LT(worst, 2e-5) << "level " << k.levels[row] << " node " << i << " scale " << scale;
      EXPECT_EQ(fast[0], 0.0);
      best_peak = std::max(best_peak, peak);
    }
  }
  EXPECT_EQ(rows_checked, 5);
  EXPECT_GT(best_peak, 100.0);  // the impulse comb is there in some node, far above the floor
}

TEST(NodeEnvelopeSes, MatchesDoublePrecisionSesOfTheNodesBins) {
  ExpectNodeSesMatches(1.0, 1.0);  // alpha up to the node width: m = 2 alpha bins is allowed
  ExpectNodeSesMatches(1.0, 0.4);
}

TEST(NodeEnvelopeSes, IndependentOfTheRecordScale) {
  ExpectNodeSesMatches(1e-25, 0.5);
  ExpectNodeSesMatches(1e22, 0.5);
}

TEST(NodeEnvelopeSes, RejectsBadInput) {
  std::vector<double> x(4096);
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.3 * i);
  EnvelopeAnalyzer analyzer(x, 1000);
  EnvelopeAnalyzer::SesWorkspace w;
  std::vector<float> se(64, 1.0f);
  EXPECT_THROW(analyzer.SesPowerFromSquaredEnvelope(se, 1.0, 0.0, &w), InputError);
  // 64 samples hold alpha up to 32 bins (df = 1000 / 4096 Hz): 40 bins is too many.
  EXPECT_THROW(analyzer.SesPowerFromSquaredEnvelope(se, 1.0, 40 * 1000.0 / 4096, &w), InputError);
  se.resize(63);
  EXPECT_THROW(analyzer.SesPowerFromSquaredEnvelope(se, 1.0, 1.0, &w), InputError);
}

}  // namespace
}  // namespace spallkit::dsp
