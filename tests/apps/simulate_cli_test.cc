// Runs the built `spall simulate` as a batch job would (stderr to a file): whole progress lines,
// one per tenth of the run; a bad scene key is one line naming it, exit code 2, and no output
// file is left behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/run_spall.h"

namespace {

using spallkit::testing::RunSpall;
namespace fs = std::filesystem;

const std::string kScene =
    std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml";
// The hybrid model on the main job's 2 mm housing mesh: 10 ms take about a second.
const std::string kFast =
    " --set model.fidelity=hybrid --set mesh.size_mm=2.0 --set run.duration_s=0.01"
    " --set operation.ramp_s=0.002";

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// The progress lines of a run's stderr.
std::vector<std::string> ProgressLines(const std::string& err) {
  std::vector<std::string> progress;
  for (const auto& l : Lines(err))
    if (l.find(" %  steps ") != std::string::npos) progress.push_back(l);
  return progress;
}

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(SimulateCli, ProgressOnANonTerminalIsOneWholeLinePerTenth) {
  const fs::path dir = TempDir("spall_sim_progress_");
  const auto r = RunSpall("simulate " + kScene + " -o " + (dir / "run.h5").string() + kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "carriage returns in a log file";
  const std::vector<std::string> progress = ProgressLines(r.err);
  ASSERT_EQ(progress.size(), 10u) << r.err;
  EXPECT_NE(progress.front().find(" 10.0 %"), std::string::npos) << progress.front();
  EXPECT_NE(progress.back().find("100.0 %"), std::string::npos) << progress.back();
  EXPECT_TRUE(fs::exists(dir / "run.h5"));
  // Stopped at half-time and resumed: the resumed process reports from where it starts.
  const std::string half =
      " -o " + (dir / "half.h5").string() + kFast + " --set solver.checkpoint_interval_s=0.005";
  ASSERT_EQ(RunSpall("simulate " + kScene + half + " --stop-after-ms 5").code, 0);
  const auto resumed = RunSpall("simulate " + kScene + half + " --resume");
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  const std::vector<std::string> rest = ProgressLines(resumed.err);
  ASSERT_GE(rest.size(), 5u) << resumed.err;
  ASSERT_LE(rest.size(), 6u) << resumed.err;
  EXPECT_EQ(rest.front().find("  10.0 %"), std::string::npos) << rest.front();
  EXPECT_NE(rest.back().find("100.0 %"), std::string::npos) << rest.back();
  // --quiet: no progress at all.
  const auto q =
      RunSpall("simulate " + kScene + " -o " + (dir / "q.h5").string() + kFast + " --quiet");
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(q.err.find(" %  steps "), std::string::npos) << q.err;
  fs::remove_all(dir);
}

TEST(SimulateCli, UnknownSceneKeyIsOneLineNamingItAndNoOutput) {
  const fs::path dir = TempDir("spall_sim_badkey_");
  const auto r = RunSpall("simulate " + kScene + " -o " + (dir / "run.h5").string() + kFast +
                          " --set mesh.sise_mm=1.0");
  EXPECT_EQ(r.code, 2);
  ASSERT_EQ(Lines(r.err).size(), 1u) << r.err;
  EXPECT_NE(r.err.find("mesh.sise_mm"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(dir)) << "output left behind";
  fs::remove_all(dir);
}

}  // namespace
