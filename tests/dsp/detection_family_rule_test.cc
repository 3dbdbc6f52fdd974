// The family rule on line patterns: one f_b harmonic with two more lines of the roller's own
// pattern (single f_c sidebands at two harmonics: several defective rollers' sidebands cancel on
// one side; or a sideband and a spin-series line) is a roller spall, while a race family still
// needs both sidebands of one harmonic.
#include <gtest/gtest.h>

#include "dsp/detection.h"
#include "tests/dsp/spectral_test_signals.h"

namespace spallkit::dsp {
namespace {

using test_signals::AddLine;
using test_signals::NoisePower;

constexpr double kDf = 1.0;
constexpr double kShaftHz = 20.0;  // 1200 rpm

// The N205EM's family of component c at 1200 rpm.
FaultFamily N205emFamily(FaultComponent c) {
  for (const auto& f :
       MakeFaultFamilies(ComputeFrequencies(CatalogBearing("N205EM"), kShaftHz), {.harmonics = 5}))
    if (f.component == c) return f;
  throw std::logic_error("no family");
}

// The family's detection in a power spectrum (bins kDf apart), the rule tested, not the
// exclusions.
FamilyDetection Detect(const std::vector<double>& power, const FaultFamily& family) {
  DetectionContext ctx;
  ctx.shaft_hz = kShaftHz;
  ctx.exclude_shaft = false;
  ctx.exclude_mains = false;
  return DetectFamily(NormalizeSpectrum(power, kDf), family, ctx);
}

// Noise with the carrier's first harmonic and one sideband (upper) at its first two harmonics.
std::vector<double> OneSidedPattern(double carrier_hz, double sideband_hz, unsigned seed) {
  auto power = NoisePower(2000, seed);
  AddLine(&power, carrier_hz, kDf, 400.0);
  AddLine(&power, carrier_hz + sideband_hz, kDf, 150.0);
  AddLine(&power, 2.0 * carrier_hz + sideband_hz, kDf, 150.0);
  return power;
}

TEST(FamilyRule, RollerHarmonicWithOneSidedSidebandsAtTwoHarmonicsIsARollerSpall) {
  const FaultFamily roller = N205emFamily(FaultComponent::kRollingElement);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const FamilyDetection d =
        Detect(OneSidedPattern(roller.fundamental_hz, roller.sideband_hz, seed), roller);
    EXPECT_EQ(d.significant_harmonics, 1) << "seed " << seed;
    EXPECT_EQ(d.significant_sidebands, 2) << "seed " << seed;
    EXPECT_TRUE(d.detected) << "seed " << seed << ": " << d.reason;
  }
}

// The carrier, one spin-series line and one sideband: three lines of the roller's own pattern
// (no bare f_b comb has the last two). The carrier with one sideband alone is not a family.
TEST(FamilyRule, RollerHarmonicWithASpinLineAndASidebandIsARollerSpall) {
  const FaultFamily roller = N205emFamily(FaultComponent::kRollingElement);
  const double f_b = roller.fundamental_hz, f_c = roller.sideband_hz;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    auto power = NoisePower(2000, seed);
    AddLine(&power, f_b, kDf, 400.0);
    AddLine(&power, f_b + f_c, kDf, 150.0);
    const FamilyDetection two = Detect(power, roller);
    EXPECT_EQ(two.significant_sidebands, 1) << "seed " << seed;
    EXPECT_FALSE(two.detected) << "seed " << seed << ": " << two.reason;
    AddLine(&power, 1.5 * f_b, kDf, 150.0);
    const FamilyDetection three = Detect(power, roller);
    EXPECT_EQ(three.significant_harmonics, 2) << "seed " << seed;  // f_b and 1.5 f_b
    EXPECT_TRUE(three.detected) << "seed " << seed << ": " << three.reason;
  }
}

TEST(FamilyRule, RaceHarmonicWithOneSidedSidebandsIsNotAFamily) {
  const FaultFamily inner = N205emFamily(FaultComponent::kInnerRace);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const FamilyDetection d =
        Detect(OneSidedPattern(inner.fundamental_hz, inner.sideband_hz, seed), inner);
    EXPECT_EQ(d.significant_sidebands, 2) << "seed " << seed;
    EXPECT_FALSE(d.detected) << "seed " << seed << ": " << d.reason;
    // Both sidebands of the one harmonic: a single inner-race defect's modulation.
    auto both = NoisePower(2000, seed);
    AddLine(&both, inner.fundamental_hz, kDf, 400.0);
    AddLine(&both, inner.fundamental_hz - inner.sideband_hz, kDf, 150.0);
    AddLine(&both, inner.fundamental_hz + inner.sideband_hz, kDf, 150.0);
    EXPECT_TRUE(Detect(both, inner).detected) << "seed " << seed;
  }
}

}  // namespace
}  // namespace spallkit::dsp
