// Staged band search (DiagnoseOptions::first_bands): at 48 kHz the width rule admits 95 kurtogram
// nodes (64 as wide as the widest comb, 31 narrower that still hold the outer-race or roller comb);
// the 16 of highest spectral kurtosis are searched first and the rest only when those show
// no detected family. The Bonferroni factor always counts all 95, healthy records are searched in
// full (so their false-alarm rate is that of the full search), and a fault is found as with every
// band searched.
#include <gtest/gtest.h>

#include <cmath>

#include "core/bearing.h"
#include "dsp/diagnose.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

using spallkit::testing::FaultSignalSpec;
using spallkit::testing::MakeFaultSignal;

TEST(DiagnoseBands, FaultStopsTheSearchEarlyWithTheSameVerdict) {
  const BearingGeometry g = CatalogBearing("6205");
  const BearingFrequencies f = ComputeFrequencies(g, 29.95);
  FaultSignalSpec s;
  s.fs_hz = 48000;
  s.duration_s = 2.0;
  s.rate_hz = f.bpfo_hz * 0.99;
  s.resonance_hz = 12000;
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  s.shaft_hz = f.shaft_hz;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  const Record r = spallkit::testing::MakeFaultRecord(s);
  const Diagnosis staged = Diagnose(r, g, f.shaft_hz);
  DiagnoseOptions all;
  all.first_bands = 0;
  const Diagnosis full = Diagnose(r, g, f.shaft_hz, all);
  SCOPED_TRACE(staged.BriefReport() + full.BriefReport());
  EXPECT_EQ(full.candidate_bands, 95);
  EXPECT_EQ(full.searched_bands, 95);
  EXPECT_EQ(staged.candidate_bands, 95);
  EXPECT_DOUBLE_EQ(staged.multiplicity, 4.0 * 95);
  EXPECT_DOUBLE_EQ(full.multiplicity, 4.0 * 95);
  EXPECT_TRUE(staged.searched_bands == 16 || staged.searched_bands == 95) << staged.searched_bands;
  EXPECT_EQ(staged.verdict, Verdict::kOuterRace);
  EXPECT_EQ(full.verdict, Verdict::kOuterRace);
  ASSERT_NE(staged.Best(), nullptr);
  EXPECT_NEAR(staged.Best()->fundamental_hz / s.rate_hz, 1.0, 1e-3);
}

// As Diagnose.HealthyRecordsFalseAlarmRateWithinDesign, at 48 kHz where the staged search is
// active (64 candidates, 16 in the first stage; a 0.5 s record has no narrower ones: their SES
// would be shorter than the floor window): a record without a detected family is searched in full,
// and the false-alarm rate stays within the design.
TEST(DiagnoseBands, HealthyRecordsAt48kHzFalseAlarmRateWithinDesign) {
  const BearingGeometry g = CatalogBearing("6205");
  const BearingFrequencies f = ComputeFrequencies(g, 29.95);
  const int kRecords = 60;
  for (double alpha : {0.2, 1e-3}) {
    int alarms = 0, alarms_lines = 0, searched = 0;
    DiagnoseOptions o;
    o.false_alarm_probability = alpha;
    for (int seed = 1; seed <= kRecords; ++seed) {
      FaultSignalSpec s;
      s.fs_hz = 48000;
      s.duration_s = 0.5;
      s.noise_rms = 1.0;
      s.seed = 7000 + seed;
      const Diagnosis d = Diagnose(spallkit::testing::MakeFaultRecord(s), g, f.shaft_hz, o);
      if (d.verdict != Verdict::kHealthy) ++alarms;
      if (d.verdict == Verdict::kHealthy) {
        EXPECT_EQ(d.searched_bands, 64);
      }
      searched = d.candidate_bands;
      FaultSignalSpec t = s;
      t.seed = 9000 + seed;
      t.noise_rms = 0.4;
      t.shaft_hz = f.shaft_hz;
      t.shaft_amplitude = 0.5;
      t.mains_amplitude = 0.2;
      t.extra_line_hz = f.bpfo_hz;
      t.extra_line_amplitude = 0.3;
      if (Diagnose(spallkit::testing::MakeFaultRecord(t), g, f.shaft_hz, o).verdict !=
          Verdict::kHealthy)
        ++alarms_lines;
    }
    EXPECT_EQ(searched, 64);
    const double margin = 3.0 * std::sqrt(alpha * (1 - alpha) / kRecords);
    EXPECT_LE(alarms / double(kRecords), alpha + margin) << "alpha " << alpha;
    EXPECT_LE(alarms_lines / double(kRecords), alpha + margin) << "alpha " << alpha;
    if (alpha < 0.01) {
      EXPECT_EQ(alarms, 0);
      EXPECT_EQ(alarms_lines, 0);
    }
  }
}

}  // namespace
}  // namespace spallkit::dsp
