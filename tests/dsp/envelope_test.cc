#include "dsp/envelope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "tests/dsp/spectral_test_signals.h"

namespace {

using namespace spallkit::dsp;
using spallkit::InputError;
using cd = std::complex<double>;

// Amplitude-modulated carrier A (1 + m cos(2 pi fm t)) cos(2 pi fc t), integer cycles in 1 s.
std::vector<double> AmCarrier(double a, double m, double fm, double fc, double fs, int n) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    const double t = i / fs;
    x[i] = a * (1 + m * std::cos(2 * std::numbers::pi * fm * t)) *
           std::cos(2 * std::numbers::pi * fc * t);
  }
  return x;
}

// Full-rate reference: analytic signal of the ideal band on the N-point grid, |.|^2 (or |.|),
// mean removed, N-point FFT, |.|/N. Straight from the definition, no decimation.
std::vector<double> FullRateSes(const std::vector<double>& x, double fs, Band band, bool squared) {
  const int n = static_cast<int>(x.size());
  RealFft real(n);
  std::vector<cd> spec(real.bins());
  real.Forward(x.data(), spec.data());
  std::vector<cd> analytic(n, 0.0);
  const double df = fs / n;
  for (int k = 1; k < real.bins(); ++k) {
    const double f = k * df;
    if (f >= band.low_hz - 1e-9 && f <= band.high_hz + 1e-9) {
      analytic[k] = (2 * k == n ? 1.0 : 2.0) * spec[k] / double(n);
    }
  }
  ComplexFft inverse(n, +1);
  inverse.Execute(analytic.data(), analytic.data());
  std::vector<double> se(n);
  double mean = 0;
  for (int i = 0; i < n; ++i) {
    se[i] = squared ? std::norm(analytic[i]) : std::abs(analytic[i]);
    mean += se[i] / n;
  }
  for (double& v : se) v -= mean;
  std::vector<cd> ses(real.bins());
  real.Forward(se.data(), ses.data());
  std::vector<double> level(real.bins());
  for (int k = 0; k < real.bins(); ++k) level[k] = std::abs(ses[k]) / n;
  return level;
}

double MaxIn(const EnvelopeSpectrum& s, double lo_hz, double hi_hz) {
  double best = 0;
  for (size_t k = 0; k < s.freq_hz.size(); ++k) {
    if (s.freq_hz[k] >= lo_hz && s.freq_hz[k] <= hi_hz) best = std::max(best, s.level[k]);
  }
  return best;
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// AM carrier: SE = A^2 (1 + m^2/2 + 2 m cos(w t) + m^2/2 cos(2 w t)), so with the |FFT|/N
// convention the SES shows m A^2 at fm and m^2 A^2 / 4 at 2 fm, nothing else.
TEST(SquaredEnvelopeSpectrum, AmCarrierGivesTheAnalyticModulationLines) {
  const double fs = 10000, a = 2.0, m = 0.5, fm = 50, fc = 2000;
  const auto x = AmCarrier(a, m, fm, fc, fs, 10000);
  const auto ses = SquaredEnvelopeSpectrum(x, fs, {1800, 2200});
  ASSERT_DOUBLE_EQ(ses.resolution_hz, 1.0);
  ASSERT_EQ(ses.freq_hz.size(), 401u);  // max alpha = band width = 400 Hz
  EXPECT_TRUE(ses.squared);
  for (size_t k = 0; k < ses.level.size(); ++k) {
    double expected = 0;
    if (k == 50) expected = m * a * a;
    if (k == 100) expected = m * m * a * a / 4;
    EXPECT_NEAR(ses.level[k], expected, 1e-9) << "alpha " << ses.freq_hz[k];
  }
}

// The amplitude envelope A (1 + m cos) is a pure cosine: a line A m / 2 at fm and no harmonic,
// where the squared envelope has one at 2 fm.
TEST(SquaredEnvelopeSpectrum, AmplitudeEnvelopeHasNoSecondHarmonic) {
  const double fs = 10000, a = 2.0, m = 0.5, fm = 50, fc = 2000;
  const auto x = AmCarrier(a, m, fm, fc, fs, 10000);
  const auto amp = SquaredEnvelopeSpectrum(x, fs, {1800, 2200}, {.squared = false});
  EXPECT_FALSE(amp.squared);
  EXPECT_NEAR(amp.level[50], a * m / 2, 1e-9);
  EXPECT_NEAR(amp.level[100], 0.0, 1e-9);
  const auto sq = SquaredEnvelopeSpectrum(x, fs, {1800, 2200});
  EXPECT_GT(sq.level[100], 0.2);
}

// Decimation is exact: the SES from the small decimated IFFT equals the full-rate SES computed
// from the definition, bin by bin up to max alpha, for an arbitrary broadband record.
TEST(EnvelopeAnalyzer, DecimatedSesEqualsFullRateDefinition) {
  const double fs = 8000;
  for (const int n : {4000, 3999}) {  // even and odd lengths
    const auto x = test_signals::MakeGaussianNoise(n, 1.0, 5);
    EnvelopeAnalyzer analyzer(x, fs);
    for (const Band band :
         {Band{1000, 1500}, Band{0, 300}, Band{3500, 4000}, Band{1234.5, 2345.6}}) {
      const auto ref = FullRateSes(x, fs, band, true);
      for (double max_alpha : {0.0, 100.0, 900.0}) {
        const auto ses = analyzer.Compute(band, {.max_alpha_hz = max_alpha});
        const double expected_alpha = max_alpha > 0 ? max_alpha : ses.freq_hz.back();
        EXPECT_NEAR(ses.freq_hz.back(), expected_alpha, 2.0);
        double scale = 0;
        for (double v : ref) scale = std::max(scale, v);
        for (size_t k = 1; k < ses.level.size(); ++k) {
          ASSERT_NEAR(ses.level[k], ref[k], 1e-10 * scale)
              << "n " << n << " band " << band.low_hz << "-" << band.high_hz << " alpha "
              << ses.freq_hz[k];
        }
      }
    }
  }
}

// Impulses at a known rate exciting a 4 kHz resonance, in noise: the SES of a band around the
// resonance peaks at the rate and shows its harmonics well above the SES floor.
TEST(SquaredEnvelopeSpectrum, ImpulseTrainPeaksAtItsRateAndHarmonics) {
  test_signals::BearingLikeSignal s;
  s.fs_hz = 20000;
  s.seconds = 2;
  s.fault_hz = 107.3;
  s.jitter = 0.002;
  s.resonance_hz = 4000;
  s.noise_std = 0.5;
  const auto x = test_signals::MakeBearingLikeSignal(s);
  const auto ses = SquaredEnvelopeSpectrum(x, s.fs_hz, {3000, 5000}, {.max_alpha_hz = 1000});
  ASSERT_DOUBLE_EQ(ses.resolution_hz, 0.5);
  // The strongest line from 20 Hz up is the fault rate (shaft lines are outside the band).
  size_t arg = 0;
  for (size_t k = 0; k < ses.level.size(); ++k) {
    if (ses.freq_hz[k] >= 20 && ses.level[k] > ses.level[arg]) arg = k;
  }
  EXPECT_NEAR(ses.freq_hz[arg], s.fault_hz, ses.resolution_hz);
  std::vector<double> floor_levels(ses.level.begin() + 40, ses.level.end());
  const double floor = Median(floor_levels);
  for (int h = 1; h <= 4; ++h) {
    const double line = MaxIn(ses, h * s.fault_hz - 1.0, h * s.fault_hz + 1.0);
    EXPECT_GT(line, 10 * floor) << "harmonic " << h;
  }
  // Half-way between harmonics there is only floor.
  EXPECT_LT(MaxIn(ses, 1.5 * s.fault_hz - 1, 1.5 * s.fault_hz + 1), 5 * floor);
}

TEST(EnvelopeAnalyzer, SquaredEnvelopeOfASineIsItsAmplitudeSquared) {
  const double fs = 1000, a = 3.0;
  std::vector<double> x(2000);
  for (size_t i = 0; i < x.size(); ++i) x[i] = a * std::sin(2 * std::numbers::pi * 123.0 * i / fs);
  EnvelopeAnalyzer analyzer(x, fs);
  double rate = 0;
  const auto se = analyzer.SquaredEnvelope({100, 150}, 0, &rate);
  EXPECT_NEAR(rate, se.size() * fs / x.size(), 1e-9);
  EXPECT_LT(rate, fs);  // decimated
  for (double v : se) EXPECT_NEAR(v, a * a, 1e-9);
  std::vector<cd> c;
  const double rate_c = analyzer.ComplexEnvelope({100, 150}, 0, &c);
  EXPECT_DOUBLE_EQ(rate_c, rate);
  for (const cd& v : c) EXPECT_NEAR(std::abs(v), a, 1e-9);
}

TEST(EnvelopeAnalyzer, ReusedAnalyzerMatchesOneShotCalls) {
  const auto x = test_signals::MakeGaussianNoise(6000, 1.0, 9);
  EnvelopeAnalyzer analyzer(x, 6000);
  EXPECT_EQ(analyzer.size(), 6000);
  EXPECT_DOUBLE_EQ(analyzer.sample_rate_hz(), 6000);
  EXPECT_EQ(analyzer.spectrum().size(), 3001u);
  EXPECT_EQ(analyzer.spectrum()[0], cd(0.0));
  for (int pass = 0; pass < 2; ++pass) {
    for (const Band band : {Band{500, 900}, Band{2000, 2999}}) {
      const auto a = analyzer.Compute(band, {.max_alpha_hz = 200});
      const auto b = SquaredEnvelopeSpectrum(x, 6000, band, {.max_alpha_hz = 200});
      ASSERT_EQ(a.level.size(), b.level.size());
      EXPECT_EQ(a.level.size(), 201u);
      for (size_t k = 0; k < a.level.size(); ++k) EXPECT_DOUBLE_EQ(a.level[k], b.level[k]);
      EXPECT_EQ(a.band.low_hz, band.low_hz);
    }
  }
}

TEST(EnvelopeAnalyzer, BadInputIsAnInputError) {
  const auto x = test_signals::MakeGaussianNoise(1000, 1.0, 1);
  EXPECT_THROW(EnvelopeAnalyzer(std::span(x).first(10), 1000), InputError);
  EXPECT_THROW(EnvelopeAnalyzer(x, 0), InputError);
  EXPECT_THROW(EnvelopeAnalyzer(x, -5), InputError);
  auto bad = x;
  bad[17] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(EnvelopeAnalyzer(bad, 1000), InputError);
  EnvelopeAnalyzer analyzer(x, 1000);
  EXPECT_THROW(analyzer.Compute({100, 600}), InputError);      // above fs/2
  EXPECT_THROW(analyzer.Compute({-10, 100}), InputError);      // below 0
  EXPECT_THROW(analyzer.Compute({300, 200}), InputError);      // inverted
  EXPECT_THROW(analyzer.Compute({200, 200}), InputError);      // empty
  EXPECT_THROW(analyzer.Compute({200.1, 200.5}), InputError);  // between two bins (1 Hz apart)
  EXPECT_THROW(analyzer.Compute({100, 200}, {.max_alpha_hz = -1}), InputError);
  EXPECT_NO_THROW(analyzer.Compute({0, 500}));  // the whole band, edges included
  try {
    analyzer.Compute({100, 600});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fs/2"), std::string::npos) << e.what();
  }
}

}  // namespace
