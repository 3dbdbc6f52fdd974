// Scene limits (sim/bearing/scene_limits.h): the shipped scenes are inside; a scene outside is
// rejected by ParseScene with one line naming the key; the contact-stress limit sits at the
// bearing's static load rating.
#include "sim/bearing/scene_limits.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.h"
#include "sim/bearing/scene.h"

namespace spallkit::sim {
namespace {

std::string ErrorOf(const std::string& toml, const std::vector<std::string>& sets) {
  try {
    ParseScene(toml, "limits.toml", sets);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneLimits, DefaultSceneIsInside) {
  const Scene scene = ParseScene("", "default.toml");
  EXPECT_FALSE(FindSceneLimitViolation(scene).has_value());
  // 10 kN on the N205EM: about 2.3 GPa at the most loaded roller (Harris-Jones with 20 um
  // clearance, Hertz line contact).
  EXPECT_NEAR(PeakContactStress(scene) / 1e9, 2.3, 0.15);
}

// The load at which the scene limit starts is the bearing's static capacity: bisect it and
// compare with ISO 76's C0 = 44 (1 - D/D_pw) Z L_we D_we = 27.8 kN for the N205EM. ISO takes
// Stribeck's Q_max = 5 F_r / Z; at the limit the Harris-Jones roller load must be that same
// 5 C0 / Z (the same 4 GPa), reached at a higher radial load because Harris-Jones with 20 um
// clearance shares the load better (Z Q_max / F_r = 4.3 there).
TEST(SceneLimits, ContactStressLimitSitsAtTheStaticLoadRating) {
  Scene scene = ParseScene("", "default.toml");
  double lo = 1e3, hi = 1e5;
  for (int i = 0; i < 60; ++i) {
    scene.operation.radial_load_n = 0.5 * (lo + hi);
    (PeakContactStress(scene) > kStaticCapacityStressPa ? hi : lo) = scene.operation.radial_load_n;
  }
  const double c0 = 27.8e3;
  LoadDistributionOptions o;
  o.radial_load_n = lo;
  o.inner_ring_speed_rad_s = scene.operation.inner_ring_speed_rad_s;
  LoadDistributionSummary s;
  SolveLoadDistribution(o, scene.geometry.bearing, &s);
  EXPECT_NEAR(s.q_max_inner_n / (5.0 * c0 / 13.0), 1.0, 0.02) << s.q_max_inner_n;
  EXPECT_GT(lo, c0);
  EXPECT_LT(lo, 1.25 * c0) << lo;
}

TEST(SceneLimits, OverloadIsRejectedNamingTheKeyAndLine) {
  const std::string e = ErrorOf("[operation]\nradial_load_n = 50000.0\n", {});
  EXPECT_EQ(e.rfind("limits.toml:2: operation.radial_load_n:", 0), 0u) << e;
  EXPECT_NE(e.find("GPa"), std::string::npos) << e;
  EXPECT_EQ(ErrorOf("", {"operation.radial_load_n=25000.0"}), "no error");
}

// A load applied faster than the inner ring's radial period overshoots (an undamped oscillator
// under a step peaks at twice its static deflection), so the stress limit is checked at the
// dynamic peak: a step load half the slow-ramp limit is rejected, naming the ramp.
TEST(SceneLimits, SuddenLoadIsCheckedAtItsDynamicPeak) {
  Scene scene = ParseScene("", "default.toml");
  scene.operation.load_ramp_s = 0.0;
  EXPECT_DOUBLE_EQ(DynamicLoadFactor(scene), 2.0);
  double previous = 2.0;
  for (double ramp : {1e-5, 1e-4, 1e-3, 1e-2}) {
    scene.operation.load_ramp_s = ramp;
    const double f = DynamicLoadFactor(scene);
    EXPECT_LE(f, previous) << ramp;
    EXPECT_GE(f, 1.0) << ramp;
    previous = f;
  }
  EXPECT_LT(previous, 1.02);  // 10 ms: many radial periods of the ring

  EXPECT_EQ(ErrorOf("", {"operation.radial_load_n=20000", "operation.load_ramp_s=0.01"}),
            "no error");
  const std::string e = ErrorOf("", {"operation.radial_load_n=20000", "operation.load_ramp_s=0"});
  EXPECT_NE(e.find("operation.radial_load_n: 20000 N (peaking at 2 x when applied over "
                   "operation.load_ramp_s = 0 ms)"),
            std::string::npos)
      << e;
}

TEST(SceneLimits, HugeDurationRateAndMeshAreRejectedNamingTheKey) {
  const std::string duration = ErrorOf("", {"run.duration_s=1e308"});
  EXPECT_NE(duration.find("--set run.duration_s: must be at most 60 s"), std::string::npos)
      << duration;
  // 0.25 mm rollers and rings, 1 mm adapter elements, brass cage (3350 m/s): 3.35 MHz.
  const std::string rate = ErrorOf("", {"run.output_rate_hz=1e7"});
  EXPECT_NE(rate.find("run.output_rate_hz: 1e+07 Hz is above what the mesh resolves"),
            std::string::npos)
      << rate;
  EXPECT_EQ(ErrorOf("", {"run.output_rate_hz=3e6", "run.duration_s=0.001"}), "no error");
  const std::string mesh = ErrorOf("", {"mesh.size_mm=0.001"});
  EXPECT_NE(mesh.find("mesh.size_mm: about"), std::string::npos) << mesh;
}

TEST(SceneLimits, ResultMemoryEstimateCountsEveryRecordedColumn) {
  Scene scene = ParseScene("", "default.toml", {"run.duration_s=0.1", "run.output_rate_hz=10000"});
  // 1001 samples x (time 1 + contact 3 x 13 + cage 2 + rollers 2 x 13 + energy 8 + 2 sensors),
  // 8 bytes, doubled for the copy made when writing.
  EXPECT_DOUBLE_EQ(EstimatedResultBytes(scene), 2.0 * 8.0 * 1001 * (1 + 39 + 2 + 26 + 8 + 2));
  SceneLimits tight;
  tight.max_result_bytes = 1e6;
  const auto v = FindSceneLimitViolation(scene, tight);
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->key, "run.output_rate_hz");
}

}  // namespace
}  // namespace spallkit::sim
