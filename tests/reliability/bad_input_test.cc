// Runs every case of tests/reliability/bad_input.corpus against the built `spall` (the format and
// the checks are described at the top of that file): exit code, one `spall:` line on stderr with
// the expected fragment, no hang, no output file left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/run_spall.h"

namespace {

namespace fs = std::filesystem;

const std::string kSource = SPALLKIT_SOURCE_DIR;
const std::string kData = kSource + "/tests/reliability/data";
constexpr int kTimeoutSeconds = 60;
constexpr std::size_t kMaxLineChars = 600;

struct Case {
  std::string name;
  int exit_code = 0;
  std::string fragment;
  std::string args;
  int line = 0;
};

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

std::vector<Case> LoadCorpus() {
  std::vector<Case> cases;
  std::ifstream in(kSource + "/tests/reliability/bad_input.corpus");
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (Trim(line).empty() || Trim(line)[0] == '#') continue;
    std::vector<std::string> f;
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {  // the arguments may contain '|'
      const auto bar = line.find('|', start);
      if (bar == std::string::npos) break;
      f.push_back(Trim(line.substr(start, bar - start)));
      start = bar + 1;
    }
    f.push_back(Trim(line.substr(start)));
    if (f.size() != 4) {
      cases.push_back({"malformed_line_" + std::to_string(line_no), -1, line, "", line_no});
      continue;
    }
    cases.push_back({f[0], std::atoi(f[1].c_str()), f[2], f[3], line_no});
  }
  return cases;
}

void Replace(std::string* s, const std::string& from, const std::string& to) {
  for (std::size_t p = 0; (p = s->find(from, p)) != std::string::npos; p += to.size())
    s->replace(p, from.size(), to);
}

using spallkit::testing::RunSpall;

std::vector<std::string> NonEmptyLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!Trim(l).empty()) lines.push_back(l);
  return lines;
}

// Shown by gtest and ctest in place of the raw bytes of a Case.
void PrintTo(const Case& c, std::ostream* os) { *os << "bad_input.corpus:" << c.line; }

class BadInput : public ::testing::TestWithParam<Case> {};

// One clear line, the right exit code, no output left behind, no hang.
TEST_P(BadInput, Case) {
  const Case& c = GetParam();
  ASSERT_GE(c.exit_code, 0) << "bad_input.corpus:" << c.line << ": expected 4 '|' fields";
  const fs::path tmp =
      fs::temp_directory_path() / ("spall_bad_input_" + c.name + "_" + std::to_string(::getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  std::vector<fs::path> placed;  // files the placeholders put into {tmp}
  std::string args = c.args;
  if (args.find("{copy}") != std::string::npos) {
    fs::copy_file(kData + "/fast.toml", tmp / "scene.toml");
    placed.push_back(tmp / "scene.toml");
    Replace(&args, "{copy}", (tmp / "scene.toml").string());
  }
  if (args.find("{wide}") != std::string::npos) {
    std::ofstream w(tmp / "wide.csv");
    w << "time,accel\n0,1\n0.0001," << std::string(1 << 20, '7') << "x\n0.0002,3\n";
    placed.push_back(tmp / "wide.csv");
    Replace(&args, "{wide}", (tmp / "wide.csv").string());
  }
  Replace(&args, "{tmp}", tmp.string());
  Replace(&args, "{scene}", kData + "/fast.toml");
  Replace(&args, "{data}", kData);

  const spallkit::testing::SpallResult r = RunSpall(args, kTimeoutSeconds);
  const std::string context = "bad_input.corpus:" + std::to_string(c.line) + " spall " + args +
                              "\nstderr: " + r.err.substr(0, 2000);

  ASSERT_FALSE(r.timed_out()) << "no result within " << kTimeoutSeconds << " s (a hang)\n"
                              << context;
  EXPECT_EQ(r.code, c.exit_code) << context;
  if (c.exit_code == 0) {
    EXPECT_NE((r.out + r.err).find(c.fragment), std::string::npos) << context;
  } else {
    const auto lines = NonEmptyLines(r.err);
    ASSERT_EQ(lines.size(), 1u) << "expected one line on stderr\n" << context;
    EXPECT_EQ(lines[0].rfind("spall:", 0), 0u) << context;
    EXPECT_NE(lines[0].find(c.fragment), std::string::npos) << context;
    EXPECT_LE(lines[0].size(), kMaxLineChars) << context;
  }
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(tmp))
    if (std::find(placed.begin(), placed.end(), e.path()) == placed.end())
      left.push_back(e.path().filename().string());
  if (c.exit_code != 0) {
    EXPECT_TRUE(left.empty()) << "output left behind: " << left.front() << "\n" << context;
  }
  fs::remove_all(tmp);
}

INSTANTIATE_TEST_SUITE_P(Corpus,
                         BadInput,
                         ::testing::ValuesIn(LoadCorpus()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           return info.param.name;
                         });

// The corpus must not silently shrink to nothing (a wrong path would pass every TEST_P).
TEST(BadInputCorpus, HasCases) { EXPECT_GE(LoadCorpus().size(), 50u); }

}  // namespace
