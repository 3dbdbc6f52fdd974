// The lubricant traction law (sim/contact/traction.h) against its analytic curve, its explicit
// step's stability, the scene keys that select it, and what it does to the default scene's
// defective roller at the paper's friction (docs/PAPER.md, "The main job").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/bearing/fidelity_choice.h"
#include "sim/bearing/roller_sliding.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"
#include "sim/contact/traction.h"

namespace spallkit::sim {
namespace {

using contact::EhlTraction;

// mu(s) = Lambda (1 - exp(-s / s_0)) (Bair & Winer's limiting-shear-stress film, uniform
// pressure and film): zero in pure rolling, the viscous slope Lambda / s_0 at s = 0, 63.2 % of
// Lambda at s_0, Lambda in pure sliding; even in s.
TEST(EhlTractionTest, CoefficientIsTheLimitingShearStressCurve) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  EXPECT_EQ(t.Coefficient(0.0), 0.0);
  for (double s : {1e-6, 1e-3, 0.005, 0.01, 0.02, 0.05, 0.3, 2.0})
    EXPECT_NEAR(t.Coefficient(s), 0.08 * (1.0 - std::exp(-s / 0.01)), 1e-15) << s;
  EXPECT_NEAR(t.Coefficient(1e-9) / 1e-9, 0.08 / 0.01, 1e-6);  // viscous slope
  EXPECT_NEAR(t.Coefficient(0.01), 0.08 * 0.6321205588, 1e-10);
  EXPECT_DOUBLE_EQ(t.Coefficient(2.0), 0.08);  // pure sliding
  EXPECT_EQ(t.Coefficient(-0.02), t.Coefficient(0.02));
}

// The force opposes the slip, is mu(s) |F_n| where the step resolves the curve, mu = Lambda with
// no entrainment, and at most m |v| / (2 dt) where the viscous slope is steeper than the step.
TEST(EhlTractionTest, ForceFollowsTheCurveAndIsLimitedByTheStep) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  const double q = 3000.0, ue = 1.2, m = 1e-3, dt = 1e-8;
  for (double v : {-0.3, -0.02, 0.012, 0.05, 1.0}) {
    const double f = t.Force(q, v, ue, m, dt);
    EXPECT_LT(f * v, 0.0) << v;
    EXPECT_NEAR(std::abs(f), t.Coefficient(v / ue) * q, 1e-9 * q) << v;  // m v / 2dt >= curve
  }
  EXPECT_NEAR(t.Force(q, 0.5, 0.0, m, dt), -0.08 * q, 1e-12);  // entrainment 0: sliding
  EXPECT_EQ(t.Force(q, 0.0, ue, m, dt), 0.0);
  EXPECT_EQ(t.Force(0.0, 0.5, ue, m, dt), 0.0);
  // Slip 1e-4 m/s, step 1e-7 s: the curve gives 0.08 * 3000 * (1 - e^-0.00833) = 2.0 N, the
  // step 0.5 N.
  EXPECT_NEAR(t.Force(q, 1e-4, ue, m, 1e-7), -0.5 * m * 1e-4 / 1e-7, 1e-12);
}

// A roller rim (tangential mass m) slipping on a race under 6 kN at 1200 rpm's entrainment: the
// curve's viscous slope Lambda Q / (s_0 u_e) = 4e4 N s/m makes an explicit step of
// 1e-7 s unstable for 1e-3 kg (c dt / m = 4 > 2, the explicit bound); with the step
// limit the slip still falls monotonically to zero, at the curve's rate while the curve is
// the smaller force.
TEST(EhlTractionTest, SlipDecaysMonotonicallyWhereTheCurveIsStifferThanTheStep) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  const double q = 6000.0, ue = 1.2, m = 1e-3, dt = 1e-7;
  ASSERT_GT(t.limiting_coefficient * q / (t.slide_roll_scale * ue) * dt / m, 2.0);
  double v = 0.6;  // s = 0.5: sliding, mu ~ Lambda
  double previous = v;
  for (int i = 0; i < 20000; ++i) {
    const double f = t.Force(q, v, ue, m, dt);
    // While the curve governs: the step changes v by mu(s) Q dt / m.
    if (std::abs(f) < 0.5 * m * std::abs(v) / dt - 1e-12) {
      ASSERT_NEAR(f, -t.Coefficient(v / ue) * q, 1e-9);
    }
    v += f * dt / m;
    ASSERT_GE(v, 0.0) << "overshoot at step " << i;
    ASSERT_LE(v, previous) << "growth at step " << i;
    previous = v;
  }
  EXPECT_LT(v, 1e-12);
}

TEST(EhlTractionTest, ValidatesItsParameters) {
  std::string error;
  EXPECT_TRUE((EhlTraction{}).IsValid(&error));
  EXPECT_FALSE((EhlTraction{.limiting_coefficient = 0.0}).IsValid(&error));
  EXPECT_NE(error.find("limiting traction"), std::string::npos);
  EXPECT_FALSE((EhlTraction{.limiting_coefficient = 0.08, .slide_roll_scale = -1}).IsValid(&error));
  EXPECT_NE(error.find("s_0"), std::string::npos);
}

TEST(EhlTractionTest, SceneSelectsItForTheRigidRollerModelsOnly) {
  const Scene coulomb = ParseScene("", "s.toml", {});
  EXPECT_EQ(coulomb.friction.model, contact::TractionModel::kCoulomb);
  const Scene ehl = ParseScene(
      "[model]\nfidelity = \"hybrid\"\n[friction]\nmodel = \"ehl\"\n"
      "ehl_limit = 0.06\nehl_slide_roll = 0.02\n",
      "s.toml",
      {});
  EXPECT_EQ(ehl.friction.model, contact::TractionModel::kEhl);
  EXPECT_DOUBLE_EQ(ehl.friction.ehl.limiting_coefficient, 0.06);
  EXPECT_DOUBLE_EQ(ehl.friction.ehl.slide_roll_scale, 0.02);
  EXPECT_NE(ehl.effective_toml.find("ehl_limit"), std::string::npos);
  auto error_of = [](const std::string& text) {
    try {
      ParseScene(text, "s.toml", {});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(
      error_of("[model]\nfidelity = \"fe\"\n[friction]\nmodel = \"ehl\"\n").find("model.fidelity"),
      std::string::npos);
  // "auto" (the default) takes a rigid-roller model for it.
  EXPECT_EQ(error_of("[friction]\nmodel = \"ehl\"\n"), "");
  EXPECT_NE(ChooseFidelity(ParseScene("[friction]\nmodel = \"ehl\"\n", "a.toml", {})).fidelity,
            Fidelity::kFe);
  EXPECT_NE(error_of("[friction]\nmodel = \"oil\"\n").find("friction.model"), std::string::npos);
  EXPECT_NE(error_of("[model]\nfidelity = \"lumped\"\n[friction]\nmodel = \"ehl\"\nehl_limit = 0\n")
                .find("friction.ehl_limit"),
            std::string::npos);
}

// Roller 0's sliding from 12 ms of a 35 ms hybrid run (2 mm housing mesh) of the default scene
// (datasets/scenes/paper-verification.toml: 1.38 x 0.59 mm through-length spall, 1200 rpm, 5 ms
// ramp, mu 0.01 / 0.005) with `sets`.
RollerSlidingSummary DefaultSceneRoller(std::vector<std::string> sets) {
  sets.insert(sets.end(), {"model.fidelity=hybrid", "mesh.size_mm=2.0", "run.duration_s=0.035"});
  const Scene scene = LoadScene(
      std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml", sets);
  Simulation sim(scene, SimulationOptions{});
  EXPECT_TRUE(sim.Run().completed);
  const Recorder& r = sim.recorder();
  const std::vector<double>& t = r.Find("/time")->data;
  const Recorder::Series* spin = r.Find("/rollers/spin");
  std::vector<double> spin0(t.size());
  for (size_t i = 0; i < t.size(); ++i) spin0[i] = spin->data[i * spin->cols];
  RollerSlidingOptions o;
  o.from_s = 0.012;
  const RollerSlidingSummary s = MeasureRollerSliding(
      t,
      spin0,
      r.Find("/cage/omega")->data,
      PureRollingRelativeSpin(scene.geometry.bearing, scene.operation.inner_ring_speed_rad_s),
      o);
  std::printf("%s\n", s.BriefReport().c_str());
  return s;
}

// Coulomb at mu 0.01 lets the first loaded spall passage (6.5 ms) stop the roller: it stands on
// its spall corners and orbits with the cage (docs/PAPER.md). The lubricant film's traction
// (limit 0.08) carries it through every passage: it keeps rolling.
TEST(EhlTractionTest, KeepsTheDefaultScenesDefectiveRollerRollingAtThePapersFriction) {
  const RollerSlidingSummary coulomb = DefaultSceneRoller({});
  EXPECT_LT(coulomb.rolling_fraction, 0.05);
  EXPECT_LT(std::abs(coulomb.mean_spin_ratio), 0.1);
  const RollerSlidingSummary ehl = DefaultSceneRoller({"friction.model=ehl"});
  EXPECT_GT(ehl.rolling_fraction, 0.95);
  EXPECT_NEAR(ehl.mean_spin_ratio, 1.0, 0.03);
}

}  // namespace
}  // namespace spallkit::sim
