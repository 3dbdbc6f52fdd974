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

// The secant mu(|v| / u_e) |F_n| / |v| the implicit step uses: the curve over the slip (its
// series branch below x = v / (u_e s_0) = 1e-2 included), the viscous slope at v -> 0, pure
// sliding without entrainment.
TEST(EhlTractionTest, SecantIsTheCurveOverTheSlip) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  const double q = 3000.0, ue = 1.2;
  for (double v : {1e-9, 1e-6, 1e-4, 1.19e-4, 1.21e-4, 1e-3, 0.012, 0.05, 1.0, -0.3}) {
    const double expected = t.Coefficient(v / ue) * q / std::abs(v);
    EXPECT_NEAR(t.Secant(q, v, ue), expected, 1e-10 * expected) << v;
  }
  EXPECT_NEAR(t.Secant(q, 0.0, ue), 0.08 * q / (0.01 * ue), 1e-9);     // viscous slope
  EXPECT_NEAR(t.Secant(q, 0.5, 0.0), 0.08 * q / 0.5, 1e-12);           // entrainment 0: sliding
  EXPECT_NEAR(t.Secant(q, 0.0, 0.0), 0.08 * q / (0.01 * 1e-6), 1e-3);  // u_e floored at 1e-6
  // The curve's force and slope.
  for (double v : {-0.02, 1e-5, 0.012, 0.3}) {
    double f, slope;
    t.CurveForce(q, v, ue, &f, &slope);
    EXPECT_NEAR(f, std::copysign(t.Coefficient(v / ue) * q, v), 1e-10 * q) << v;
    const double h = 1e-7 * std::max(std::abs(v), 1e-3);
    double f_plus, f_minus, unused;
    t.CurveForce(q, v + h, ue, &f_plus, &unused);
    t.CurveForce(q, v - h, ue, &f_minus, &unused);
    EXPECT_NEAR(slope, (f_plus - f_minus) / (2 * h), 1e-5 * slope + 1e-9 * q / (0.01 * ue)) << v;
  }
}

// A rolling roller's rim (tangential mass m) driven by a steady force F (the cage, the other
// race) at 1200 rpm's entrainment: the film carries F at the creep the curve gives,
// v* = -u_e s_0 ln(1 - F / (Lambda Q)), whatever the step. The curve's viscous slope
// (2.5e4 N s/m) is 2.5 to 250 times m / dt here, the regime where a force from the slip at the
// step's start must be capped and then creeps by about F dt / m instead: dissipation in
// proportion to the step.
TEST(EhlTractionTest, ImplicitStepCreepsAtTheCurvesSlipAtAnyStep) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  const double q = 3000.0, ue = 1.2, m = 1e-3;
  for (double load_fraction : {0.01, 0.3, 0.9}) {
    const double drive = load_fraction * 0.08 * q;
    const double creep = -ue * 0.01 * std::log(1.0 - load_fraction);
    for (double dt : {1e-7, 1e-6, 1e-5}) {
      double v = 0.0, f = 0.0, secant = 0.0;  // the last step's secant carried over
      for (int i = 0; i < 20000; ++i) {
        const double free_slip = v + dt * drive / m, compliance = dt / m;
        contact::SolveImplicitTraction(t, 1, &q, &free_slip, &ue, &compliance, &secant, &f);
        ASSERT_LE(std::abs(f), 0.08 * q * (1 + 1e-15));
        v = free_slip + compliance * f;
      }
      EXPECT_NEAR(f, -drive, 1e-9 * drive) << load_fraction << " " << dt;
      EXPECT_NEAR(v, creep, 2e-3 * creep) << load_fraction << " " << dt;
    }
  }
}

// Two contacts on one roller (a disc: tangential mobility 3 / m at each rim point, -1 / m
// between opposite rim points) with a stiff curve: the joint solve gives forces that are each
// the curve's at the slip left after the step (no contact overcorrects the other), in the
// linear, knee and sliding parts of the curve, also for four contacts, and a sliding roller's
// slips decay without overshoot.
TEST(EhlTractionTest, ContactsSharingARollerAreSolvedTogether) {
  const EhlTraction t{.limiting_coefficient = 0.08, .slide_roll_scale = 0.01};
  const double q[2] = {3000.0, 2000.0}, ue[2] = {1.2, 1.2}, m = 2.3e-3, dt = 1e-6;
  const double w[4] = {3 * dt / m, -dt / m, -dt / m, 3 * dt / m};
  for (double v1 : {1e-4, 5e-3, 0.3}) {
    const double free_slip[2] = {v1, -0.5 * v1};
    double f[2], secant[2] = {0.0, 0.0};
    contact::SolveImplicitTraction(t, 2, q, free_slip, ue, w, secant, f);
    for (int k = 0; k < 2; ++k) {
      const double after = free_slip[k] + w[2 * k] * f[0] + w[2 * k + 1] * f[1];
      double curve, slope;
      t.CurveForce(q[k], after, ue[k], &curve, &slope);
      EXPECT_NEAR(f[k], -curve, 1e-3 * std::abs(f[k]) + 1e-9 * 0.08 * q[k]) << v1 << " " << k;
      EXPECT_NEAR(secant[k] * q[k] * std::abs(after), std::abs(curve), 1e-9 * std::abs(curve));
      EXPECT_LE(f[k] * after, 0.0) << v1 << " " << k;
    }
  }
  // A roller sliding at 0.6 m/s on one race and 0.3 on the other, nothing else acting.
  double v[2] = {0.6, 0.3}, previous[2] = {0.6, 0.3}, secants[2] = {0.0, 0.0};
  for (int i = 0; i < 5000; ++i) {
    double f[2];
    contact::SolveImplicitTraction(t, 2, q, v, ue, w, secants, f);
    const double next[2] = {v[0] + w[0] * f[0] + w[1] * f[1], v[1] + w[2] * f[0] + w[3] * f[1]};
    for (int k = 0; k < 2; ++k) {
      ASSERT_GE(next[k], -1e-12) << "overshoot at step " << i;
      ASSERT_LE(next[k], previous[k] + 1e-12) << "growth at step " << i;
      previous[k] = v[k] = next[k];
    }
  }
  EXPECT_LT(std::max(v[0], v[1]), 1e-9);
  // Four contacts (a partial-length spall: its spalled and intact profiles on both races, the
  // two on one race sharing the roller's rim point), solved by LU: each force is still the
  // curve's at the slip it leaves.
  {
    const double q4[4] = {2000.0, 1000.0, 1500.0, 500.0}, ue4[4] = {1.2, 1.2, 1.2, 1.2};
    const double c = dt / m;
    const double w4[16] = {3 * c + 1e-6,
                           3 * c,
                           -c,
                           -c,
                           3 * c,
                           3 * c + 1e-6,
                           -c,
                           -c,
                           -c,
                           -c,
                           3 * c + 2e-6,
                           3 * c,
                           -c,
                           -c,
                           3 * c,
                           3 * c + 2e-6};
    const double slips[4] = {2e-3, 2e-3, -1e-3, -1e-3};
    double f4[4], s4[4] = {0, 0, 0, 0};
    contact::SolveImplicitTraction(t, 4, q4, slips, ue4, w4, s4, f4);
    for (int k = 0; k < 4; ++k) {
      double after = slips[k];
      for (int l = 0; l < 4; ++l) after += w4[4 * k + l] * f4[l];
      double curve, slope;
      t.CurveForce(q4[k], after, ue4[k], &curve, &slope);
      EXPECT_NEAR(f4[k], -curve, 1e-3 * std::abs(f4[k]) + 1e-9 * 0.08 * q4[k]) << k;
    }
  }
  // An unloaded contact takes no force.
  const double unloaded[2] = {3000.0, 0.0}, slips[2] = {0.1, 0.1};
  double f[2], none[2] = {0.0, 0.0};
  contact::SolveImplicitTraction(t, 2, unloaded, slips, ue, w, none, f);
  EXPECT_EQ(f[1], 0.0);
  EXPECT_LT(f[0], 0.0);
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
      "ehl_limit = 0.06\nehl_slide_roll = 0.02\nehl_viscosity_pa_s = 0.1\n",
      "s.toml",
      {});
  EXPECT_EQ(ehl.friction.model, contact::TractionModel::kEhl);
  EXPECT_DOUBLE_EQ(ehl.friction.ehl.limiting_coefficient, 0.06);
  EXPECT_DOUBLE_EQ(ehl.friction.ehl.slide_roll_scale, 0.02);
  EXPECT_DOUBLE_EQ(ehl.friction.ehl.inlet_viscosity_pa_s, 0.1);
  EXPECT_DOUBLE_EQ(coulomb.friction.ehl.inlet_viscosity_pa_s, 0.05);  // the default
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
  EXPECT_NE(error_of("[friction]\nmodel = \"ehl\"\nehl_viscosity_pa_s = -0.01\n")
                .find("friction.ehl_viscosity_pa_s"),
            std::string::npos);
  std::string error;
  EXPECT_FALSE((EhlTraction{.inlet_viscosity_pa_s = -1}).IsValid(&error));
  EXPECT_NE(error.find("viscosity"), std::string::npos);
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
