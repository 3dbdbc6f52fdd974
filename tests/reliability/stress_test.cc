// A fixed-seed subset of `spall stress` (sim/stress/stress.h): every drawn scene is either rejected
// up front with a one-line reason or runs clean; the draw is reproducible; the run checks can fail.
#include "sim/stress/stress.h"

#include <gtest/gtest.h>

#include <string>

namespace spallkit::sim::stress {
namespace {

// Short runs on a coarse housing mesh (1.5-2.5 mm):
// about half a second per scene.
StressOptions Subset() {
  StressOptions o;
  o.scenes = 10;
  o.seed = 1;
  o.max_duration_s = 0.004;
  o.min_mesh_size_mm = 1.5;
  o.max_mesh_size_mm = 2.5;
  return o;
}

TEST(Stress, FixedSeedSubsetHasNoFailure) {
  const StressSummary s = RunStress(Subset());
  ASSERT_EQ(s.cases.size(), 10u);
  for (const StressCase& c : s.cases)
    EXPECT_NE(c.outcome, StressOutcome::kFailed)
        << "scene " << c.index << ": " << StressOutcomeName(c.outcome) << " " << c.reason << "\n"
        << s.Table();
  // The draw covers both outcomes (else the subset would test nothing).
  EXPECT_GE(s.passed, 3) << s.Table();
  EXPECT_GE(s.rejected, 1) << s.Table();
  for (const StressCase& c : s.cases) {
    if (c.outcome != StressOutcome::kRejected) continue;
    EXPECT_FALSE(c.reason.empty());
    EXPECT_EQ(c.reason.find('\n'), std::string::npos) << c.reason;
  }
}

TEST(Stress, DrawIsReproducibleAndSeedDependent) {
  const StressOptions o = Subset();
  const StressCase a = DrawScene(o, 3), b = DrawScene(o, 3);
  EXPECT_EQ(a.overrides, b.overrides);
  StressOptions other = o;
  other.seed = 2;
  EXPECT_NE(DrawScene(other, 3).overrides, a.overrides);
  EXPECT_NE(a.Reproduce().find("--set 'model.fidelity=\"hybrid\"'"), std::string::npos)
      << a.Reproduce();
}

// With bounds no run can meet, the checks must report a failure: they are live.
TEST(Stress, RunChecksCatchAnEnergyErrorAndAnOverlap) {
  const StressOptions o = Subset();
  StressCase ok;  // the first passing scene with a measurable energy error
  for (int i = 0; i < o.scenes; ++i) {
    ok = DrawScene(o, i);
    RunScene(o, &ok);
    if (ok.outcome == StressOutcome::kPassed && ok.energy_error_percent > 1e-6) break;
  }
  ASSERT_EQ(ok.outcome, StressOutcome::kPassed) << "no passing scene in the subset";
  StressOptions strict = o;
  strict.max_energy_error_percent = 1e-12;
  StressCase energy = DrawScene(strict, ok.index);
  RunScene(strict, &energy);
  EXPECT_EQ(energy.outcome, StressOutcome::kFailed);
  EXPECT_NE(energy.reason.find("energy balance error"), std::string::npos) << energy.reason;
  strict = o;
  strict.max_overlap_fraction = 1e-12;
  StressCase overlap = DrawScene(strict, ok.index);
  RunScene(strict, &overlap);
  EXPECT_EQ(overlap.outcome, StressOutcome::kFailed);
  EXPECT_NE(overlap.reason.find("overlaps a race"), std::string::npos) << overlap.reason;
}

TEST(Stress, InvalidOptionsAreRefused) {
  StressOptions o;
  o.scenes = 0;
  std::string why;
  EXPECT_FALSE(o.Validate(&why));
  EXPECT_NE(why.find("scenes"), std::string::npos);
  o = StressOptions();
  o.fidelity = Fidelity::kAuto;
  EXPECT_FALSE(o.Validate(&why));
}

}  // namespace
}  // namespace spallkit::sim::stress
