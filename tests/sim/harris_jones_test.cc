// Harris–Jones load distribution against published references (N205EM as modelled in the paper,
// l = 9 mm, 10 kN; docs/BEARING_MODEL.md, "Harris–Jones load distribution").
#include "sim/quasistatic/harris_jones.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "tests/apps/run_spall.h"

namespace spallkit::sim {
namespace {

constexpr double kDeg = kPi / 180.0;

LoadDistributionSummary Solve(double pd_mm, double phase_rad = 0.0, double rpm = 1200.0) {
  LoadDistributionOptions o;
  o.radial_load_n = 10000.0;
  o.inner_ring_speed_rad_s = rpm * 2.0 * kPi / 60.0;
  o.roller_length_m = 9e-3;
  o.diametral_clearance_m = pd_mm * 1e-3;
  o.phase_rad = phase_rad;
  LoadDistributionSummary s;
  SolveLoadDistribution(o, CatalogBearing("N205EM"), &s);
  EXPECT_TRUE(s.IsSolutionUsable()) << s.message;
  return s;
}

// Roller with psi closest to `deg` (the solution lists rollers in index order).
const RollerLoad& At(const LoadDistributionSummary& s, double deg) {
  const RollerLoad* best = &s.rollers[0];
  for (const auto& r : s.rollers)
    if (std::abs(r.angle_rad - deg * kDeg) < std::abs(best->angle_rad - deg * kDeg)) best = &r;
  return *best;
}

TEST(HarrisJones, CaseAWithRollerOnLoadLineMatchesReference) {
  const auto s = Solve(0.02);
  EXPECT_NEAR(s.q_max_n, 3563.0, 3.0);
  EXPECT_NEAR(s.delta_r_m * 1e6, 30.83, 0.03);
  EXPECT_NEAR(s.load_zone_half_angle_rad / kDeg, 71.1, 0.1);
  EXPECT_NEAR(s.load_distribution_factor, 0.338, 0.001);
  EXPECT_NEAR(At(s, 27.69).outer_load_n, 2899.0, 3.0);
  EXPECT_NEAR(At(s, -27.69).outer_load_n, 2899.0, 3.0);
  EXPECT_NEAR(At(s, 55.38).outer_load_n, 1147.0, 3.0);
  EXPECT_NEAR(At(s, 83.08).inner_load_n, 0.0, 1e-12);
  // Each contact deflects half the approach at psi = 0 (F_c is 0.1 N): 10.41 um.
  EXPECT_NEAR(At(s, 0).inner_deflection_m * 1e6, 10.41, 0.02);
  // Linearised radial stiffness ~5.9e8 N/m.
  EXPECT_NEAR(s.radial_stiffness_n_m, 5.92e8, 0.05e8);
}

TEST(HarrisJones, RollersShiftedByHalfPitch) {
  const auto s = Solve(0.02, kPi / 13.0);
  EXPECT_NEAR(s.q_max_n, 3440.0, 3.0);
  EXPECT_NEAR(At(s, 41.54).outer_load_n, 2158.0, 3.0);
  EXPECT_NEAR(At(s, 69.23).outer_load_n, 125.0, 3.0);
}

TEST(HarrisJones, CaseBDiametralClearanceFortyMicrons) {
  const auto s = Solve(0.04);
  EXPECT_NEAR(s.q_max_n, 3948.0, 4.0);
  EXPECT_NEAR(s.delta_r_m * 1e6, 42.84, 0.05);
  EXPECT_NEAR(s.load_zone_half_angle_rad / kDeg, 62.2, 0.1);
}

TEST(HarrisJones, ZeroClearanceApproachesStribeck) {
  const auto s = Solve(0.0);
  // Exact discrete answer F_r / sum cos^(19/9) psi_j with F_c -> 0; Stribeck 4.08 F_r/Z = 3138 N.
  double sum = 0.0;
  for (int j = 0; j < 13; ++j) {
    const double c = std::cos(2.0 * kPi * j / 13.0);
    if (c > 0) sum += std::pow(c, 19.0 / 9.0);
  }
  EXPECT_NEAR(s.q_max_n, 10000.0 / sum, 1.0);
  EXPECT_NEAR(s.q_max_n, 3149.0, 2.0);
  EXPECT_NEAR(s.q_max_n, 4.08 * 10000.0 / 13.0, 0.01 * 3138.0);
  EXPECT_NEAR(s.load_zone_half_angle_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(At(s, 83.08).outer_load_n, 300.0, 2.0);
}

TEST(HarrisJones, ForceEquilibriumAndSymmetry) {
  for (double phase : {0.0, 0.1, kPi / 13.0}) {
    const auto s = Solve(0.02, phase, 6000.0);
    double fy = 0.0, fx = 0.0;
    for (const auto& r : s.rollers) {
      fy += r.inner_load_n * std::cos(r.angle_rad);
      fx += r.inner_load_n * std::sin(r.angle_rad);
      // Outer = inner + centrifugal, for every roller (Jones).
      EXPECT_NEAR(r.outer_load_n - r.inner_load_n, s.centrifugal_force_n, 1e-9);
      // Deflections add up to the approach where the roller touches both races.
      if (r.inner_load_n > 0) {
        EXPECT_NEAR(r.inner_deflection_m + r.outer_deflection_m, r.approach_m, 1e-12);
      }
    }
    EXPECT_NEAR(fy, 10000.0, 1e-6);
    if (phase == 0.0 || phase == kPi / 13.0) {
      EXPECT_NEAR(fx, 0.0, 1e-6);
    }
  }
}

TEST(HarrisJones, CentrifugalForceOfTheRoller) {
  const auto s1200 = Solve(0.02, 0.0, 1200.0);
  EXPECT_NEAR(s1200.roller_mass_kg * 1e3, 2.344, 0.001);
  EXPECT_NEAR(s1200.cage_speed_rad_s, 52.224, 0.001);
  EXPECT_NEAR(s1200.centrifugal_force_n, 0.123, 0.001);
  const auto s6000 = Solve(0.02, 0.0, 6000.0);
  EXPECT_NEAR(s6000.centrifugal_force_n, 3.08, 0.01);
  // Speed barely changes the distribution (Jones: only the centrifugal force).
  EXPECT_NEAR(s6000.q_max_n, s1200.q_max_n, 0.002 * s1200.q_max_n);
}

TEST(HarrisJones, RadialIntegralValues) {
  EXPECT_NEAR(RadialIntegral(0.5), 0.2448, 1e-4);
  EXPECT_NEAR(1.0 / RadialIntegral(0.5), 4.085, 2e-3);
  EXPECT_NEAR(RadialIntegral(0.338), 0.2146, 1e-4);
  EXPECT_NEAR(RadialIntegral(0.265), 0.1950, 3e-4);
  EXPECT_THROW(RadialIntegral(0.0), InputError);
}

// The continuous-roller limit Q_max = F_r / (Z J_r(epsilon)) tracks the discrete solution.
TEST(HarrisJones, DiscreteSolutionAgreesWithIntegral) {
  for (double pd : {0.0, 0.02, 0.04}) {
    for (double phase : {0.0, kPi / 13.0}) {
      const auto s = Solve(pd, phase);
      const double q_int = 10000.0 / (13.0 * RadialIntegral(s.load_distribution_factor));
      EXPECT_NEAR(s.q_max_n, q_int, 0.08 * q_int) << "P_d " << pd << " phase " << phase;
    }
  }
  // With the roller on the load line the discrete and continuous answers are within 1 %.
  const auto s = Solve(0.02);
  const double q_int = 10000.0 / (13.0 * RadialIntegral(s.load_distribution_factor));
  EXPECT_NEAR(s.q_max_n, q_int, 0.01 * q_int);
}

TEST(HarrisJones, LongerRollersCarryMorePeakLoad) {
  // Reference values for l = 6.5 / 15 mm at P_d = 0.02 mm.
  LoadDistributionOptions o;
  o.inner_ring_speed_rad_s = 1200.0 * 2.0 * kPi / 60.0;
  LoadDistributionSummary s;
  o.roller_length_m = 6.5e-3;
  SolveLoadDistribution(o, CatalogBearing("N205EM"), &s);
  EXPECT_NEAR(s.q_max_n, 3474.0, 4.0);
  EXPECT_NEAR(s.delta_r_m * 1e6, 36.4, 0.1);
  o.roller_length_m = 15e-3;
  SolveLoadDistribution(o, CatalogBearing("N205EM"), &s);
  EXPECT_NEAR(s.q_max_n, 3759.0, 4.0);
  EXPECT_NEAR(s.load_zone_half_angle_rad / kDeg, 65.9, 0.1);
}

TEST(HarrisJones, ZeroLoadLeavesRollersUnloaded) {
  LoadDistributionOptions o;
  o.radial_load_n = 0.0;
  LoadDistributionSummary s;
  SolveLoadDistribution(o, CatalogBearing("N205EM"), &s);
  EXPECT_TRUE(s.IsSolutionUsable());
  EXPECT_EQ(s.q_max_n, 0.0);
}

TEST(HarrisJones, BadInputIsInputError) {
  LoadDistributionOptions o;
  LoadDistributionSummary s;
  o.radial_load_n = -1.0;
  EXPECT_THROW(SolveLoadDistribution(o, CatalogBearing("N205EM"), &s), InputError);
  o = LoadDistributionOptions();
  o.roller_length_m = 0.0;
  try {
    SolveLoadDistribution(o, CatalogBearing("N205EM"), &s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("roller length"), std::string::npos) << e.what();
  }
  o = LoadDistributionOptions();
  o.diametral_clearance_m = -1e-6;
  EXPECT_THROW(SolveLoadDistribution(o, CatalogBearing("N205EM"), &s), InputError);
  std::string why;
  EXPECT_TRUE(LoadDistributionOptions().IsValid(&why)) << why;
}

// Extreme inputs for the bounded bracketing loop: each ends, either with a solution or with an
// InputError naming the input.
TEST(HarrisJones, ExtremeInputsEndWithASolutionOrAnError) {
  const BearingGeometry b = CatalogBearing("N205EM");
  LoadDistributionSummary s;
  LoadDistributionOptions o;
  o.radial_load_n = 1e-20;  // far below one ulp of the clearance's force scale
  SolveLoadDistribution(o, b, &s);
  EXPECT_TRUE(s.IsSolutionUsable()) << s.message;
  EXPECT_GE(s.delta_r_m, 0.5 * o.diametral_clearance_m);
  o.diametral_clearance_m = 1e-3;  // large clearance, tiny load: the step starts at ulps
  SolveLoadDistribution(o, b, &s);
  EXPECT_TRUE(s.IsSolutionUsable()) << s.message;
  o = LoadDistributionOptions();
  o.radial_load_n = 1e12;
  SolveLoadDistribution(o, b, &s);
  EXPECT_TRUE(s.IsSolutionUsable()) << s.message;
  EXPECT_NEAR(s.force_residual_n, 0.0, 1e-6 * o.radial_load_n);

  auto message = [&](const LoadDistributionOptions& bad) {
    try {
      SolveLoadDistribution(bad, b, &s);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  o = LoadDistributionOptions();
  o.phase_rad = 1e20;  // the roller angles would all round to one value
  EXPECT_NE(message(o).find("roller phase"), std::string::npos) << message(o);
  o = LoadDistributionOptions();
  o.diametral_clearance_m = 1e97;
  EXPECT_NE(message(o).find("clearance"), std::string::npos) << message(o);
  o = LoadDistributionOptions();
  o.roller_length_m = 1e97;
  EXPECT_NE(message(o).find("roller length"), std::string::npos) << message(o);
}

// ISO 76 defines the static load rating of roller bearings as the load giving 4000 MPa at the most
// loaded contact, with Stribeck's Q_max = 5 F_r / Z and C0 = 44 (1 - D cos a / D_pw) Z L_we D_we
// (N, mm). The Hertz line-contact pressure at Q = 5 C0 / Z must then be 4000 MPa.
TEST(HertzLinePressure, ReproducesTheIso76StaticLoadRating) {
  const BearingGeometry b = CatalogBearing("N205EM");
  const double d_mm = b.element_diameter_m * 1e3, dpw_mm = b.pitch_diameter_m * 1e3;
  const double l_mm = 9.0;
  const double c0 = 44.0 * (1.0 - d_mm / dpw_mm) * b.num_elements * l_mm * d_mm;
  EXPECT_NEAR(c0, 27.8e3, 0.1e3);
  const double q = 5.0 * c0 / b.num_elements;
  const double p0 = HertzLinePressure(
      q, l_mm * 1e-3, 0.5 * b.element_diameter_m, 0.5 * b.inner_raceway_diameter_m);
  EXPECT_NEAR(p0 / kStaticCapacityStressPa, 1.0, 0.02) << p0;
  EXPECT_EQ(HertzLinePressure(0.0, 9e-3, 1e-3, 1e-3), 0.0);
}

// The CLI prints the same solution; JSON keys are documented in docs/BEARING_MODEL.md.
using spallkit::testing::RunSpall;

TEST(HarrisJonesCli, LoadsJsonReportsQmaxAndRollers) {
  int rc = -1;
  const std::string out = RunSpall(
      "loads --bearing N205EM --load-n 10000 --rpm 1200 --roller-length-mm 9 "
      "--clearance-mm 0.02 --json",
      &rc);
  ASSERT_EQ(rc, 0) << out;
  const auto j = nlohmann::json::parse(out);
  EXPECT_NEAR(j.at("q_max_n").get<double>(), 3563.0, 3.0);
  EXPECT_NEAR(j.at("delta_r_um").get<double>(), 30.83, 0.03);
  EXPECT_NEAR(j.at("load_zone_half_angle_deg").get<double>(), 71.1, 0.1);
  ASSERT_EQ(j.at("rollers").size(), 13u);
  EXPECT_NEAR(j["rollers"][1].at("angle_deg").get<double>(), 27.69, 0.01);
  EXPECT_NEAR(j["rollers"][1].at("load_outer_n").get<double>(), 2899.0, 3.0);
  EXPECT_TRUE(j["rollers"][1].contains("load_inner_n"));
  EXPECT_TRUE(j["rollers"][1].contains("deflection_inner_um"));
}

TEST(HarrisJonesCli, NegativeLoadIsOneLineErrorWithExitCode2) {
  int rc = -1;
  const std::string out = RunSpall("loads --load-n -10", &rc);
  EXPECT_EQ(rc, 2);
  EXPECT_EQ(out.rfind("spall: error: --load-n", 0), 0u) << out;
  EXPECT_EQ(out.find('\n'), out.size() - 1) << out;
}

}  // namespace
}  // namespace spallkit::sim
