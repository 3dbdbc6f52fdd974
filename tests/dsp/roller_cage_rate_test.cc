// The roller spall's cage rate f_c (MeasureRollerCageRate, dsp/explain.h): least squares over the
// +/- f_c sideband pairs around k f_b and the SES's own modulation lines m f_c, each weighted by
// its precision; single sidebands only as a fallback; modulation lines that are not resolved from
// a shaft order are left out. Checked on hand-made spectra with bin-centred lines (whose sub-bin
// interpolation is exact), so every expected value is exact arithmetic.
#include <gtest/gtest.h>

#include <vector>

#include "dsp/detection.h"
#include "dsp/explain.h"
#include "dsp/fault_bands.h"

namespace spallkit::dsp {
namespace {

constexpr double kDf = 0.25;        // Hz per bin (a 4 s record)
constexpr double kShaftHz = 20.0;   // N205EM at 1200 rpm: half orders at 10, 30 Hz
constexpr double kFbHz = 114.25;    // measured f_b (bin 457)
constexpr double kCageHz = 8.3117;  // kinematic f_c

// A flat floor with strong single-bin lines at the given frequencies (bin centres).
NormalizedSpectrum Spectrum(const std::vector<double>& lines_hz) {
  std::vector<double> power(4000, 1.0);
  for (double f : lines_hz) power[static_cast<int>(f / kDf + 0.5)] = 1e4;
  return NormalizeSpectrum(power, kDf);
}

FaultFamily RollerFamily() {
  FaultFamily f;
  f.component = FaultComponent::kRollingElement;
  f.fundamental_hz = 115.08;
  f.sideband_hz = kCageHz;
  return f;
}

LineEvidence Line(int harmonic, int sideband, double freq_hz) {
  LineEvidence e;
  e.line.harmonic = harmonic;
  e.line.sideband = sideband;
  e.freq_hz = freq_hz;
  e.significant = true;
  return e;
}

FamilyDetection Roller(std::vector<LineEvidence> lines) {
  FamilyDetection d;
  d.component = FaultComponent::kRollingElement;
  d.detected = true;
  d.fundamental_hz = kFbHz;
  d.scale = kFbHz / 115.08;
  d.lines = std::move(lines);
  return d;
}

CageRateMeasurement Measure(const NormalizedSpectrum& s, const FamilyDetection& d) {
  return MeasureRollerCageRate(s, d, RollerFamily(), kCageHz, kShaftHz, DetectionOptions{});
}

TEST(RollerCageRate, ModulationLinesAloneGiveTheRate) {
  // No sideband pair: f_c from the lines at f_c and 2 f_c (weights 1 and 4).
  const auto s = Spectrum({8.25, 16.5, kFbHz, 2 * kFbHz});
  const auto r = Measure(s, Roller({Line(1, 0, kFbHz), Line(2, 0, 2 * kFbHz)}));
  EXPECT_DOUBLE_EQ(r.hz, 8.25);
  EXPECT_EQ(r.modulation_lines, 2);
  EXPECT_EQ(r.sideband_pairs, 0);
  EXPECT_EQ(r.Source(), "2 modulation lines");
}

TEST(RollerCageRate, PairsAndModulationLinesAreWeightedByPrecision) {
  // Pair around f_b: half-distance 8.0 (weight 2); modulation lines 8.25 (weight 1) and
  // 16.5 / 2 (weight 4): (2 x 8 + 8.25 + 4 x 8.25) / 7.
  const auto s = Spectrum({8.25, 16.5, kFbHz - 8.0, kFbHz, kFbHz + 8.0});
  const auto r =
      Measure(s, Roller({Line(1, 0, kFbHz), Line(1, -1, kFbHz - 8.0), Line(1, +1, kFbHz + 8.0)}));
  EXPECT_NEAR(r.hz, (2 * 8.0 + 8.25 + 4 * 8.25) / 7.0, 1e-12);
  EXPECT_EQ(r.sideband_pairs, 1);
  EXPECT_EQ(r.modulation_lines, 2);
  EXPECT_EQ(r.single_sidebands, 0);
}

TEST(RollerCageRate, InsignificantSidebandsDoNotMakeAPair) {
  const auto s = Spectrum({8.25, kFbHz, kFbHz + 8.0});
  auto lower = Line(1, -1, kFbHz - 8.0);
  lower.significant = false;
  const auto r = Measure(s, Roller({Line(1, 0, kFbHz), lower, Line(1, +1, kFbHz + 8.0)}));
  EXPECT_EQ(r.sideband_pairs, 0);
  EXPECT_EQ(r.modulation_lines, 1);
  EXPECT_DOUBLE_EQ(r.hz, 8.25);  // the single sideband is not used next to a modulation line
}

TEST(RollerCageRate, LineOnAShaftHalfOrderIsLeftOutAndSingleSidebandsStandIn) {
  // The only line near f_c sits within a bin of the half order 10 Hz: it could be the shaft's.
  // Measured with a cage rate of 9.9 Hz so that the line is inside the match window.
  const auto s = Spectrum({10.0, kFbHz, kFbHz + 9.75});
  const auto r = MeasureRollerCageRate(s,
                                       Roller({Line(1, 0, kFbHz), Line(1, +1, kFbHz + 9.75)}),
                                       RollerFamily(),
                                       9.9 * 115.08 / kFbHz,
                                       kShaftHz,
                                       DetectionOptions{});
  EXPECT_EQ(r.modulation_lines, 0);
  EXPECT_EQ(r.single_sidebands, 1);
  EXPECT_DOUBLE_EQ(r.hz, 9.75);
  EXPECT_EQ(r.Source(), "1 single sideband");
}

TEST(RollerCageRate, LinesInTheRollerForestAreNotModulationLines) {
  // Orders at or above f_b / 2 - 2.5 f_c (= 36.4 Hz here) belong to the 1 x BSF series and its
  // sidebands: a line at 5 f_c = 41.25 Hz is not used, so the rate comes from f_c alone.
  const auto s = Spectrum({8.25, 41.0, kFbHz});
  const auto r = Measure(s, Roller({Line(1, 0, kFbHz)}));
  EXPECT_EQ(r.modulation_lines, 1);
  EXPECT_DOUBLE_EQ(r.hz, 8.25);
}

TEST(RollerCageRate, NothingMeasuredGivesZero) {
  const auto s = Spectrum({kFbHz});
  const auto r = Measure(s, Roller({Line(1, 0, kFbHz)}));
  EXPECT_EQ(r.hz, 0.0);
  EXPECT_EQ(r.Source(), "none");
  // Other families are not measured here.
  FaultFamily cage = RollerFamily();
  cage.component = FaultComponent::kCage;
  EXPECT_EQ(MeasureRollerCageRate(s, Roller({}), cage, kCageHz, kShaftHz, {}).hz, 0.0);
}

}  // namespace
}  // namespace spallkit::dsp
