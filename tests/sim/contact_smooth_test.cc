// Smooth (cubic B-spline) contact surfaces (spline_surface.h, ContactPairOptions::
// smooth_surfaces): a polygon of nodes on a circle pressed into a circular bore touches as the
// circle does (k x the analytic overlap, along the line of centres, at every rotation), the forces
// are conservative along a rolling path and over a closed deform cycle, and, the reason for the
// B-splines, the nodal forces are C2 in the contact's position: their second difference along a
// roll shrinks with the square of the step, where the arc contact's (C0 weights, a kink at every
// node) shrinks only linearly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "sim/contact/contact_pair.h"
#include "sim/contact/spline_surface.h"
#include "sim/contact/surface.h"
#include "sim/fe/nodal_state.h"
#include "tests/sim/roller_in_bore.h"

namespace spallkit::sim::contact {
namespace {

using namespace roller_in_bore;  // Scene, MakeScene, PlaceRoller, Evaluate, constants

ContactPairOptions Options(bool smooth = true) { return ConstantPenalty(smooth); }

TEST(SmoothContactTest, SplineOfACircleIsAnOffsetCircle) {
  Scene s = MakeScene(true);
  PlaceRoller(&s, 0.0, 0.0, 0.0);
  SplineSurface roller = MakeSplineSurface(s.roller), bore = MakeSplineSurface(s.bore);
  roller.offset = MeasureSplineOffset(s.roller, roller, s.state.x.data(), s.state.y.data());
  bore.offset = MeasureSplineOffset(s.bore, bore, s.state.x.data(), s.state.y.data());
  const double dphi = 2 * kPi / kRim, dpsi = 2 * kPi / kRace;
  EXPECT_NEAR(roller.offset, kR * (1 - std::cos(dphi)) / 3, 1e-12);    // inside: convex, +
  EXPECT_NEAR(bore.offset, -kBore * (1 - std::cos(dpsi)) / 3, 1e-12);  // towards the void: -
  for (int i = 0; i < kRim; ++i) EXPECT_TRUE(roller.valid_span[i]);
  // Mid-span the curve's radius differs from the nodes' by ~r dphi^4 / 100: 0.04 um here.
  const SplinePoint mid =
      EvaluateSpan(s.roller, roller, 5, 0.5, s.state.x.data(), s.state.y.data());
  EXPECT_NEAR(std::hypot(mid.x, mid.y) + roller.offset, kR, 1e-7);
}

TEST(SmoothContactTest, PolygonRollerTouchesABoreAsTheCircleDoesAtEveryRotation) {
  const double overlap = 10e-6, d = kBore - kR + overlap, theta = -1.2;
  Scene s = MakeScene(true);
  ContactPair pair("roller/bore", s.roller, s.bore, Options());
  for (int k = 0; k < 16; ++k) {
    SCOPED_TRACE(k);
    PlaceRoller(&s, d, theta, 2 * kPi / kRim * k / 16.0);
    const Force f = Evaluate(pair, &s, d, theta);
    const double fn = std::hypot(f.fx, f.fy);
    // The curve is a circle to 0.04 um mid-span (0.4 % of the overlap).
    EXPECT_NEAR(fn, kK * overlap, 5e-3 * kK * overlap);
    EXPECT_NEAR(f.fx / fn, -std::cos(theta), 1e-4);
    EXPECT_NEAR(f.fy / fn, -std::sin(theta), 1e-4);
    EXPECT_NEAR(f.moment, 0.0, 1e-4 * fn * kR);
    EXPECT_EQ(pair.Resultant().active_nodes, 1);  // one contact point
  }
}

TEST(SmoothContactTest, ForcesAreConservativeAlongARollingPath) {
  double energy_change = 0;
  const double work = RollingPathWork(Options(), &energy_change);
  const double scale = 0.5 * kK * 15e-6 * 15e-6;
  std::printf("rolling path: work %.7e J, -dE %.7e J\n", work, -energy_change);
  EXPECT_NEAR(energy_change, 0.5 * kK * (15e-6 * 15e-6 - 5e-6 * 5e-6), 1e-2 * scale);
  EXPECT_NEAR(work, -energy_change, 1e-5 * scale);
}

TEST(SmoothContactTest, ForcesAreConservativeWhileTheSurfacesDeform) {
  double peak = 0;
  const double work = DeformCycleWork(Options(), &peak);
  std::printf("deform cycle: work %.3e J, peak stored %.3e J\n", work, peak);
  EXPECT_GT(peak, 0.0);
  EXPECT_NEAR(work, 0.0, 1e-6 * peak);
}

// Largest second difference of any roller node's force along a roll of one and a half rim
// segments in `steps` steps at constant overlap: ~ h^2 F'' where the weights are C2, ~ h x the
// slope jump where they kink.
double LargestSecondDifference(bool smooth, int steps) {
  Scene s = MakeScene(true);
  ContactPair pair("roller/bore", s.roller, s.bore, Options(smooth));
  const double d = kBore - kR + 10e-6, theta = -1.2;
  std::vector<double> f0, f1;
  double largest = 0;
  for (int step = 0; step <= steps; ++step) {
    PlaceRoller(&s, d, theta, theta + 0.2 + 1.5 * 2 * kPi / kRim * step / steps);
    Evaluate(pair, &s, d, theta);
    std::vector<double> f(2 * kRim);
    for (int i = 0; i < kRim; ++i) f[2 * i] = s.state.fx[i], f[2 * i + 1] = s.state.fy[i];
    if (step >= 2)
      for (int i = 0; i < 2 * kRim; ++i)
        largest = std::max(largest, std::abs(f[i] - 2 * f1[i] + f0[i]));
    f0 = std::move(f1);
    f1 = std::move(f);
  }
  return largest;
}

TEST(SmoothContactTest, NodalForcesAreSmoothInTheContactsPosition) {
  const double smooth_ratio =
      LargestSecondDifference(true, 200) / LargestSecondDifference(true, 400);
  const double arc_ratio =
      LargestSecondDifference(false, 200) / LargestSecondDifference(false, 400);
  std::printf("second difference ratio (200 -> 400 steps): smooth %.2f, arcs %.2f\n",
              smooth_ratio,
              arc_ratio);
  EXPECT_GT(smooth_ratio, 3.5) << "halving the step should quarter it (C2)";
  EXPECT_LT(arc_ratio, 2.5) << "the arc contact's weights kink at the nodes (C0)";
}

TEST(SmoothContactTest, ANotchsCornersTouchAsNodesAndTheRimBesideItAsTheSpline) {
  // A 40 um deep, three-node notch rolled through the contact at 10 um overlap: the force never
  // vanishes or doubles while the intact rim beside the notch carries it (the spline ends
  // where its control points reach a corner; node contact takes over there), and it drops below
  // half while the notch faces the bore.
  const double notch = 40e-6, overlap = 10e-6, d = kBore - kR + overlap, theta = -1.2;
  Scene s = MakeScene(true, notch);
  ContactPair pair("roller/bore", s.roller, s.bore, Options());
  const double dphi = 2 * kPi / kRim;
  double lowest = 1e300, highest = 0;
  bool dropped = false;
  for (int k = 0; k <= 160; ++k) {
    const double offset = -8 * dphi + 16 * dphi * k / 160;  // notch centre relative to the line
    PlaceRoller(&s, d, theta, theta + offset, notch);
    const Force f = Evaluate(pair, &s, d, theta);
    const double fn = std::hypot(f.fx, f.fy);
    ASSERT_TRUE(std::isfinite(fn));
    if (std::abs(offset) > 4.5 * dphi) {
      lowest = std::min(lowest, fn);
      highest = std::max(highest, fn);
    }
    dropped = dropped || fn < 0.5 * kK * overlap;
  }
  std::printf("notch: beside it %.4f .. %.4f x k overlap\n",
              lowest / (kK * overlap),
              highest / (kK * overlap));
  EXPECT_GT(lowest, 0.95 * kK * overlap);
  EXPECT_LT(highest, 1.05 * kK * overlap);
  EXPECT_TRUE(dropped);
}

}  // namespace
}  // namespace spallkit::sim::contact
