// The hump shape: Harris-Jones relative load q(psi) and its half angle.
#include "identify/load_zone.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/bearing.h"
#include "core/constants.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::identify {
namespace {

TEST(LoadZone, RelativeLoadIsOneOnTheLoadLineAndZeroAtTheEdge) {
  const double half = 70.0 * kPi / 180.0;
  EXPECT_DOUBLE_EQ(RelativeLoad(0.0, half), 1.0);
  EXPECT_DOUBLE_EQ(RelativeLoad(half, half), 0.0);
  EXPECT_DOUBLE_EQ(RelativeLoad(1.3 * half, half), 0.0);
  // Palmgren: q = ((cos psi - cos psi_l) / (1 - cos psi_l))^(10/9).
  const double psi = 0.4;
  EXPECT_NEAR(RelativeLoad(psi, half),
              std::pow((std::cos(psi) - std::cos(half)) / (1.0 - std::cos(half)), 10.0 / 9.0),
              1e-15);
  EXPECT_NEAR(RelativeLoad(psi, half), RelativeLoad(-psi, half), 1e-15);
}

// The relative load equals the solver's own roller loads (same delta_r, same law) at the rollers.
TEST(LoadZone, MatchesTheHarrisJonesRollerLoads) {
  const BearingGeometry g = CatalogBearing("N205EM");
  sim::LoadDistributionOptions o;
  o.radial_load_n = 10000.0;
  sim::LoadDistributionSummary s;
  sim::SolveLoadDistribution(o, g, &s);
  ASSERT_TRUE(s.IsSolutionUsable());
  const LoadZone z =
      SolveLoadZone(g, 10000.0, 0.0 + 1e-9, o.diametral_clearance_m, o.roller_length_m);
  EXPECT_NEAR(z.half_angle_rad, s.load_zone_half_angle_rad, 1e-9);
  for (const auto& r : s.rollers)
    EXPECT_NEAR(z.Relative(r.angle_rad), r.inner_load_n / s.q_max_inner_n, 0.02)
        << "roller at " << r.angle_rad;
}

TEST(LoadZone, LargerLoadWidensTheZone) {
  const BearingGeometry g = CatalogBearing("N205EM");
  const double a = SolveLoadZone(g, 5000.0, 20.0, 20e-6, 9e-3).half_angle_rad;
  const double b = SolveLoadZone(g, 15000.0, 20.0, 20e-6, 9e-3).half_angle_rad;
  EXPECT_LT(a, b);
  EXPECT_LT(b, 0.5 * kPi);
}

}  // namespace
}  // namespace spallkit::identify
