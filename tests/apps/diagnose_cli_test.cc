// Runs the built `spall` binary: `frequencies` and `diagnose` outputs, and bad input -> one line on
// stderr with exit code 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/record_io.h"
#include "tests/apps/run_spall.h"
#include "tests/dsp/diagnose_test_signals.h"

namespace {

using Result = spallkit::testing::SpallResult;
using spallkit::testing::RunSpall;

std::string WriteSynthetic(const std::string& name, double seconds, bool fault) {
  spallkit::testing::FaultSignalSpec s;
  s.fs_hz = 12000;
  s.duration_s = seconds;
  s.amplitude = 3.0;
  s.noise_rms = 0.4;
  if (fault) s.rate_hz = 107.36 * 0.99;  // 6205 BPFO at 1797 rpm, 1 % slip
  const auto x = spallkit::testing::MakeFaultSignal(s);
  std::vector<double> t(x.size());
  for (size_t i = 0; i < t.size(); ++i) t[i] = i / s.fs_hz;
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  spallkit::WriteCsvRecord(path, {{"time_s", t}, {"accel_g", x}});
  return path;
}

TEST(FrequenciesCli, JsonHasOrdersAndTheFbConvention) {
  const Result r = RunSpall("frequencies --bearing N205EM --rpm 1200 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["frequencies"]["f_b"]["hz"].get<double>(), 115.08, 0.01);
  EXPECT_NEAR(j["frequencies"]["cage"]["hz"].get<double>(), 8.31, 0.005);
  EXPECT_NEAR(j["frequencies"]["f_b"]["hz"].get<double>(),
              2 * j["frequencies"]["roller_spin"]["hz"].get<double>(),
              1e-9);
  EXPECT_NEAR(j["frequencies"]["bpfo"]["order"].get<double>(), 108.052 / 20.0, 1e-4);
  EXPECT_EQ(j["families"]["inner_race"].size(), 9u);  // 3 harmonics + 6 sidebands
}

TEST(FrequenciesCli, ExplicitGeometryMatchesCatalogue) {
  const Result a = RunSpall("frequencies --bearing 6205 --rpm 1797 --json");
  const Result b = RunSpall(
      "frequencies --elements 9 --element-diameter-mm 7.94 --pitch-diameter-mm 39.04 --rpm 1797 "
      "--json");
  ASSERT_EQ(a.code, 0);
  ASSERT_EQ(b.code, 0);
  EXPECT_NEAR(nlohmann::json::parse(a.out)["frequencies"]["bpfi"]["hz"].get<double>(),
              nlohmann::json::parse(b.out)["frequencies"]["bpfi"]["hz"].get<double>(),
              1e-9);
}

TEST(DiagnoseCli, OuterRaceJsonAndPlots) {
  const std::string path = WriteSynthetic("spall_cli_outer.csv", 2.0, true);
  const std::string dir = (std::filesystem::temp_directory_path() / "spall_cli_plots").string();
  std::filesystem::remove_all(dir);
  const Result r =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json --plot-dir " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["verdict"], "outer_race");
  EXPECT_TRUE(j["faults"][0]["detected"].get<bool>());
  for (const char* f : {"ses.png", "spectrogram.png", "kurtogram.png"})
    EXPECT_GT(std::filesystem::file_size(std::filesystem::path(dir) / f), 10000u) << f;
  const Result text = RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797");
  EXPECT_EQ(text.code, 0);
  EXPECT_NE(text.out.find("VERDICT: outer_race"), std::string::npos) << text.out;
}

// --json-out writes the JSON object --json would print, while the text summary goes to stdout; it
// never overwrites the record, and a bad path fails before the analysis.
TEST(DiagnoseCli, JsonOutWritesTheJsonBesideTheTextSummary) {
  const std::string path = WriteSynthetic("spall_cli_outer_json_out.csv", 2.0, true);
  const std::string json_path =
      (std::filesystem::temp_directory_path() / "spall_cli_outer_json_out.json").string();
  std::filesystem::remove(json_path);
  const Result both =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json-out " + json_path);
  ASSERT_EQ(both.code, 0) << both.err;
  EXPECT_NE(both.out.find("VERDICT: outer_race"), std::string::npos) << both.out;
  const Result json = RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json");
  ASSERT_EQ(json.code, 0) << json.err;
  const std::string written = spallkit::testing::ReadTextFile(json_path);
  EXPECT_EQ(written, json.out);
  EXPECT_EQ(nlohmann::json::parse(written)["verdict"], "outer_race");

  const Result onto_record =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json-out " + path);
  EXPECT_EQ(onto_record.code, 2);
  EXPECT_NE(onto_record.err.find("--json-out"), std::string::npos) << onto_record.err;
  EXPECT_GT(std::filesystem::file_size(path), 100000u);  // the record is intact
  const Result no_folder =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json-out /nonexistent/r.json");
  EXPECT_EQ(no_folder.code, 2);
  EXPECT_NE(no_folder.err.find("/nonexistent"), std::string::npos) << no_folder.err;
}

// --from-s leaves out the record's start (a simulation's start-up): the analysis sees the rest.
TEST(DiagnoseCli, FromSecondsLeavesOutTheStart) {
  const std::string path = WriteSynthetic("spall_cli_outer_from.csv", 2.0, true);
  const Result whole = RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json");
  const Result cut =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json --from-s 0.5");
  ASSERT_EQ(whole.code, 0) << whole.err;
  ASSERT_EQ(cut.code, 0) << cut.err;
  const auto a = nlohmann::json::parse(whole.out), b = nlohmann::json::parse(cut.out);
  const double fs = a["record"]["sample_rate_hz"].get<double>();
  EXPECT_EQ(a["record"]["samples"].get<long>() - b["record"]["samples"].get<long>(),
            std::lround(0.5 * fs));
  EXPECT_EQ(b["verdict"], "outer_race");
}

// --min-band-hz keeps the band search above a frequency; a limit that leaves no band is refused.
TEST(DiagnoseCli, MinBandHzKeepsTheBandSearchAboveIt) {
  const std::string path = WriteSynthetic("spall_cli_outer_min_band.csv", 2.0, true);
  const Result r =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --json --min-band-hz 4000");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GE(j["band"]["low_hz"].get<double>(), 4000.0);
  EXPECT_EQ(j["settings"]["min_band_low_hz"].get<double>(), 4000.0);
  const Result none =
      RunSpall("diagnose " + path + " --bearing 6205 --rpm 1797 --min-band-hz 5900");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("starting at or above 5900 Hz"), std::string::npos) << none.err;
}

void ExpectError(const std::string& args, const std::string& needle) {
  const Result r = RunSpall(args);
  EXPECT_EQ(r.code, 2) << args;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << " -> " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(DiagnoseCli, BadInputIsOneLineAndExitCode2) {
  const std::string path = WriteSynthetic("spall_cli_noise.csv", 2.0, false);
  const std::string shortp = WriteSynthetic("spall_cli_short.csv", 0.1, false);
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 0", "--rpm must be > 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm -100", "--rpm must be > 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --fs 0", "--fs must be > 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --fs -5", "--fs must be > 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --fs 200", "above Nyquist");
  ExpectError("diagnose " + shortp + " --bearing 6205 --rpm 1797", "too few samples");
  ExpectError("diagnose /nonexistent/x.csv --bearing 6205 --rpm 1797", "x.csv");
  ExpectError("diagnose " + path + " --bearing X999 --rpm 1797", "unknown bearing");
  ExpectError("diagnose " + path + " --rpm 1797", "no bearing");
  ExpectError("frequencies --bearing 6205 --rpm 0", "--rpm must be > 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --threads 100000",
              "--threads must be in 0..64");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --from-s -1",
              "--from-s must be >= 0");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --from-s 2", "leaves no samples");
  ExpectError("diagnose " + path + " --bearing 6205 --rpm 1797 --min-band-hz -1",
              "--min-band-hz must be >= 0");
}

TEST(DiagnoseCli, RecordsThatCannotBeAnalysedAreRefusedOrFlagged) {
  const std::string dir = std::filesystem::temp_directory_path().string();
  std::vector<double> t(24000), zero(24000, 0.0), constant(24000, 1.5);
  for (size_t i = 0; i < t.size(); ++i) t[i] = i / 12000.0;
  spallkit::WriteCsvRecord(dir + "/spall_cli_zero.csv", {{"time_s", t}, {"accel_g", zero}});
  spallkit::WriteCsvRecord(dir + "/spall_cli_const.csv", {{"time_s", t}, {"accel_g", constant}});
  ExpectError("diagnose " + dir + "/spall_cli_zero.csv --bearing 6205 --rpm 1797", "constant");
  ExpectError("diagnose " + dir + "/spall_cli_const.csv --bearing 6205 --rpm 1797", "constant");
  // One 1e20 spike in a fault record: a report with finite statistics and a warning.
  const std::string path = WriteSynthetic("spall_cli_spike.csv", 2.0, true);
  spallkit::Record r = spallkit::ReadRecord(path);
  r.samples[3000] = 1e20;
  spallkit::WriteCsvRecord(dir + "/spall_cli_spike.csv", {{"time_s", t}, {"accel_g", r.samples}});
  const Result text =
      RunSpall("diagnose " + dir + "/spall_cli_spike.csv --bearing 6205 --rpm 1797");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("WARNING (verdict not confident)"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("inf"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("nan"), std::string::npos) << text.out;
  const Result json =
      RunSpall("diagnose " + dir + "/spall_cli_spike.csv --bearing 6205 --rpm 1797 --json");
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_FALSE(nlohmann::json::parse(json.out)["confident"].get<bool>());
}

}  // namespace
