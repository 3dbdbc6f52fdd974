// Sweep files: case enumeration (grid order, random draws per case), the defect-list keys, and
// one-line errors.
#include "study/sweep.h"

#include <gtest/gtest.h>

#include <set>

#include "core/error.h"

namespace spallkit::study {
namespace {

const std::string kScenes = std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes";

Sweep Parse(const std::string& text) { return ParseSweep(text, "test.toml", kScenes); }

const char* kGridSweep = R"(
[base]
scene = "paper-verification.toml"
[base.set]
"model.fidelity" = "hybrid"
[grid]
"defects.0.width_mm" = [0.8, 1.2, 1.6]
"operation.speed_rpm" = [1000.0, 1500.0]
[random]
cases = 2
seed = 7
"operation.radial_load_n" = { uniform = [5000.0, 15000.0] }
"defects.0.angle_deg" = { choice = [0.0, 90.0] }
)";

TEST(SweepTest, GridIsACartesianProductFirstKeySlowestWithDrawsPerPoint) {
  const Sweep s = Parse(kGridSweep);
  ASSERT_EQ(s.num_cases(), 3 * 2 * 2);
  EXPECT_EQ(s.ParameterKeys(),
            (std::vector<std::string>{"defects.0.width_mm",
                                      "operation.speed_rpm",
                                      "defects.0.angle_deg",
                                      "operation.radial_load_n"}));
  const std::vector<SweepCase> cases = MakeCases(s);
  // Cases 0,1 are the two draws at (0.8, 1000); 2,3 at (0.8, 1500); 4.. at 1.2 mm.
  EXPECT_EQ(cases[0].parameters[0].second.get<double>(), 0.8);
  EXPECT_EQ(cases[1].parameters[1].second.get<double>(), 1000.0);
  EXPECT_EQ(cases[2].parameters[1].second.get<double>(), 1500.0);
  EXPECT_EQ(cases[4].parameters[0].second.get<double>(), 1.2);
  EXPECT_EQ(cases[11].parameters[0].second.get<double>(), 1.6);
  EXPECT_EQ(cases[11].id, "case-00011");
  std::set<double> loads;
  for (const SweepCase& c : cases) {
    const double load = c.parameters[3].second.get<double>();
    EXPECT_GE(load, 5000.0);
    EXPECT_LT(load, 15000.0);
    loads.insert(load);
    const double angle = c.parameters[2].second.get<double>();
    EXPECT_TRUE(angle == 0.0 || angle == 90.0);
  }
  EXPECT_EQ(loads.size(), cases.size());  // independent draws
}

TEST(SweepTest, DrawsDependOnlyOnSeedAndCaseIndex) {
  const Sweep s = Parse(kGridSweep);
  // Case 9 made alone equals case 9 of the full list; another seed gives other draws.
  EXPECT_EQ(MakeCase(s, 9).parameters, MakeCases(s)[9].parameters);
  std::string other = kGridSweep;
  other.replace(other.find("seed = 7"), 8, "seed = 8");
  EXPECT_NE(MakeCase(Parse(other), 9).parameters[3].second, MakeCase(s, 9).parameters[3].second);
}

TEST(SweepTest, CaseSceneAppliesOverridesAndFixesOneSolverThread) {
  const Sweep s = Parse(kGridSweep);
  const SweepCase c = MakeCase(s, 5);
  const sim::Scene scene = CaseScene(s, c);
  EXPECT_EQ(scene.model.fidelity, sim::Fidelity::kHybrid);
  EXPECT_EQ(scene.solver.threads, 1);
  EXPECT_DOUBLE_EQ(scene.defects.at(0).width_m, 1.2e-3);
  EXPECT_NEAR(scene.operation.inner_ring_speed_rad_s, 1000.0 * 2 * M_PI / 60, 1e-9);
  EXPECT_EQ(scene.operation.radial_load_n, c.parameters[3].second.get<double>());
}

TEST(SweepTest, DefectCountAndRollersBuildTheDefectList) {
  const Sweep s = Parse(R"(
[base]
scene = "paper-verification.toml"
[grid]
"defects.count" = [0, 1, 3]
"defects.0.width_mm" = [2.0]
)");
  ASSERT_EQ(s.num_cases(), 3);
  const sim::Scene healthy = CaseScene(s, MakeCase(s, 0));
  EXPECT_TRUE(healthy.defects.empty());  // the width key names no defect: skipped
  const sim::Scene three = CaseScene(s, MakeCase(s, 2));
  ASSERT_EQ(three.defects.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(three.defects[i].roller, i);
    EXPECT_DOUBLE_EQ(three.defects[i].depth_m, 0.59e-3);  // copied from the base defect
  }
  EXPECT_DOUBLE_EQ(three.defects[0].width_m, 2.0e-3);
  EXPECT_DOUBLE_EQ(three.defects[1].width_m, 1.38e-3);

  const Sweep r = Parse(R"(
[base]
scene = "paper-verification.toml"
[random]
cases = 8
"defects.rollers" = { choice = [[], [0, 6]] }
"defects.*.width_mm" = { uniform = [0.5, 2.0] }
)");
  int healthy_cases = 0;
  for (int i = 0; i < r.num_cases(); ++i) {
    const sim::Scene scene = CaseScene(r, MakeCase(r, i));
    healthy_cases += scene.defects.empty();
    if (!scene.defects.empty()) {
      ASSERT_EQ(scene.defects.size(), 2u);
      EXPECT_EQ(scene.defects[1].roller, 6);
      // "defects.*" keys reach every defect.
      EXPECT_EQ(scene.defects[0].width_m, scene.defects[1].width_m);
      EXPECT_GE(scene.defects[1].width_m, 0.5e-3);
    }
  }
  EXPECT_GT(healthy_cases, 0);
  EXPECT_LT(healthy_cases, r.num_cases());
}

// "defects.*.KEY" sets KEY on every defect of the case; a base scene that lists no [[defects]]
// has the scene's default one (the paper's spall), which it then sets.
TEST(SweepTest, EveryDefectKeyReachesTheDefaultSpall) {
  const Sweep s = Parse("[base]\nscene = \"" + std::string(SPALLKIT_SOURCE_DIR) +
                        "/tests/reliability/data/fast.toml\"\n[grid]\n\"defects.*.width_mm\" = "
                        "[0.5, 2.0]\n");
  for (int i = 0; i < 2; ++i) {
    const sim::Scene scene = CaseScene(s, MakeCase(s, i));
    ASSERT_EQ(scene.defects.size(), 1u);
    EXPECT_DOUBLE_EQ(scene.defects[0].width_m, i == 0 ? 0.5e-3 : 2.0e-3);
  }
}

TEST(SweepTest, TomlValueTextRoundTripsDoublesAndKeepsThemFloats) {
  EXPECT_EQ(TomlValueText(1000.0), "1000.0");
  EXPECT_EQ(TomlValueText(0.1), "0.1");
  EXPECT_EQ(TomlValueText(3), "3");
  EXPECT_EQ(TomlValueText("hybrid"), "\"hybrid\"");
  EXPECT_EQ(TomlValueText(nlohmann::json::array({0, 3})), "[0, 3]");
  const double x = 1.0 / 3.0;
  EXPECT_EQ(std::stod(TomlValueText(x)), x);
}

void ExpectError(const std::string& text, const std::string& fragment) {
  try {
    Parse(text);
    ADD_FAILURE() << "no error for: " << text;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(SweepTest, BadSweepsGiveOneLineNamingFileLineAndKey) {
  const std::string base = "[base]\nscene = \"paper-verification.toml\"\n";
  ExpectError("[grid]\nx = [1]\n", "[base]");
  ExpectError(base + "[grid]\n\"defects.0.width_mm\" = []\n",
              "test.toml:4: grid.defects.0.width_mm");
  ExpectError(base + "[random]\n\"operation.speed_rpm\" = { gauss = [1, 2] }\n",
              "unknown distribution 'gauss'");
  ExpectError(base + "[random]\n\"operation.speed_rpm\" = { uniform = [2.0, 1.0] }\n", "lo <= hi");
  ExpectError(base + "[grid]\n\"operation.speed_rmp\" = [1000.0]\n", "speed_rmp");
  ExpectError(base + "[grid]\n\"defects.count\" = [-1]\n", "integer >= 0");
  ExpectError(base + "[gird]\n", "unknown table");
  ExpectError("[base]\nscene = \"missing.toml\"\n", "missing.toml: cannot open");
}

}  // namespace
}  // namespace spallkit::study
