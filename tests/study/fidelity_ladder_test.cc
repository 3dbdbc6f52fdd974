// The fidelity ladder's books (study/fidelity_ladder.h): a rung run twice is deterministic, so
// against itself every error is exactly 0, while the kinematics it measured are the rolling
// bearing's (cage near pure rolling); options with fewer than two rungs are refused.
#include "study/fidelity_ladder.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/bearing/scene.h"

namespace spallkit::study {
namespace {

using sim::LoadScene;

Scene LumpedScene(std::vector<std::string> sets) {
  sets.insert(sets.begin(), "model.fidelity=lumped");
  return LoadScene(std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml",
                   sets);
}

TEST(FidelityLadderTest, ARungAgainstItselfHasNoErrorAndOptionsAreChecked) {
  LadderOptions o;
  o.scenes.emplace_back("paper",
                        LumpedScene({"operation.speed_rpm=6000", "operation.ramp_s=0.002"}));
  o.rungs = {{Fidelity::kLumped, 0.0}, {Fidelity::kLumped, 0.0}};
  o.duration_s = 0.06;
  const LadderSummary s = RunFidelityLadder(o);
  ASSERT_EQ(s.runs.size(), 2u);
  ASSERT_EQ(s.rungs.size(), 2u);
  for (const LadderRungSummary& r : s.rungs) {
    EXPECT_EQ(r.f_b, 0.0);
    EXPECT_EQ(r.f_c, 0.0);
    EXPECT_EQ(r.cage_slip, 0.0);
    EXPECT_EQ(r.rms, 0.0);
    EXPECT_EQ(r.ses_correlation, 0.0);
    EXPECT_GT(r.wall_s_per_simulated_s, 0.0);
  }
  const LadderMetrics& m = s.runs[0].metrics;
  const BearingGeometry& g = o.scenes[0].second.geometry.bearing;
  const double fc_pure = 0.5 * 100.0 * (1.0 - g.element_diameter_m / g.pitch_diameter_m);
  EXPECT_NEAR(m.f_c_hz / fc_pure, 1.0, 0.02);  // after only 20 ms with the 2 ms ramp
  EXPECT_GT(m.f_b_hz, 0.0);
  EXPECT_GT(m.harris_jones_load_n, 0.0);
  EXPECT_GT(m.ses.size(), 10u);  // 5 f_b at the 17 Hz resolution of 60 ms
  std::printf("%s", s.Table().c_str());
  o.rungs.pop_back();
  EXPECT_THROW(RunFidelityLadder(o), InputError);
}

// Against the hybrid at 2 mm (its FE housing has many modes, the lumped ring one) the lumped
// rung's signal differs: its SES error is strictly between 0 and 1, and the hybrid, the
// reference, has none.
TEST(FidelityLadderTest, LumpedSesDiffersFromTheHybridsButStaysCorrelated) {
  LadderOptions o;
  o.scenes.emplace_back("paper",
                        LumpedScene({"operation.speed_rpm=6000", "operation.ramp_s=0.002"}));
  o.rungs = {{Fidelity::kLumped, 0.0}, {Fidelity::kHybrid, 2e-3}};
  o.duration_s = 0.06;
  const LadderSummary s = RunFidelityLadder(o);
  std::printf("%s", s.Table().c_str());
  EXPECT_GT(s.rungs[0].ses_correlation, 0.0);
  EXPECT_LT(s.rungs[0].ses_correlation, 1.0);
  EXPECT_EQ(s.rungs[1].ses_correlation, 0.0);
}

}  // namespace
}  // namespace spallkit::study
