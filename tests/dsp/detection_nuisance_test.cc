// Fault lines that coincide with a shaft order or a mains harmonic: left out of the comb score,
// but counted in the family rule when they stand out of their nuisance comb; and the line table
// of a comb whose lines are all capped sits on the peaks, not on their leakage.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dsp/detection.h"
#include "tests/dsp/spectral_test_signals.h"

namespace spallkit::dsp {
namespace {

// The MFPT rig's bearing at 1488 rpm: BPFO = 3.245 f_r, so 2 x BPFO (6.49 f_r) lies 0.25 Hz
// from the shaft half order 6.5 f_r and 4 x BPFO from 13 f_r, within the 2-bin guard at 1 Hz.
constexpr double kShaftHz = 24.8;
constexpr double kDf = 1.0;

FaultFamily OuterRace() {
  const auto f = ComputeFrequencies(CustomBearing(8, 5.969, 31.623, 0.0), kShaftHz);
  return MakeFaultFamilies(f, {.harmonics = 5})[0];
}

using test_signals::NoisePower;

void AddLine(std::vector<double>* power, double hz, double level) {
  test_signals::AddLine(power, hz, kDf, level);
}

DetectionContext Context() {
  DetectionContext ctx;
  ctx.shaft_hz = kShaftHz;
  ctx.measured_shaft_scale = 1.0;
  return ctx;
}

const LineEvidence& Harmonic(const FamilyDetection& d, int k) {
  for (const auto& l : d.lines)
    if (l.line.harmonic == k && !l.line.is_sideband()) return l;
  throw std::logic_error("no harmonic");
}

// Noise with BPFO (400) and 2 x BPFO (200, on the shaft half order 6.5 f_r).
std::vector<double> OuterRaceLines(double bpfo, unsigned seed) {
  auto power = NoisePower(2000, seed);
  AddLine(&power, bpfo, 400.0);
  AddLine(&power, 2 * bpfo, 200.0);
  return power;
}

TEST(DetectionNuisance, HarmonicOnAShaftHalfOrderCountsWhenItStandsOutOfTheShaftComb) {
  const FaultFamily outer = OuterRace();
  const double bpfo = outer.fundamental_hz;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto power = OuterRaceLines(bpfo, seed);
    const auto s = NormalizeSpectrum(power, kDf);
    const FamilyDetection d = DetectFamily(s, outer, Context());
    const LineEvidence& h2 = Harmonic(d, 2);
    EXPECT_TRUE(h2.excluded);
    EXPECT_EQ(h2.exclusion, "shaft");
    EXPECT_GT(h2.nuisance_z, 0.0);
    EXPECT_TRUE(h2.significant) << "seed " << seed << ": z " << h2.z << " nuisance "
                                << h2.nuisance_z;
    EXPECT_EQ(d.significant_harmonics, 2);
    EXPECT_TRUE(d.detected) << d.reason;
    // The comb score does not use the excluded lines (2x and 4x on the half orders 13 and 26,
    // 3x on 240 Hz, 5x near 400 Hz at some scales).
    EXPECT_LE(d.lines_used, 2);
  }
}

TEST(DetectionNuisance, HarmonicOnAShaftHalfOrderIsNotEvidenceWhenTheShaftCombIsAsStrong) {
  const FaultFamily outer = OuterRace();
  const double bpfo = outer.fundamental_hz;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto power = OuterRaceLines(bpfo, seed);
    // Looseness: every half order carries a line as strong as the one on 2 x BPFO.
    for (int m = 1; m * 0.5 * kShaftHz < 450.0; ++m)
      if (std::abs(m * 0.5 * kShaftHz - 2 * bpfo) > 3.0) AddLine(&power, m * 0.5 * kShaftHz, 200.0);
    const auto s = NormalizeSpectrum(power, kDf);
    const FamilyDetection d = DetectFamily(s, outer, Context());
    const LineEvidence& h2 = Harmonic(d, 2);
    EXPECT_TRUE(h2.excluded);
    EXPECT_FALSE(h2.significant) << "seed " << seed << ": z " << h2.z << " nuisance "
                                 << h2.nuisance_z;
    EXPECT_FALSE(d.detected) << d.reason;
  }
}

TEST(DetectionNuisance, WithoutReferenceLinesTheCoincidentLineStaysOut) {
  const FaultFamily outer = OuterRace();
  auto power = NoisePower(2000, 7);
  AddLine(&power, outer.fundamental_hz, 400.0);
  AddLine(&power, 2 * outer.fundamental_hz, 200.0);
  const auto s = NormalizeSpectrum(power, kDf);
  DetectionOptions o;
  o.min_nuisance_references = 1000;  // more shaft orders than the searched range holds
  const FamilyDetection d = DetectFamily(s, outer, Context(), o);
  EXPECT_EQ(Harmonic(d, 2).nuisance_z, 0.0);
  EXPECT_FALSE(Harmonic(d, 2).significant);
  EXPECT_FALSE(d.detected) << d.reason;
}

// A roller spall whose f_b is twice the mains frequency: its spin series (k - 1/2) f_b then sits
// on the odd mains harmonics and f_b on the even ones. The spin series is not scored, so its
// windows must not take the mains comb's reference lines away: without references the line on
// f_b could not be tested against its comb and the spall, carried by f_b and its f_c sidebands,
// would be called healthy (as a lumped spalled record at 1059 rpm was).
TEST(DetectionNuisance, SpinSeriesWindowsLeaveTheMainsCombItsReferenceLines) {
  const double mains = 50.0;
  const auto bearing = CustomBearing(13, 6.5, 38.5, 0.0);  // the N205EM's geometry
  const double f_b_per_shaft = ComputeFrequencies(bearing, 1.0).f_b_hz;
  const double shaft = 2.0 * mains / f_b_per_shaft;  // f_b = 100 Hz
  const auto f = ComputeFrequencies(bearing, shaft);
  const FaultFamily roller = MakeFaultFamilies(f, {.harmonics = 5})[2];
  ASSERT_EQ(roller.component, FaultComponent::kRollingElement);
  DetectionContext ctx;
  ctx.shaft_hz = shaft;
  ctx.exclude_shaft = false;  // the shaft's orders are not what is tested here
  DetectionOptions o;
  o.mains_hz = {mains};
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto power = NoisePower(2000, seed);
    AddLine(&power, 2.0 * mains, 400.0);
    AddLine(&power, 2.0 * mains - f.cage_hz, 150.0);
    AddLine(&power, 2.0 * mains + f.cage_hz, 150.0);
    const auto s = NormalizeSpectrum(power, kDf);
    const FamilyDetection d = DetectFamily(s, roller, ctx, o);
    const LineEvidence& h1 = Harmonic(d, 1);
    EXPECT_EQ(h1.exclusion, "mains");
    EXPECT_GT(h1.nuisance_z, 0.0) << "seed " << seed << ": the mains comb has no reference line";
    EXPECT_TRUE(h1.significant) << "seed " << seed;
    EXPECT_TRUE(d.detected) << "seed " << seed << ": " << d.reason;
  }
}

// Every line capped (max_line_score): many speed scales tie; the table must sit on the peaks
// (the largest uncapped evidence), not on the strong leakage two bins beside them.
TEST(DetectionNuisance, TiedCappedCombReportsThePeaksNotTheirLeakage) {
  const auto f = ComputeFrequencies(CatalogBearing("6205"), 29.5);
  const FaultFamily outer = MakeFaultFamilies(f, {.harmonics = 4})[0];
  const double df = 0.2, rate = f.bpfo_hz * 1.004;
  auto power = NoisePower(6000, 11);
  for (int k = 1; k <= 4; ++k) {
    const int peak = static_cast<int>(std::lround(k * rate / df));
    power[peak] += 1e6;
    power[peak - 2] += 2e4;  // leakage: capped as well
  }
  const auto s = NormalizeSpectrum(power, df);
  DetectionContext ctx;
  ctx.shaft_hz = 29.5;
  ctx.exclude_shaft = false;
  ctx.exclude_mains = false;
  const FamilyDetection d = DetectFamily(s, outer, ctx);
  ASSERT_TRUE(d.detected) << d.reason;
  for (int k = 1; k <= 4; ++k) {
    const LineEvidence& h = Harmonic(d, k);
    EXPECT_GT(h.z, 1e5) << "harmonic " << k << " at " << h.freq_hz << " Hz";
  }
  EXPECT_NEAR(d.fundamental_hz / rate, 1.0, 5e-4);
}

}  // namespace
}  // namespace spallkit::dsp
