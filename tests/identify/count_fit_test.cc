// Number and positions of defective rollers on synthetic records with known answers, and the
// sideband feature's model on its own.
#include "identify/count_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/constants.h"
#include "dsp/envelope.h"
#include "identify/load_zone.h"
#include "tests/identify/identify_test_records.h"

namespace spallkit::identify {
namespace {

using spallkit::testing::IdentifyRecord;
using spallkit::testing::RollerRecordSpec;

// These records are made by the fits' own signal model, so the calibration for the simulator's
// records (temperatures, width scale) does not apply.
IdentifyOptions ExactModel() { return SignalModelOptions(); }

// One spall, 10 dB in the resonance band, 1 s at 1200 rpm (8 cage revolutions).
TEST(CountFit, OneDefectiveRoller) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0, 1.38, 0}}));
  const Identification id = IdentifyRecord(r, 1200, 10000, ExactModel());
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 1);
  EXPECT_GT(id.probabilities[1], 0.9);
  // With the calibrated temperatures the same answer, less sure.
  const Identification calibrated = IdentifyRecord(r, 1200, 10000);
  ASSERT_TRUE(calibrated.count_identifiable) << calibrated.BriefReport();
  EXPECT_EQ(calibrated.count, 1);
  EXPECT_LT(calibrated.probabilities[1], id.probabilities[1]);
  EXPECT_EQ(id.positions_deg, (std::vector<double>{0.0}));
}

// CountFitOptions::combine_per_count: each feature's evidence is averaged over the
// configurations of K and then tempered, so the combined log evidence is the tempered sum of the
// two features' (the combination scripts/choose_temperatures.py calibrates); the default tempers
// each configuration first and differs. Either way this record counts one roller.
TEST(CountFit, CombinedPerCountIsTheTemperedSumOfTheFeatures) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0, 1.38, 0}}));
  IdentifyOptions o;
  o.count.combine_per_count = true;
  const Identification id = IdentifyRecord(r, 1200, 10000, o);
  const CountFit& f = id.count_fit;
  ASSERT_GT(f.sideband_lines, 0);
  for (size_t k = 1; k < f.log_evidence.size(); ++k) {
    if (!std::isfinite(f.log_evidence[k])) continue;
    EXPECT_NEAR(f.log_evidence[k],
                f.log_evidence_cage[k] / o.count.temperature_cage +
                    f.log_evidence_sidebands[k] / o.count.temperature_sidebands,
                1e-9)
        << k;
  }
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 1);
  const Identification by_configuration = IdentifyRecord(r, 1200, 10000);
  EXPECT_NE(by_configuration.count_fit.log_evidence[2], f.log_evidence[2]);
}

// Two spalls four slots apart: count 2, positions 0 and 4 x 360/13 = 110.8 deg.
TEST(CountFit, TwoRollersFourSlotsApart) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0}, {4, 1.38, 120}}));
  const Identification id = IdentifyRecord(r, 1200, 10000, ExactModel());
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 2);
  ASSERT_EQ(id.positions_deg.size(), 2u);
  EXPECT_NEAR(id.positions_deg[1], 4 * 360.0 / 13, 1e-9);
}

// Adjacent rollers: their load-zone humps overlap (27.7 deg apart, each ~140 deg wide) and the
// cage average alone cannot tell one from two; the sideband pattern (different spin phases) does.
TEST(CountFit, AdjacentRollersNeedTheSidebands) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0}, {1, 1.38, 120}}));
  const Identification id = IdentifyRecord(r, 1200, 10000, ExactModel());
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 2);
  EXPECT_GT(id.probabilities_sidebands[2], 0.9);
  EXPECT_LT(id.probabilities_cage[2], 0.5);  // the average alone prefers one wide hump
  EXPECT_NEAR(id.positions_deg[1], 360.0 / 13, 1e-9);
}

// Three rollers of different widths at slots 0, 3, 7 (canonical form {0, 3, 7}: its mirror image
// {0, 4, 7} is another configuration, so this also checks the direction of rotation).
TEST(CountFit, ThreeRollersAndTheirOrder) {
  const Record r =
      MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0, 1.38, 0}, {3, 1.0, 60}, {7, 2.0, 200}}));
  const Identification id = IdentifyRecord(r, 1200, 10000, ExactModel());
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 3);
  ASSERT_EQ(id.positions_deg.size(), 3u);
  EXPECT_NEAR(id.positions_deg[1], 3 * 360.0 / 13, 1e-9);
  EXPECT_NEAR(id.positions_deg[2], 7 * 360.0 / 13, 1e-9);
}

// One roller (1.38 mm, 20 dB) whose inner-race impacts reach a horizontal sensor whole while its
// outer-race ones come with sin psi, and the exact model's options for that sensor.
SyntheticRecordSpec UnprojectedInnerRaceRecord() {
  auto spec = RollerRecordSpec(1200, 20, {{0, 1.38, 0}});
  spec.sensor_angle_rad = 0.5 * kPi;
  spec.inner_race_projected = false;
  return spec;
}
IdentifyOptions HorizontalSensorExactModel() {
  IdentifyOptions o = ExactModel();
  o.count.sensor_angle_rad = 0.5 * kPi;
  return o;
}

// That roller's odd and even spin harmonics have different cage-angle patterns. Feature
// B with one pattern per parity (CountFitOptions::sideband_pattern_per_parity) takes it for one
// roller; with one pattern for every spin harmonic (IdentifyOptions::sideband_spin_step 1) a
// second, phantom roller fits the difference.
TEST(CountFit, OuterAndInnerRaceImpactsWithTheirOwnPatternsAreOneRoller) {
  const SyntheticRecordSpec spec = UnprojectedInnerRaceRecord();
  IdentifyOptions o = HorizontalSensorExactModel();
  o.count.sideband_pattern_per_parity = true;
  const Identification id = IdentifyRecord(MakeSyntheticRecord(spec), 1200, 10000, o);
  ASSERT_EQ(id.probabilities_sidebands.size(), id.probabilities.size()) << id.BriefReport();
  const auto& pb = id.probabilities_sidebands;
  EXPECT_EQ(std::max_element(pb.begin(), pb.end()) - pb.begin(), 1) << id.BriefReport();
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 1);
  // One pattern for every spin harmonic fits these lines worse (reduced chi2 20 against 1) and
  // makes the roller two.
  o.count.sideband_pattern_per_parity = false;
  ASSERT_EQ(o.sideband_spin_step, 1);  // ExactModel(): every spin harmonic
  const Identification shared = IdentifyRecord(MakeSyntheticRecord(spec), 1200, 10000, o);
  EXPECT_GT(shared.count_fit.chi2_scale_sidebands, 5.0 * id.count_fit.chi2_scale_sidebands)
      << shared.BriefReport();
}

// The same roller with feature B on the harmonics of f_b = 2 f_s (sideband_spin_step 2, the
// default): there the outer- and inner-race impacts, half a spin turn apart, add in phase, so
// every line carries their sum, whose cage-angle pattern is the cage average's, and the one
// shared pattern (feature A's hump) fits the lines nearly to their noise (reduced chi2 1.4, 20 on
// every spin harmonic). It still fits them best with two rollers here: the sum of a projected and
// an unprojected hump lies outside feature A's hump shapes, which feature B borrows.
TEST(CountFit, FbHarmonicsCarryOneRollersImpactsWithTheCageAveragesPattern) {
  IdentifyOptions o = HorizontalSensorExactModel();
  o.sideband_spin_step = 2;
  const Record r = MakeSyntheticRecord(UnprojectedInnerRaceRecord());
  const Identification fb = IdentifyRecord(r, 1200, 10000, o);
  o.sideband_spin_step = 1;
  const Identification every = IdentifyRecord(r, 1200, 10000, o);
  ASSERT_GT(fb.count_fit.sideband_lines, 0) << fb.BriefReport();
  std::printf("feature B's reduced chi2: %.2f on the f_b harmonics, %.2f on every spin harmonic\n",
              fb.count_fit.chi2_scale_sidebands,
              every.count_fit.chi2_scale_sidebands);
  EXPECT_LT(fb.count_fit.chi2_scale_sidebands, 2.0);
  EXPECT_GT(every.count_fit.chi2_scale_sidebands, 5.0 * fb.count_fit.chi2_scale_sidebands);
}

// The same roller's f_b harmonics carry the sum of a projected and an unprojected hump, which
// feature A's hump shapes do not describe (above). A second pattern per roller
// (CountFitOptions::sideband_second_pattern: real, symmetric about the roller's load-line
// crossing, fitted) fits that sum to its noise and raises the one-roller evidence by far more than
// its parameters cost; a phantom second roller still fits this record better (measured, not the
// default: docs/IDENTIFY.md, "Where the failures lie").
TEST(CountFit, ASecondPatternPerRollerFitsOneRollersTwoPatterns) {
  IdentifyOptions o = HorizontalSensorExactModel();
  o.sideband_spin_step = 2;
  const Record r = MakeSyntheticRecord(UnprojectedInnerRaceRecord());
  const Identification one = IdentifyRecord(r, 1200, 10000, o);
  o.count.sideband_second_pattern = true;
  const Identification two = IdentifyRecord(r, 1200, 10000, o);
  ASSERT_GE(one.count_fit.log_evidence_sidebands.size(), 2u) << one.BriefReport();
  ASSERT_GE(two.count_fit.log_evidence_sidebands.size(), 2u) << two.BriefReport();
  std::printf("feature B: reduced chi2 %.2f -> %.2f, ln Z(K = 1) %.1f -> %.1f\n",
              one.count_fit.chi2_scale_sidebands,
              two.count_fit.chi2_scale_sidebands,
              one.count_fit.log_evidence_sidebands[1],
              two.count_fit.log_evidence_sidebands[1]);
  EXPECT_GT(one.count_fit.chi2_scale_sidebands, 1.3);
  EXPECT_LT(two.count_fit.chi2_scale_sidebands, 1.05);
  EXPECT_GT(two.count_fit.log_evidence_sidebands[1], one.count_fit.log_evidence_sidebands[1] + 50);
}

// Feature B's lines reach 4 f_b + 4 f_c by default; the squared envelope is made alias-free up to
// them whatever the diagnosis band (here a 300 Hz one, narrower than those lines: without its
// rate set for the f_b harmonics, two of the four would be left out).
TEST(CountFit, SquaredEnvelopeHoldsEveryFbHarmonicOfTheSidebands) {
  const Record r = MakeSyntheticRecord(RollerRecordSpec(1200, 10, {{0, 1.38, 0}}));
  const BearingGeometry g = CatalogBearing("N205EM");
  dsp::Diagnosis d = dsp::Diagnose(r, g, 20.0);
  d.band.high_hz = d.band.low_hz + 300.0;
  IdentifyOptions o;
  o.radial_load_n = 10000.0;
  const Identification id = Identify(r, g, 20.0, d, o);
  ASSERT_EQ(o.sideband_spin_step, 2);
  EXPECT_EQ(id.sidebands.harmonics, o.sideband_harmonics);
  EXPECT_NEAR(id.sidebands.spin_hz, 2.0 * id.spin_hz, 1e-9);
  EXPECT_GT(id.sidebands.FrequencyHz(o.sideband_harmonics, o.sideband_orders), 4.0 * 115.0);
}

// A horizontal sensor under a vertical load: an impact along the roller's radius at orbit angle
// psi reaches it with sin(psi), so one roller's load-zone hump has two lobes, at the zone's
// flanks, and none on the load line. Given the sensor's direction, the count fit projects its
// humps the same way: one roller, and a closer fit of the cage average than with the sensor
// taken on the load line or with no projection.
TEST(CountFit, HorizontalSensorSeesOneRollerAsTwoLobes) {
  auto spec = RollerRecordSpec(1200, 10, {{0, 1.38, 0}});
  spec.sensor_angle_rad = 0.5 * kPi;
  const Record r = MakeSyntheticRecord(spec);
  auto identify_with_sensor = [&](std::optional<double> sensor_angle_rad) {
    IdentifyOptions o = ExactModel();
    o.count.sensor_angle_rad = sensor_angle_rad;
    return IdentifyRecord(r, 1200, 10000, o);
  };
  const Identification id = identify_with_sensor(0.5 * kPi);
  ASSERT_TRUE(id.count_identifiable) << id.BriefReport();
  EXPECT_EQ(id.count, 1);
  EXPECT_GT(id.probabilities[1], 0.9);
  const double chi2 = id.count_fit.best[1].chi2;
  for (std::optional<double> other : {std::optional<double>(0.0), std::optional<double>()}) {
    const Identification o = identify_with_sensor(other);
    std::printf("sensor %s: K = 1 chi2 %.1f (horizontal: %.1f)\n",
                other ? "on the load line" : "not given",
                o.count_fit.best[1].chi2,
                chi2);
    EXPECT_LT(chi2, 0.8 * o.count_fit.best[1].chi2);
  }
}

// Feature B alone: the true configuration's lines fit to their noise, a single roller does not.
TEST(CountFit, SidebandModelFitsTheTrueConfiguration) {
  SyntheticRecordSpec spec = RollerRecordSpec(1200, 60, {{0}, {1, 1.38, 120}});
  spec.spin_phase_walk_rad = 0.0;
  spec.entry_ratio = 0.0;
  SyntheticTruth truth;
  const Record r = MakeSyntheticRecord(spec, &truth);
  dsp::EnvelopeAnalyzer an(r.samples, r.sample_rate_hz);
  double rate = 0.0;
  const auto se = an.SquaredEnvelope({2500, 3500}, 1000, &rate);
  const SpinSidebands sb = MeasureSpinSidebands(se, rate, truth.spin_hz, truth.cage_hz);
  SpinSidebands tolerant = sb;  // the fit's 3 % model tolerance
  for (int j = 1; j <= sb.harmonics; ++j) {
    double peak = 0.0;
    for (int m = -sb.orders; m <= sb.orders; ++m)
      peak = std::max(peak, std::abs(sb.value[sb.Index(j, m)]));
    for (int m = -sb.orders; m <= sb.orders; ++m)
      tolerant.noise_power[sb.Index(j, m)] += std::pow(0.03 * peak, 2);
  }
  HumpFit two;
  two.slots = {0, 1};
  two.amplitudes = {1.0, 1.0};
  two.shape.exponent = 1.0;
  two.shape.smear_rad = 0.02;
  two.shape.half_angle_rad = truth.load_zone_half_angle_rad;
  two.theta0_rad = 0.0;  // roller 0 on the load line at t = 0
  HumpFit one = two;
  one.slots = {0};
  one.amplitudes = {1.0};
  int p2 = 0, p1 = 0;
  const double lines = 2.0 * sb.harmonics * (2 * sb.orders + 1);
  EXPECT_LT(SidebandChi2(tolerant, two, 13, &p2), 1.5 * lines);
  EXPECT_GT(SidebandChi2(tolerant, one, 13, &p1), 5.0 * lines);
}

TEST(CountFit, HumpFourierOfAFlatHumpIsItsMean) {
  HumpShape s;
  s.exponent = 1.0;
  s.half_angle_rad = 1.2;
  s.smear_rad = 0.01;
  const auto m = HumpFourier(s, 3);
  double mean = 0.0;
  for (int i = 0; i < 3600; ++i) mean += SmoothedHump(-kPi + (i + 0.5) * 2 * kPi / 3600, s, 0.0);
  EXPECT_NEAR(m[0], mean / 3600, 1e-4);
  EXPECT_GT(m[0], m[1]);
  EXPECT_GT(m[1], m[2]);
}

// The strength law's edge-to-centre ratio against a brute-force maximum over q.
TEST(CountFit, EdgeToCentreIsTheStrengthLawsMaximum) {
  for (double p : {0.25, 0.5, 1.0, 3.0})
    for (double beta : {0.0, 0.3, 1.06, 7.0, 20.0}) {
      HumpShape s;
      s.exponent = p;
      s.edge_gain = beta;
      double best = 0.0;
      for (int i = 1; i <= 100000; ++i) {
        const double q = i / 100000.0;
        best = std::max(best, std::pow(q, p) * (1.0 + beta * (1.0 - q)));
      }
      EXPECT_NEAR(s.EdgeToCentre(), best, 1e-6 * best) << "p " << p << " beta " << beta;
    }
  HumpShape flat;
  flat.exponent = 0.25;
  flat.edge_gain = 1.06;
  EXPECT_NEAR(flat.EdgeToCentre(), 1.30, 0.005);
}

TEST(CountFit, OptionsAreChecked) {
  CountFitOptions o;
  std::string e;
  EXPECT_TRUE(o.IsValid(&e));
  o.min_relative_amplitude = 1.5;
  EXPECT_FALSE(o.IsValid(&e));
  EXPECT_NE(e.find("min_relative_amplitude"), std::string::npos);
}

}  // namespace
}  // namespace spallkit::identify
