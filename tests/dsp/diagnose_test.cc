// End-to-end diagnosis of synthetic records: each fault type is recovered with its rate, and noise
// (with shaft, mains and BPFO-order lines) is called healthy at the stated false-alarm rate.
#include "dsp/diagnose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "core/bearing.h"
#include "core/error.h"
#include "dsp/envelope.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

using spallkit::testing::FaultSignalSpec;
using spallkit::testing::MakeFaultSignal;

const FamilyDetection& Find(const Diagnosis& d, FaultComponent c) {
  for (const auto& f : d.faults)
    if (f.component == c) return f;
  throw std::runtime_error("family missing");
}

// Distractors every healthy machine has: shaft harmonics and mains lines.
FaultSignalSpec Base(double shaft_hz, double fs, unsigned seed) {
  FaultSignalSpec s;
  s.fs_hz = fs;
  s.duration_s = 2.0;
  s.shaft_hz = shaft_hz;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  s.noise_rms = 0.4;
  s.amplitude = 3.0;  // first harmonics modulate ~30-60 % of the band, as CWRU's faults do
  s.seed = seed;
  return s;
}

struct Case {
  const char* bearing;
  double rpm;
  double fs;
  FaultComponent component;
};

class FaultRecovery : public ::testing::TestWithParam<Case> {};

TEST_P(FaultRecovery, VerdictAndRateWithinOnePermille) {
  const Case c = GetParam();
  const BearingGeometry g = CatalogBearing(c.bearing);
  const BearingFrequencies f = ComputeFrequencies(g, c.rpm / 60.0);
  FaultSignalSpec s = Base(f.shaft_hz, c.fs, 7);
  const double slip = 0.99;  // real bearings run 1 % below kinematics
  switch (c.component) {
    case FaultComponent::kOuterRace:
      s.rate_hz = f.bpfo_hz * slip;
      break;
    case FaultComponent::kInnerRace:
      s.rate_hz = f.bpfi_hz * slip;
      s.modulation_hz = f.shaft_hz;  // fault turns through the load zone
      s.modulation_depth = 0.8;
      break;
    case FaultComponent::kRollingElement:
      s.rate_hz = f.f_b_hz * slip;
      s.modulation_hz = f.cage_hz * slip;  // roller goes round with the cage
      s.modulation_depth = 0.8;
      break;
    case FaultComponent::kCage:
      s.rate_hz = f.cage_hz * slip;
      break;
  }
  s.resonance_hz = 0.27 * c.fs;
  const Diagnosis d = Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz);
  SCOPED_TRACE(d.BriefReport());
  EXPECT_EQ(d.verdict, VerdictOf(c.component));
  const FamilyDetection& det = Find(d, c.component);
  EXPECT_TRUE(det.detected);
  EXPECT_NEAR(det.fundamental_hz / s.rate_hz, 1.0, 1e-3);
  EXPECT_LT(det.p_value, 1e-3);
  if (c.component == FaultComponent::kRollingElement) {
    ASSERT_TRUE(d.measured_f_b_hz.has_value());
    EXPECT_NEAR(*d.measured_f_b_hz / s.rate_hz, 1.0, 1e-3);
    ASSERT_TRUE(d.f_b_slip_percent.has_value());
    EXPECT_NEAR(*d.f_b_slip_percent, -1.0, 0.1);
    ASSERT_TRUE(d.measured_f_c_hz.has_value());
    EXPECT_NEAR(*d.measured_f_c_hz / s.modulation_hz, 1.0, 1e-2);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Bearings,
    FaultRecovery,
    ::testing::Values(Case{"6205", 1797, 12000, FaultComponent::kOuterRace},
                      Case{"6205", 1797, 12000, FaultComponent::kInnerRace},
                      Case{"6205", 1797, 12000, FaultComponent::kRollingElement},
                      Case{"6205", 1797, 12000, FaultComponent::kCage},
                      Case{"N205EM", 1200, 20000, FaultComponent::kRollingElement},
                      Case{"N205EM", 1200, 20000, FaultComponent::kInnerRace},
                      Case{"6203", 1750, 48000, FaultComponent::kOuterRace},
                      Case{"6203", 1750, 25600, FaultComponent::kInnerRace}));

// A roller spall whose impacts ring only a low resonance (950 Hz, as the full-FE record of
// docs/BEARING_MODEL.md carries its spall in 500-1250 Hz): N205EM at 1200 rpm, 20 kHz. Bands as
// wide as the inner-race comb (5 BPFI + f_r, 835 Hz with the search range) that start above half
// of it begin at 1250 Hz and never hold the resonance; bands down to the narrowest that holds
// the whole rolling-element comb (5 f_b + f_c, 625 Hz) do, e.g. [625, 1250] or [833, 1667] Hz (the
// one chosen here).
TEST(Diagnose, RollerSpallRingingOnlyBelowTheWideBandsIsFound) {
  const BearingGeometry g = CatalogBearing("N205EM");
  const BearingFrequencies f = ComputeFrequencies(g, 20.0);
  FaultSignalSpec s = Base(f.shaft_hz, 20000, 11);
  s.rate_hz = f.f_b_hz * 0.995;
  s.modulation_hz = f.cage_hz * 0.995;
  s.modulation_depth = 0.8;
  s.resonance_hz = 950.0;
  s.damping_ratio = 0.08;  // rings ~2 ms of the 8.7 ms between impacts
  const Diagnosis d = Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz);
  SCOPED_TRACE(d.BriefReport());
  EXPECT_EQ(d.verdict, Verdict::kRollingElement);
  EXPECT_LE(d.band.width_hz(), 835.0);
  EXPECT_LT(d.band.low_hz, 950.0);
  EXPECT_GT(d.band.high_hz, 950.0);
  ASSERT_TRUE(d.measured_f_b_hz.has_value());
  EXPECT_NEAR(*d.measured_f_b_hz / s.rate_hz, 1.0, 2e-3);
  ASSERT_TRUE(d.measured_f_c_hz.has_value());
  EXPECT_NEAR(*d.measured_f_c_hz / s.modulation_hz, 1.0, 2e-2);
}

// A nominal speed 3 % off: the measured shaft speed re-centres the search.
TEST(Diagnose, RecoversOuterRaceWithNominalSpeedThreePercentOff) {
  const BearingGeometry g = CatalogBearing("6205");
  const BearingFrequencies f = ComputeFrequencies(g, 30.0);
  FaultSignalSpec s = Base(f.shaft_hz, 12000, 3);
  s.rate_hz = f.bpfo_hz * 0.995;
  for (double off : {0.97, 1.03}) {
    const Diagnosis d = Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz * off);
    SCOPED_TRACE(d.BriefReport());
    EXPECT_EQ(d.verdict, Verdict::kOuterRace);
    ASSERT_TRUE(d.measured_shaft_hz.has_value());
    EXPECT_NEAR(*d.measured_shaft_hz, f.shaft_hz, 0.01);
  }
}

// The shaft-speed estimate needs the 1x or 2x line: lines at only 4x and 5x of a speed 4.5 %
// above nominal (a simulated roller spall's cage-lattice lines at 1200 rpm: 10 f_c and f_b - f_c
// fell on 4 x and 5 x 20.9 Hz) are not a shaft comb; with the 1x and 2x lines the same comb is.
TEST(Diagnose, ShaftSpeedNeedsItsFirstOrSecondHarmonic) {
  const double fs = 20000.0, f0 = 20.9;
  std::vector<double> high(20000), low(20000);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (size_t i = 0; i < high.size(); ++i) {
    const double t = i / fs;
    const double n = noise(rng);
    high[i] = n + std::sin(2 * M_PI * 4 * f0 * t) + 0.8 * std::sin(2 * M_PI * 5 * f0 * t);
    low[i] = n + std::sin(2 * M_PI * f0 * t) + 0.8 * std::sin(2 * M_PI * 2 * f0 * t);
  }
  EXPECT_FALSE(EstimateShaftSpeed(EnvelopeAnalyzer(high, fs), 20.0, 0.05).has_value());
  const auto measured = EstimateShaftSpeed(EnvelopeAnalyzer(low, fs), 20.0, 0.05);
  ASSERT_TRUE(measured.has_value());
  EXPECT_NEAR(*measured, f0, 0.1);  // 1 Hz bins, lines up to 2x: the speed grid's step
}

// Healthy records: noise, shaft and mains lines and a BPFO-order line (varying compliance).
// Bonferroni over families, bands and comb combinations makes the test conservative: the
// empirical false-alarm fraction must not exceed the design rate (binomial 3-sigma margin).
TEST(Diagnose, HealthyRecordsFalseAlarmRateWithinDesign) {
  const BearingGeometry g = CatalogBearing("6205");
  const BearingFrequencies f = ComputeFrequencies(g, 29.95);
  const int kRecords = 120;
  for (double alpha : {0.2, 1e-3}) {
    int alarms = 0, alarms_lines = 0;
    DiagnoseOptions o;
    o.false_alarm_probability = alpha;
    for (int seed = 1; seed <= kRecords; ++seed) {
      FaultSignalSpec s;
      s.fs_hz = 12000;
      s.duration_s = 1.0;
      s.noise_rms = 1.0;
      s.seed = 1000 + seed;
      if (Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz, o).verdict !=
          Verdict::kHealthy)
        ++alarms;
      FaultSignalSpec t = Base(f.shaft_hz, 12000, 5000 + seed);
      t.duration_s = 1.0;
      t.extra_line_hz = f.bpfo_hz;
      t.extra_line_amplitude = 0.3;
      if (Diagnose(spallkit::testing::MakeFaultRecord(t), g, f.shaft_hz, o).verdict !=
          Verdict::kHealthy)
        ++alarms_lines;
    }
    const double margin = 3.0 * std::sqrt(alpha * (1 - alpha) / kRecords);
    EXPECT_LE(alarms / double(kRecords), alpha + margin) << "alpha " << alpha;
    EXPECT_LE(alarms_lines / double(kRecords), alpha + margin) << "alpha " << alpha;
    if (alpha < 0.01) {
      EXPECT_EQ(alarms, 0);
      EXPECT_EQ(alarms_lines, 0);
    }
  }
}

TEST(Diagnose, JsonHasTheStableKeys) {
  const BearingGeometry g = CatalogBearing("6205");
  const BearingFrequencies f = ComputeFrequencies(g, 29.95);
  FaultSignalSpec s = Base(f.shaft_hz, 12000, 11);
  s.rate_hz = f.bpfi_hz;
  s.modulation_hz = f.shaft_hz;
  s.modulation_depth = 0.8;
  const Diagnosis d = Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz);
  const auto j = nlohmann::json::parse(d.ToJson());
  EXPECT_EQ(j["verdict"], "inner_race");
  ASSERT_EQ(j["faults"].size(), 4u);
  EXPECT_EQ(j["faults"][0]["component"], "inner_race");
  for (const char* k : {"detected", "score", "threshold", "p_value", "harmonics"})
    EXPECT_TRUE(j["faults"][0].contains(k)) << k;
  for (const char* k : {"center_hz", "bandwidth_hz"}) EXPECT_TRUE(j["band"].contains(k)) << k;
  for (const char* k : {"f_b_hz", "bpfo_hz", "bpfi_hz", "cage_hz"})
    EXPECT_TRUE(j["kinematics"].contains(k)) << k;
  for (const char* k : {"f_b_hz", "f_c_hz", "slip_percent"})
    EXPECT_TRUE(j["measured"].contains(k)) << k;
  EXPECT_TRUE(j["measured"]["f_b_hz"].is_null());  // no roller fault here
  EXPECT_TRUE(j["statistics"].contains("kurtosis"));
}

TEST(Diagnose, BadInputIsAnInputError) {
  const BearingGeometry g = CatalogBearing("6205");
  Record r;
  r.samples.assign(24000, 0.0);
  r.sample_rate_hz = 12000;
  EXPECT_THROW(Diagnose(r, g, 0.0), InputError);
  EXPECT_THROW(Diagnose(r, g, -5.0), InputError);
  Record bad_fs = r;
  bad_fs.sample_rate_hz = 0.0;
  EXPECT_THROW(Diagnose(bad_fs, g, 30.0), InputError);
  Record low_fs = r;
  low_fs.sample_rate_hz = 200.0;  // BPFI 162 Hz above Nyquist 100 Hz
  EXPECT_THROW(Diagnose(low_fs, g, 30.0), InputError);
  Record short_r = r;
  short_r.samples.resize(1000);
  EXPECT_THROW(Diagnose(short_r, g, 30.0), InputError);
  DiagnoseOptions o;
  o.harmonics = 0;
  EXPECT_THROW(Diagnose(r, g, 30.0, o), InputError);
}

}  // namespace
}  // namespace spallkit::dsp
