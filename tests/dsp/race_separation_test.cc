// Outer against inner race on the harmonics only one of them predicts (dsp/explain.h): for a 6205
// 3 BPFO lies 0.7 % from 2 BPFI, so an outer-race fault feeds the inner-race comb, and the shaft
// modulation of that line looks like the inner race's +/- f_r sidebands.
#include <gtest/gtest.h>

#include <random>

#include "dsp/detection.h"
#include "dsp/explain.h"
#include "tests/dsp/spectral_test_signals.h"

namespace spallkit::dsp {
namespace {

constexpr double kShaftHz = 29.5, kDf = 0.2;

using test_signals::NoisePower;

void AddLine(std::vector<double>* power, double hz, double level) {
  test_signals::AddLine(power, hz, kDf, level);
}

TEST(RaceSeparation, OuterRaceCombFeedingTheInnerRaceCombGoesFirst) {
  const auto kin = ComputeFrequencies(CatalogBearing("6205"), kShaftHz);
  const auto families = MakeFaultFamilies(kin, {.harmonics = 5});
  for (unsigned seed = 1; seed <= 3; ++seed) {
    auto power = NoisePower(6000, seed);
    // Moderate 1, 2, 4 x BPFO; 3 x and 6 x BPFO (= 2 x and 4 x BPFI) far stronger, so that the
    // mean evidence of all harmonics would favour the inner race.
    for (int k : {1, 2, 4}) AddLine(&power, k * kin.bpfo_hz, 60.0);
    for (int k : {3, 6}) AddLine(&power, k * kin.bpfo_hz, 1e5);
    // Shaft modulation of the strongest shared line: 3 BPFO +/- f_r (= 2 BPFI +/- f_r), a bin
    // wide (the inner comb's scale puts them 0.2 Hz off).
    for (double sb : {-kShaftHz, kShaftHz})
      for (double offset : {-kDf, 0.0, kDf}) AddLine(&power, 3 * kin.bpfo_hz + sb + offset, 300.0);
    const auto s = NormalizeSpectrum(power, kDf);
    DetectionContext ctx;
    ctx.shaft_hz = kShaftHz;
    ctx.measured_shaft_scale = 1.0;
    ctx.multiplicity = 4;
    std::vector<FamilyDetection> dets;
    for (const auto& f : families) dets.push_back(DetectFamily(s, f, ctx));
    ASSERT_TRUE(dets[0].detected) << dets[0].reason;
    ASSERT_TRUE(dets[1].detected) << "the inner-race comb must be fed for this test: "
                                  << dets[1].reason;
    const RaceSeparation r = SeparateRaces(dets[0], dets[1], kDf, {});
    EXPECT_TRUE(r.separable);
    EXPECT_GE(r.outer_significant, 2);
    EXPECT_EQ(r.inner_significant, 0);
    EXPECT_GT(r.outer_evidence, r.inner_evidence);
    EXPECT_GT(dets[1].harmonic_evidence, dets[0].harmonic_evidence);  // all lines: inner
    const JointExplanation j = ExplainJointly(s, families, dets, ctx, {});
    ASSERT_FALSE(j.ranked.empty());
    EXPECT_EQ(j.ranked[0].component, FaultComponent::kOuterRace);
    EXPECT_TRUE(j.races.tested);
  }
}

// Both races' only significant harmonic is the shared line: not separable.
TEST(RaceSeparation, OnlySharedHarmonicsAreNotSeparable) {
  const auto kin = ComputeFrequencies(CatalogBearing("6205"), kShaftHz);
  auto harmonic = [](int k, double hz, double p, bool significant) {
    LineEvidence e;
    e.line.harmonic = k;
    e.freq_hz = hz;
    e.p_value = p;
    e.significant = significant;
    return e;
  };
  const double shared = 3 * kin.bpfo_hz;  // within 0.7 % of 2 BPFI, i.e. 2.3 Hz: 3 bins + guard
  FamilyDetection outer, inner;
  outer.component = FaultComponent::kOuterRace;
  outer.fundamental_hz = kin.bpfo_hz;
  inner.component = FaultComponent::kInnerRace;
  inner.fundamental_hz = shared / 2;
  for (int k = 1; k <= 5; ++k) {
    outer.lines.push_back(harmonic(k, k * outer.fundamental_hz, k == 3 ? 1e-30 : 0.5, k == 3));
    inner.lines.push_back(harmonic(k, k * inner.fundamental_hz, k == 2 ? 1e-30 : 0.5, k == 2));
  }
  const RaceSeparation r = SeparateRaces(outer, inner, kDf, {});
  EXPECT_FALSE(r.separable);
  EXPECT_EQ(r.outer_significant, 0);
  EXPECT_EQ(r.inner_significant, 0);
  EXPECT_NE(r.Describe().find("not separable"), std::string::npos);
  // An unshared significant harmonic makes them separable.
  outer.lines[0] = harmonic(1, outer.fundamental_hz, 1e-20, true);
  EXPECT_TRUE(SeparateRaces(outer, inner, kDf, {}).separable);
}

}  // namespace
}  // namespace spallkit::dsp
