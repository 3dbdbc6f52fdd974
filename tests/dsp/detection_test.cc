// The detection statistic's null model: exponential SES bins over an estimated floor give the
// stated tail probabilities, so thresholds mean what they say.
#include "dsp/detection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace spallkit::dsp {
namespace {

std::vector<double> NullPower(int n, std::mt19937_64& rng) {
  std::exponential_distribution<double> e(1.0);
  std::vector<double> p(n);
  for (int i = 0; i < n; ++i) p[i] = e(rng) * (1.0 + 0.5 * i / n);  // sloped floor
  return p;
}

TEST(Detection, GammaTailMatchesClosedForms) {
  EXPECT_NEAR(std::exp(LogGammaUpperTail(1, 3.0)), std::exp(-3.0), 1e-12);
  EXPECT_NEAR(std::exp(LogGammaUpperTail(2, 3.0)), 4.0 * std::exp(-3.0), 1e-12);
  const double t = GammaThreshold(5, 1e-6);
  EXPECT_NEAR(LogGammaUpperTail(5, t), std::log(1e-6), 1e-6);
}

// Per-bin p-values under the null are uniform: the fraction below a is a (binomial bounds).
TEST(Detection, BinPValuesAreCalibratedUnderTheNull) {
  std::mt19937_64 rng(3);
  int below1 = 0, below01 = 0, total = 0;
  for (int rep = 0; rep < 20; ++rep) {
    const auto power = NullPower(20000, rng);
    const auto s = NormalizeSpectrum(power, 0.1);
    for (size_t i = 500; i + 500 < power.size(); i += 3) {
      const double p = s.BinTail(s.z[i]);
      below1 += p <= 0.1;
      below01 += p <= 0.01;
      ++total;
    }
  }
  const double f1 = below1 / double(total), f01 = below01 / double(total);
  EXPECT_NEAR(f1, 0.1, 4 * std::sqrt(0.1 * 0.9 / total) + 0.01);
  EXPECT_NEAR(f01, 0.01, 4 * std::sqrt(0.01 * 0.99 / total) + 0.002);
}

// A family comb on null spectra is detected with probability <= alpha (Bonferroni-conservative),
// and a comb of real lines is detected with its fundamental.
TEST(Detection, FamilyFalseAlarmsAndDetection) {
  const auto f = ComputeFrequencies(CatalogBearing("6205"), 30.0);
  const auto fams = MakeFaultFamilies(f, {.harmonics = 5});
  DetectionContext ctx;
  ctx.shaft_hz = 30.0;
  DetectionOptions o;
  o.false_alarm_probability = 0.2;
  std::mt19937_64 rng(5);
  int alarms = 0, significant = 0;
  const int trials = 200;
  for (int t = 0; t < trials; ++t) {
    const auto s = NormalizeSpectrum(NullPower(12000, rng), 0.1, o);
    const auto d = DetectFamily(s, fams[0], ctx, o);
    alarms += d.detected;
    significant += d.p_value <= o.false_alarm_probability;
  }
  EXPECT_LE(significant / double(trials), 0.2 + 3 * std::sqrt(0.2 * 0.8 / trials));
  EXPECT_LE(alarms, significant);

  auto power = NullPower(12000, rng);
  const double rate = f.bpfo_hz * 0.99;
  for (int k = 1; k <= 5; ++k) power[static_cast<int>(std::lround(k * rate / 0.1))] += 200.0;
  const auto s = NormalizeSpectrum(power, 0.1, o);
  const auto d = DetectFamily(s, fams[0], ctx, {});
  EXPECT_TRUE(d.detected) << d.reason;
  EXPECT_NEAR(d.fundamental_hz / rate, 1.0, 1e-3);
  // One strong line alone is not a family.
  auto single = NullPower(12000, rng);
  single[static_cast<int>(std::lround(rate / 0.1))] += 1e4;
  const auto d1 = DetectFamily(NormalizeSpectrum(single, 0.1, o), fams[0], ctx, {});
  EXPECT_FALSE(d1.detected) << d1.reason;
}

}  // namespace
}  // namespace spallkit::dsp
