// Roller spall versus cage and outer-race combs: the joint explanation of the SES lines
// (dsp/explain.h). The shipped sample record (datasets/samples, a textbook N205EM roller spall)
// must be called rolling_element with its measured f_b and f_c; synthetic roller defects with
// strong cage modulation (N205EM: f_b = 13.85 f_c, the whole roller "forest" lies within ~1 % of
// cage harmonics and f_b - f_c within 1.2 % of BPFO) must not be called cage or outer race; a pure
// cage comb must still be called cage, load-zone-free outer-race impulses outer race, and noise
// healthy at the design rate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/bearing.h"
#include "core/record_io.h"
#include "dsp/diagnose.h"
#include "dsp/explain.h"
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

TEST(SampleRecord, RollerSpallIsRollingElementWithMeasuredRates) {
  const std::string path =
      std::string(SPALLKIT_SOURCE_DIR) + "/datasets/samples/n205em_roller_defect_1200rpm.csv";
  const Record r = ReadRecord(path);
  const Diagnosis d = Diagnose(r, CatalogBearing("N205EM"), 1200 / 60.0);
  SCOPED_TRACE(d.BriefReport());
  EXPECT_EQ(d.verdict, Verdict::kRollingElement);
  // scripts/make_sample_record.py: f_b = 2 BSF = 115.0849 Hz (zero-mean 0.8 % jitter), f_c =
  // 8.3117 Hz (the load-zone modulation rate).
  ASSERT_TRUE(d.measured_f_b_hz.has_value());
  EXPECT_NEAR(*d.measured_f_b_hz / 115.0849, 1.0, 0.005);
  ASSERT_TRUE(d.measured_f_c_hz.has_value());
  EXPECT_NEAR(*d.measured_f_c_hz / 8.3117, 1.0, 0.02);
  // The roller explains the cage line and the f_b - f_c ~ BPFO lines: nothing else is left.
  EXPECT_FALSE(Find(d, FaultComponent::kCage).detected);
  EXPECT_FALSE(Find(d, FaultComponent::kOuterRace).detected);
  bool cage_line_claimed = false;
  for (const auto& e : d.explained_lines)
    cage_line_claimed |= e.by == FaultComponent::kRollingElement &&
                         std::abs(e.freq_hz - 8.3117) < 2.0 * d.ses.resolution_hz;
  EXPECT_TRUE(cage_line_claimed);
}

enum class Kind { kRoller, kCage, kOuter };

// 20 kHz, a 5.4 kHz resonance, shaft and mains distractors; no impulses yet.
FaultSignalSpec BaseSpec(double shaft_hz, unsigned seed, double duration_s) {
  FaultSignalSpec s;
  s.fs_hz = 20000;
  s.duration_s = duration_s;
  s.shaft_hz = shaft_hz;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  s.noise_rms = 0.4;
  s.amplitude = 3.0;
  s.resonance_hz = 5400;
  s.seed = seed;
  return s;
}

// 2 s (or `duration_s`) of BaseSpec with a roller, cage or outer-race impulse train; 1 % slip on
// every rate.
Record Synthetic(const char* bearing,
                 double rpm,
                 Kind kind,
                 unsigned seed,
                 double* rate_hz,
                 double* cage_hz,
                 double duration_s = 2.0) {
  const BearingFrequencies f = ComputeFrequencies(CatalogBearing(bearing), rpm / 60.0);
  FaultSignalSpec s = BaseSpec(f.shaft_hz, seed, duration_s);
  switch (kind) {
    case Kind::kRoller:
      s.rate_hz = f.f_b_hz * 0.99;
      s.modulation_hz = f.cage_hz * 0.99;  // the spall orbits with the cage through the load zone
      s.modulation_depth = 0.9;            // strong: a large f_c line and +/- f_c sidebands
      break;
    case Kind::kCage:
      s.rate_hz = f.cage_hz * 0.99;  // an f_c impulse train: a dense comb, no f_b
      break;
    case Kind::kOuter:
      s.rate_hz = f.bpfo_hz * 0.99;  // fixed fault, no load-zone modulation
      break;
  }
  *rate_hz = s.rate_hz;
  *cage_hz = f.cage_hz * 0.99;
  Record r;
  r.samples = MakeFaultSignal(s);
  r.sample_rate_hz = s.fs_hz;
  r.source = "synthetic";
  return r;
}

struct Case {
  const char* bearing;
  double rpm;
  Kind kind;
  // 1 s records (1 Hz bins, the main job's simulated record) are the hard case for telling a
  // roller forest from a cage comb: N205EM's f_b / f_c = 13.85 is 1.1 % from 14, and the rates
  // measured from a few lines scatter by up to 1 %.
  double duration_s = 2.0;
};

std::string Name(const Case& c) {
  const char* kinds[] = {"roller", "cage", "outer"};
  return std::string(c.bearing) + " " + std::to_string(static_cast<int>(c.rpm)) + " rpm " +
         kinds[static_cast<int>(c.kind)] + " " + std::to_string(c.duration_s) + " s";
}

class JointExplanationCases : public ::testing::TestWithParam<Case> {};

TEST_P(JointExplanationCases, VerdictAndRates) {
  const Case c = GetParam();
  for (unsigned seed : {1u, 2u}) {
    double rate = 0.0, cage = 0.0;
    const Record r = Synthetic(c.bearing, c.rpm, c.kind, seed, &rate, &cage, c.duration_s);
    const Diagnosis d = Diagnose(r, CatalogBearing(c.bearing), c.rpm / 60.0);
    SCOPED_TRACE(Name(c) + ", seed " + std::to_string(seed) + "\n" + d.BriefReport());
    switch (c.kind) {
      case Kind::kRoller:
        EXPECT_EQ(d.verdict, Verdict::kRollingElement);
        ASSERT_TRUE(d.measured_f_b_hz.has_value());
        EXPECT_NEAR(*d.measured_f_b_hz / rate, 1.0, 3e-3);
        ASSERT_TRUE(d.measured_f_c_hz.has_value());
        // f_c from the +/- f_c sideband pairs: its error scales with the bin width 1 / T.
        EXPECT_NEAR(*d.measured_f_c_hz / cage, 1.0, 0.02 * 2.0 / c.duration_s);
        EXPECT_FALSE(Find(d, FaultComponent::kCage).detected);
        EXPECT_FALSE(Find(d, FaultComponent::kOuterRace).detected);
        break;
      case Kind::kCage:
        if (c.duration_s * cage < DiagnoseOptions{}.min_periods) {
          // Too few cage turns to claim the family (DiagnoseOptions::min_periods): reported with
          // its evidence, not claimed.
          EXPECT_NE(d.verdict, Verdict::kCage);
          EXPECT_NE(Find(d, FaultComponent::kCage).reason.find("not claimed"), std::string::npos);
          // Nor is the roller comb inside an f_c impulse train a roller spall, also where the
          // record cannot resolve the two (ordered by harmonic evidence, RollerCageSeparation).
          EXPECT_NE(d.verdict, Verdict::kRollingElement);
          break;
        }
        EXPECT_EQ(d.verdict, Verdict::kCage);
        EXPECT_FALSE(d.measured_f_b_hz.has_value());
        ASSERT_TRUE(d.measured_f_c_hz.has_value());
        EXPECT_NEAR(*d.measured_f_c_hz / rate, 1.0, 0.01);
        break;
      case Kind::kOuter:
        EXPECT_EQ(d.verdict, Verdict::kOuterRace);
        EXPECT_NEAR(d.Best()->fundamental_hz / rate, 1.0, 1e-3);
        break;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bearings,
                         JointExplanationCases,
                         ::testing::Values(Case{"N205EM", 900, Kind::kRoller},
                                           Case{"N205EM", 1200, Kind::kRoller},
                                           Case{"N205EM", 1800, Kind::kRoller},
                                           Case{"N205EM", 2400, Kind::kRoller},
                                           Case{"6205", 1200, Kind::kRoller},
                                           Case{"6205", 1797, Kind::kRoller},
                                           Case{"6203", 2400, Kind::kRoller},
                                           Case{"6203", 1750, Kind::kRoller},
                                           Case{"N205EM", 1200, Kind::kCage},
                                           Case{"N205EM", 2400, Kind::kCage},
                                           Case{"6205", 1200, Kind::kCage},
                                           Case{"6205", 1797, Kind::kCage},
                                           Case{"6203", 1750, Kind::kCage},
                                           Case{"N205EM", 1200, Kind::kOuter},
                                           Case{"6205", 1797, Kind::kOuter},
                                           Case{"6203", 1750, Kind::kOuter},
                                           Case{"N205EM", 1200, Kind::kRoller, 1.0},
                                           Case{"N205EM", 1800, Kind::kRoller, 1.0},
                                           Case{"6205", 1797, Kind::kRoller, 1.0},
                                           Case{"N205EM", 1200, Kind::kCage, 1.0},
                                           Case{"N205EM", 1800, Kind::kCage, 1.0},
                                           Case{"6205", 1797, Kind::kCage, 1.0}));

// The rolling-element family's spin series (docs/DIAGNOSIS.md, "Detection statistic"): a roller
// spall whose outer- and inner-race impacts differ (every other impulse at 0.4 of the others)
// repeats at BSF = f_b / 2, and the lines (k - 1/2) f_b join the family rule. Without load-zone
// modulation there are no f_c sidebands, so only the spin-series rule (three lines, of both
// series) can call it; with the impacts alike (no spin series) the same record is not a roller
// spall, as before the rule. N205EM, 1200 rpm, 2 s, 1 % slip, shaft and mains lines.
TEST(SpinSeries, RollerSpallWithoutSidebandsIsCalledByItsTwoSeries) {
  const BearingFrequencies f = ComputeFrequencies(CatalogBearing("N205EM"), 1200 / 60.0);
  for (unsigned seed : {1u, 2u}) {
    for (double ratio : {0.4, 1.0}) {
      FaultSignalSpec s = BaseSpec(f.shaft_hz, seed, 2.0);
      s.rate_hz = f.f_b_hz * 0.99;
      s.alternate_ratio = ratio;
      Record r;
      r.samples = MakeFaultSignal(s);
      r.sample_rate_hz = s.fs_hz;
      const Diagnosis d = Diagnose(r, CatalogBearing("N205EM"), 1200 / 60.0);
      SCOPED_TRACE("seed " + std::to_string(seed) + ", ratio " + std::to_string(ratio) + "\n" +
                   d.BriefReport());
      const FamilyDetection& roller = Find(d, FaultComponent::kRollingElement);
      int half_orders = 0;
      for (const auto& l : roller.lines) half_orders += l.line.half_order && l.significant;
      // No load-zone modulation: fewer significant sidebands than the sideband rule needs (a
      // chance line may pass the line test).
      EXPECT_LT(roller.significant_sidebands, roller.min_sidebands);
      if (ratio < 1.0) {
        EXPECT_EQ(d.verdict, Verdict::kRollingElement);
        EXPECT_GE(half_orders, 1);
        ASSERT_TRUE(d.measured_f_b_hz.has_value());
        EXPECT_NEAR(*d.measured_f_b_hz / s.rate_hz, 1.0, 3e-3);
      } else {
        EXPECT_EQ(half_orders, 0);
        EXPECT_NE(d.verdict, Verdict::kRollingElement);
      }
    }
  }
}

// The wider sweep of docs/DIAGNOSIS.md ("Joint explanation"): 2 s records, 1 % slip on every
// rate, 4 seeds, roller / cage / outer-race signals on the N205EM at 600-2400 rpm, the 6205 at
// 900-2400 and the 6203 at 1200-2400. Right: the roller spall rolling_element, the outer race
// outer_race, the cage comb cage, or where the record holds too few cage turns to claim it
// (DiagnoseOptions::min_periods) anything but cage and rolling_element. The misclassified
// records are printed.
TEST(JointExplanation, WiderSweepMisclassifiesOnlyTheDocumentedFew) {
  struct Speed {
    const char* bearing;
    double rpm;
  };
  const Speed speeds[] = {{"N205EM", 600},
                          {"N205EM", 900},
                          {"N205EM", 1200},
                          {"N205EM", 1500},
                          {"N205EM", 1800},
                          {"N205EM", 2400},
                          {"6205", 900},
                          {"6205", 1200},
                          {"6205", 1797},
                          {"6205", 2400},
                          {"6203", 1200},
                          {"6203", 1750},
                          {"6203", 2400}};
  int records = 0, wrong = 0, unresolved = 0;
  for (const Speed& sp : speeds)
    for (Kind kind : {Kind::kRoller, Kind::kCage, Kind::kOuter})
      for (unsigned seed : {1u, 2u, 3u, 4u}) {
        double rate = 0.0, cage = 0.0;
        const Record r = Synthetic(sp.bearing, sp.rpm, kind, seed, &rate, &cage);
        const Diagnosis d = Diagnose(r, CatalogBearing(sp.bearing), sp.rpm / 60.0);
        bool right = false;
        switch (kind) {
          case Kind::kRoller:
            right = d.verdict == Verdict::kRollingElement;
            break;
          case Kind::kCage:
            right = 2.0 * cage < DiagnoseOptions{}.min_periods
                        ? d.verdict != Verdict::kCage && d.verdict != Verdict::kRollingElement
                        : d.verdict == Verdict::kCage;
            break;
          case Kind::kOuter:
            right = d.verdict == Verdict::kOuterRace;
            break;
        }
        ++records;
        unresolved += d.roller_cage.tested && !d.roller_cage.separable;
        if (!right) {
          ++wrong;
          std::printf("misclassified: %s, seed %u -> %s\n",
                      Name({sp.bearing, sp.rpm, kind}).c_str(),
                      seed,
                      VerdictName(d.verdict));
        }
      }
  std::printf(
      "%d of %d records misclassified; %d with roller and cage combs the record cannot "
      "separate\n",
      wrong,
      records,
      unresolved);
  EXPECT_EQ(records, 156);
  EXPECT_EQ(wrong, 0);
}

// Noise only on the N205EM: the re-tests after explaining away keep the false-alarm control (no
// family is detected first, so nothing is re-tested; with shaft and mains lines likewise).
TEST(JointExplanation, NoiseStaysHealthyAtTheDesignRate) {
  const BearingGeometry g = CatalogBearing("N205EM");
  const int kRecords = 40;
  int alarms = 0;
  for (int seed = 1; seed <= kRecords; ++seed) {
    FaultSignalSpec s;
    s.fs_hz = 20000;
    s.duration_s = 2.0;
    s.noise_rms = 1.0;
    s.shaft_hz = 20.0;
    s.shaft_amplitude = seed % 2 ? 0.5 : 0.0;
    s.mains_amplitude = seed % 2 ? 0.2 : 0.0;
    s.seed = 9000 + seed;
    Record r;
    r.samples = MakeFaultSignal(s);
    r.sample_rate_hz = s.fs_hz;
    if (Diagnose(r, g, 20.0).verdict != Verdict::kHealthy) ++alarms;
  }
  EXPECT_EQ(alarms, 0);  // design rate 1e-3 per record: P(any of 40) <= 4 %
}

// The explanation sets: a roller claims its harmonics, the 1 x BSF series, +/- m f_c sidebands
// and the modulation lines m f_c; a cage claims every harmonic up to the top.
TEST(JointExplanation, PredictedLines) {
  FamilyRates r;
  r.fundamental_hz = 100.0;
  r.sideband_hz = 7.0;
  const auto roller = PredictedLines(FaultComponent::kRollingElement, r, 2, 2, 1000.0);
  auto has = [&](const std::vector<double>& v, double f) {
    for (double x : v)
      if (std::abs(x - f) < 1e-9) return true;
    return false;
  };
  for (double f :
       {100.0, 93.0, 86.0, 107.0, 114.0, 200.0, 186.0, 50.0, 43.0, 57.0, 150.0, 7.0, 14.0})
    EXPECT_TRUE(has(roller, f)) << f;
  EXPECT_FALSE(has(roller, 21.0));  // modulation lines up to the harmonic count only
  EXPECT_EQ(roller.size(), 2u * 5u + 2u * 5u + 2u);
  FamilyRates c;
  c.fundamental_hz = 8.0;
  EXPECT_EQ(PredictedLines(FaultComponent::kCage, c, 5, 2, 100.0).size(), 12u);
  FamilyRates o;
  o.fundamental_hz = 100.0;
  o.sideband_hz = 10.0;
  EXPECT_EQ(PredictedLines(FaultComponent::kOuterRace, o, 3, 1, 1000.0).size(), 9u);
}

}  // namespace
}  // namespace spallkit::dsp
