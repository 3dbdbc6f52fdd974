// `spall bench diagnose` on the real measured records (CWRU 6205 at 0-2 hp, MFPT at six loads):
// every clear race-fault record gets its verdict, and the healthy record is healthy. Skipped when
// the measured records are absent (they are never copied into the repository).
//
// "Clear": Smith & Randall (2015) grade the CWRU 0.014 in outer-race records at 6 o'clock (197-200)
// as not diagnosable (their envelope spectra carry inner-race-like lines); they must not be
// called inner_race, and are not required to be outer_race.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "dsp/diagnosis_benchmark.h"
#include "tests/measured_data.h"

namespace spallkit::dsp {
namespace {

bool NotClear(const std::string& name) {
  return name.find("OR014at6") != std::string::npos;  // records 198, 199
}

TEST(DiagnosisMeasured, ClearRaceFaultsAndTheHealthyRecordAreRight) {
  const std::string manifest = spallkit::testing::MeasuredDataDir() + "/manifest.json";
  if (!std::filesystem::exists(manifest)) GTEST_SKIP() << "measured records not found";
  DiagnoseOptions options;
  options.threads = 1;
  const BenchmarkResult r = RunDiagnosisBenchmark(ReadBenchmarkManifest(manifest), options);
  int races = 0, mfpt_outer = 0;
  for (const BenchmarkRow& row : r.rows) {
    const std::string& name = row.record.name;
    ASSERT_TRUE(row.verdict.has_value()) << name << ": " << row.error;  // nothing refused
    const Verdict truth = row.record.truth;
    if (truth == Verdict::kHealthy) {
      EXPECT_EQ(*row.verdict, Verdict::kHealthy) << name;
    }
    if (truth == Verdict::kInnerRace || truth == Verdict::kOuterRace) {
      if (NotClear(name)) {
        EXPECT_NE(*row.verdict, Verdict::kInnerRace) << name;
        continue;
      }
      ++races;
      mfpt_outer += truth == Verdict::kOuterRace && name.rfind("mfpt", 0) == 0;
      EXPECT_EQ(VerdictName(*row.verdict), std::string(VerdictName(truth)))
          << name << ": " << row.evidence;
    }
  }
  EXPECT_EQ(races, 24);  // 13 inner race + 11 clear outer race, of which 6 MFPT
  EXPECT_EQ(mfpt_outer, 6);
  EXPECT_EQ(r.false_alarms, 0);
}

}  // namespace
}  // namespace spallkit::dsp
