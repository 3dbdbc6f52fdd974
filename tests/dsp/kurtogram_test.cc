#include "dsp/kurtogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "dsp/fft.h"
#include "tests/dsp/spectral_test_signals.h"

namespace {

using namespace spallkit::dsp;
using spallkit::InputError;
using cd = std::complex<double>;

// Carrier fc with envelope exp(beta cos(2 pi fm t)): |c|^2 = exp(2 beta cos), so
// <|c|^4>/<|c|^2>^2 - 2 = I0(4 beta) / I0(2 beta)^2 - 2 exactly (modified Bessel functions).
std::vector<double> BesselEnvelopeSignal(double beta, double fm, double fc, double fs, int n) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    const double t = i / fs;
    x[i] = std::exp(beta * std::cos(2 * std::numbers::pi * fm * t)) *
           std::cos(2 * std::numbers::pi * fc * t);
  }
  return x;
}

TEST(FastKurtogram, RowsFollowTheOneThirdBinaryTree) {
  const auto x = test_signals::MakeGaussianNoise(1 << 14, 1.0, 2);
  const auto k = FastKurtogram(x, 1000, {.max_level = 4});
  const std::vector<double> levels{0, 1, 1.585, 2, 2.585, 3, 3.585, 4};
  const std::vector<size_t> nodes{1, 2, 3, 4, 6, 8, 12, 16};
  ASSERT_EQ(k.levels.size(), levels.size());
  ASSERT_EQ(k.kurtosis.size(), levels.size());
  EXPECT_EQ(k.max_level, 4);
  EXPECT_DOUBLE_EQ(k.sample_rate_hz, 1000);
  size_t total = 0;
  for (size_t r = 0; r < levels.size(); ++r) {
    EXPECT_NEAR(k.levels[r], levels[r], 1e-3);
    EXPECT_EQ(k.kurtosis[r].size(), nodes[r]);
    EXPECT_NEAR(k.BandwidthHz(static_cast<int>(r)), 500.0 / nodes[r], 1e-9);
    total += nodes[r];
  }
  const auto all = k.Nodes();
  ASSERT_EQ(all.size(), total);
  EXPECT_NEAR(all.back().center_hz + all.back().bandwidth_hz / 2, 500.0, 1e-9);
  EXPECT_NEAR(all[3].band().low_hz, 0.0, 1e-12);  // first node of level 1.585
  EXPECT_NEAR(all[3].band().high_hz, 500.0 / 3, 1e-9);
  // Automatic depth: floor(log2 N) - 7 = 7 here.
  EXPECT_EQ(FastKurtogram(x, 1000).max_level, 7);
}

// The node kurtosis is the envelope kurtosis: for an exp(beta cos) envelope it equals the Bessel
// ratio, in every node that holds the whole modulated carrier.
TEST(FastKurtogram, NodeKurtosisMatchesBesselEnvelopeValue) {
  const double fs = 8000, beta = 1.5;
  const auto x = BesselEnvelopeSignal(beta, 20, 1500, fs, 8000);
  const double expected =
      std::cyl_bessel_i(0.0, 4 * beta) / std::pow(std::cyl_bessel_i(0.0, 2 * beta), 2) - 2;
  ASSERT_NEAR(expected, 0.8224, 1e-3);
  {
    const auto k = FastKurtogram(x, fs, {.max_level = 3});
    int checked = 0;
    for (const auto& node : k.Nodes()) {
      const Band b = node.band();
      if (b.low_hz <= 1340 && b.high_hz >= 1660) {  // fc +- 8 fm: all but < 3e-6 of the content
        EXPECT_NEAR(node.kurtosis, expected, 1e-6) << node.level << " " << node.index;
        ++checked;
      } else if (b.high_hz <= 1000 || b.low_hz >= 2000) {
        EXPECT_EQ(node.kurtosis, 0.0) << "empty node " << node.level << " " << node.index;
      }
    }
    EXPECT_GE(checked, 5);
    EXPECT_NEAR(k.best.kurtosis, expected, 1e-6);
    EXPECT_EQ(k.best.level, 0.0);  // ties go to the widest band
  }
}

// The kurtosis of each node equals (to single-precision rounding) the one from the full-rate
// complex envelope (ideal band on the N-point grid, N-point inverse FFT), from the definition.
TEST(FastKurtogram, NodeKurtosisEqualsFullRateDefinition) {
  test_signals::BearingLikeSignal s;
  s.fs_hz = 16000;
  s.seconds = 1;
  s.resonance_hz = 5000;
  s.noise_std = 0.4;
  const auto record = test_signals::MakeBearingLikeSignal(s);
  for (const size_t used : {record.size(), record.size() - 1}) {  // even and odd lengths
    const std::span<const double> x(record.data(), used);
    const int n = static_cast<int>(x.size());
    RealFft real(n);
    std::vector<cd> spec(real.bins());
    real.Forward(x.data(), spec.data());
    const auto exact = FastKurtogram(x, s.fs_hz, {.max_level = 5});
    ComplexFft inverse(n, +1);
    for (size_t r = 1; r < exact.levels.size(); ++r) {  // level 0 would need 2B-1 > N samples
      const int nodes = static_cast<int>(exact.kurtosis[r].size());
      for (int i = 0; i < nodes; ++i) {
        const int lo = static_cast<int>((int64_t(i) * n + 2 * nodes - 1) / (2 * nodes));
        const int hi = i + 1 == nodes
                           ? real.bins()
                           : static_cast<int>((int64_t(i + 1) * n + 2 * nodes - 1) / (2 * nodes));
        std::vector<cd> c(n, 0.0);
        for (int k = std::max(lo, 1); k < hi; ++k) c[k] = (2 * k == n ? 1.0 : 2.0) * spec[k];
        inverse.Execute(c.data(), c.data());
        double m2 = 0, m4 = 0;
        for (const cd& v : c) {
          m2 += std::norm(v) / n;
          m4 += std::norm(v) * std::norm(v) / n;
        }
        const double ref = std::max(0.0, m4 / (m2 * m2) - 2);
        ASSERT_NEAR(exact.kurtosis[r][i], ref, 1e-6 * std::max(1.0, ref))
            << n << " " << r << " " << i;
      }
    }
  }
}

// Impulses ringing a 9 kHz resonance, buried in Gaussian noise with shaft lines: the best node
// contains the resonance and has a clearly non-Gaussian envelope.
TEST(FastKurtogram, PicksTheBandOfAnImpulsiveResonance) {
  test_signals::BearingLikeSignal s;
  s.fs_hz = 48000;
  s.seconds = 2;
  s.resonance_hz = 9000;
  s.noise_std = 0.4;
  const auto x = test_signals::MakeBearingLikeSignal(s);
  const auto k = FastKurtogram(x, s.fs_hz);
  EXPECT_EQ(k.max_level, 9);
  const Band best = k.best.band();
  EXPECT_LE(best.low_hz, 9000);
  EXPECT_GE(best.high_hz, 9000);
  EXPECT_GT(k.best.kurtosis, 1.0);
  EXPECT_GE(k.best.bandwidth_hz, 500);  // not a sliver: the resonance is ~540 Hz wide
  // The whole-band kurtosis is far lower: the noise elsewhere dilutes the impulses.
  EXPECT_LT(k.kurtosis[0][0], 0.5 * k.best.kurtosis);
  // Steering away: nodes centred below 15 kHz are never chosen, whatever their kurtosis; above
  // it there is only noise, whose narrow nodes reach a few tenths by estimation error alone.
  const auto high = FastKurtogram(x, s.fs_hz, {.min_center_hz = 15000});
  EXPECT_GE(high.best.center_hz, 15000);
  EXPECT_LT(high.best.kurtosis, 0.5 * k.best.kurtosis);
  // Sharing the analyser's spectrum, or running on two threads, gives the identical result.
  EnvelopeAnalyzer analyzer(x, s.fs_hz);
  const auto shared = FastKurtogram(analyzer);
  EXPECT_EQ(shared.kurtosis, k.kurtosis);
  EXPECT_EQ(shared.best.center_hz, k.best.center_hz);
  const auto threaded = FastKurtogram(analyzer, {.threads = 2});
  EXPECT_EQ(threaded.kurtosis, k.kurtosis);
}

// Gaussian noise: every node's kurtosis is within sampling error of 0 (std ~ 2/sqrt(M)).
TEST(FastKurtogram, GaussianNoiseHasSmallKurtosisEverywhere) {
  const auto x = test_signals::MakeGaussianNoise(1 << 16, 2.0, 17);
  const auto k = FastKurtogram(x, 10000, {.max_level = 5});
  double mean = 0;
  int count = 0;
  for (size_t r = 0; r < k.levels.size(); ++r) {
    const double samples = double(1 << 15) / k.kurtosis[r].size();
    for (double v : k.kurtosis[r]) {
      EXPECT_LT(v, 5 * 2 / std::sqrt(samples)) << "level " << k.levels[r];
      mean += v;
      ++count;
    }
  }
  EXPECT_LT(mean / count, 0.05);
  EXPECT_LT(k.best.kurtosis, 0.2);
}

// A tone (integer number of cycles) has a constant envelope, K = -1, clipped to 0; the nodes
// without it hold no energy and report 0 too.
TEST(FastKurtogram, PureToneIsClippedToZero) {
  std::vector<double> x(4096);
  for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * std::numbers::pi * 0.125 * i);
  const auto k = FastKurtogram(x, 1.0, {.max_level = 3});
  for (const auto& row : k.kurtosis) {
    for (double v : row) EXPECT_EQ(v, 0.0);
  }
}

TEST(FastKurtogram, BadInputIsAnInputError) {
  const auto x = test_signals::MakeGaussianNoise(4096, 1.0, 3);
  EXPECT_THROW(FastKurtogram(std::span(x).first(32), 1000), InputError);
  EXPECT_THROW(FastKurtogram(x, 0), InputError);
  EXPECT_THROW(FastKurtogram(x, 1000, {.max_level = -1}), InputError);
  EXPECT_THROW(FastKurtogram(x, 1000, {.max_level = 9}), InputError);  // log2(4096) - 4 = 8
  EXPECT_NO_THROW(FastKurtogram(x, 1000, {.max_level = 8}));
  EXPECT_THROW(FastKurtogram(x, 1000, {.min_center_hz = 500}), InputError);
}

}  // namespace
