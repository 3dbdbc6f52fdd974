// The labelled-record benchmark (dsp/diagnosis_benchmark.h): manifest parsing and its errors, the
// confusion matrix on a small synthetic folder, and `spall bench diagnose` on it.
#include "dsp/diagnosis_benchmark.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/record_io.h"
#include "tests/apps/run_spall.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace spallkit::dsp {
namespace {

namespace fs = std::filesystem;

void WriteCsv(const fs::path& path, const spallkit::testing::FaultSignalSpec& s) {
  const auto x = spallkit::testing::MakeFaultSignal(s);
  std::vector<double> t(x.size());
  for (size_t i = 0; i < t.size(); ++i) t[i] = i / s.fs_hz;
  spallkit::WriteCsvRecord(path.string(), {{"time_s", t}, {"accel_g", x}});
}

// A folder with an outer-race record, a healthy one and a constant one (refused), 6205 at
// 1797 rpm, and its manifest in the measured-data format.
fs::path MakeFolder() {
  const fs::path dir = fs::temp_directory_path() / "spallkit_diagnosis_benchmark_test";
  fs::create_directories(dir);
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 12000;
  s.duration_s = 2.0;
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  s.rate_hz = 107.36 * 0.99;
  WriteCsv(dir / "outer.csv", s);
  s.rate_hz = 0.0;
  s.shaft_hz = 29.95;
  s.shaft_amplitude = 0.5;
  s.mains_amplitude = 0.2;
  WriteCsv(dir / "healthy.csv", s);
  s.noise_rms = 0.0;
  s.shaft_amplitude = 0.0;
  s.mains_amplitude = 0.0;
  WriteCsv(dir / "constant.csv", s);
  const nlohmann::json geometry = {{"n_rolling_elements", 9},
                                   {"element_diameter_mm", 7.94},
                                   {"pitch_diameter_mm", 39.04},
                                   {"contact_angle_deg", 0.0}};
  nlohmann::json m = nlohmann::json::array();
  m.push_back({{"file", "outer.csv"},
               {"fault", "outer_race_6oclock"},
               {"rpm_from_file", 1797},
               {"bearing_geometry", geometry}});
  m.push_back({{"file", "healthy.csv"}, {"fault", "normal"}, {"rpm", 1797}, {"bearing", "6205"}});
  m.push_back({{"file", "constant.csv"}, {"fault", "healthy"}, {"rpm", 1797}, {"bearing", "6205"}});
  std::ofstream(dir / "manifest.json") << m.dump(1);
  return dir;
}

TEST(DiagnosisBenchmark, ConfusionMatrixOnASyntheticFolder) {
  const fs::path dir = MakeFolder();
  const auto set = ReadBenchmarkManifest((dir / "manifest.json").string());
  ASSERT_EQ(set.size(), 3u);
  EXPECT_EQ(set[0].truth, Verdict::kOuterRace);
  EXPECT_EQ(set[1].truth, Verdict::kHealthy);
  EXPECT_NEAR(set[0].shaft_hz, 1797 / 60.0, 1e-12);
  std::vector<std::pair<int, int>> progress;  // (done, total) after each record, refused included
  const BenchmarkResult r =
      RunDiagnosisBenchmark(set, {}, [&](int done, int total, const std::string& path) {
        progress.emplace_back(done, total);
        EXPECT_EQ(path, set[done - 1].path);
      });
  EXPECT_EQ(progress, (std::vector<std::pair<int, int>>{{1, 3}, {2, 3}, {3, 3}}));
  const int outer = static_cast<int>(Verdict::kOuterRace);
  const int healthy = static_cast<int>(Verdict::kHealthy);
  EXPECT_EQ(r.confusion[outer][outer], 1);
  EXPECT_EQ(r.confusion[healthy][healthy], 1);
  EXPECT_EQ(r.refused, 1);  // the constant record
  EXPECT_NE(r.rows[2].error.find("constant"), std::string::npos) << r.rows[2].error;
  EXPECT_EQ(r.correct, 2);
  EXPECT_EQ(r.false_alarms, 0);
  EXPECT_EQ(r.healthy_records, 2);
  const auto j = nlohmann::json::parse(r.ToJson());
  EXPECT_EQ(j["confusion"][outer][outer].get<int>(), 1);
  EXPECT_EQ(j["records"][0]["verdict"].get<std::string>(), "outer_race");
  EXPECT_NE(r.BriefReport().find("confusion matrix"), std::string::npos);
  // The cost per second of signal counts the two analysed 2 s records, not the refused one.
  EXPECT_NEAR(r.SignalSeconds(), 4.0, 1e-3);
  EXPECT_NEAR(j["signal_seconds_total"].get<double>(), 4.0, 1e-3);
  EXPECT_NE(r.BriefReport().find("ms per second of signal"), std::string::npos) << r.BriefReport();
}

TEST(DiagnosisBenchmark, ManifestErrorsNameTheEntryAndKey) {
  const fs::path dir = fs::temp_directory_path() / "spallkit_diagnosis_benchmark_bad";
  fs::create_directories(dir);
  auto expect_error = [&](const nlohmann::json& m, const std::string& fragment) {
    std::ofstream(dir / "manifest.json") << m.dump();
    try {
      ReadBenchmarkManifest((dir / "manifest.json").string());
      ADD_FAILURE() << "accepted: " << m.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  expect_error(nlohmann::json::array(), "no records");
  expect_error({{{"file", "a.csv"}, {"fault", "wobble"}, {"rpm", 1}, {"bearing", "6205"}}},
               "'fault' = 'wobble'");
  expect_error({{{"file", "a.csv"}, {"fault", "ball"}, {"bearing", "6205"}}}, "'rpm'");
  expect_error({{{"file", "a.csv"}, {"fault", "ball"}, {"rpm", 1200}}}, "record 0");
  expect_error({{{"file", "a.csv"}, {"fault", "ball"}, {"rpm", 1200}, {"bearing", "nope"}}},
               "record 0");
}

TEST(BenchDiagnoseCli, PrintsTheMatrixAndJson) {
  const fs::path dir = MakeFolder();
  const auto r = spallkit::testing::RunSpall("bench diagnose " + dir.string() + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["correct"].get<int>(), 2);
  EXPECT_EQ(j["refused"].get<int>(), 1);
  const auto bad = spallkit::testing::RunSpall("bench diagnose " + (dir / "nothere").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("not a directory"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace spallkit::dsp
