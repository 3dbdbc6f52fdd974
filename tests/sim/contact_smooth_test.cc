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

namespace spallkit::contact {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 3.25e-3, kBore = 22.5e-3, kK = 1e9;  // roller, bore radii (m); N/m
constexpr int kRim = 40, kRace = 283;                      // the 0.5 mm bearing mesh's counts

// Nodes 0..kRim-1: the roller (CCW, body on the left), then the bore (CW, ring body on the left).
struct Scene {
  fe::NodalState state;
  ContactSurface roller, bore;
};

// notch: nodes 0 and kRim-1.. pushed `notch` into the roller (a flat-bottomed pit of 3 nodes:
// kRim-1, 0, 1), so the segments around them are straight and their ends are kinks.
Scene MakeScene(double notch = 0.0) {
  Scene s;
  s.state.Resize(kRim + kRace);
  std::vector<int> rn, bn;
  for (int i = 0; i < kRim; ++i) rn.push_back(i);
  for (int i = 0; i < kRace; ++i) {
    const double a = -2 * kPi * i / kRace;
    s.state.x[kRim + i] = kBore * std::cos(a);
    s.state.y[kRim + i] = kBore * std::sin(a);
    bn.push_back(kRim + i);
  }
  for (int i = 0; i < kRim + kRace; ++i) s.state.mass[i] = 1e-5;
  s.roller = MakeSurfaceFromChain("roller", rn, true);
  s.bore = MakeSurfaceFromChain("bore", bn, true);
  std::vector<double> x(kRim), y(kRim);
  for (int i = 0; i < kRim; ++i) {
    const double r = (i == 0 || i == 1 || i == kRim - 1) ? kR - notch : kR;
    x[i] = r * std::cos(2 * kPi * i / kRim);
    y[i] = r * std::sin(2 * kPi * i / kRim);
  }
  const int arcs = MarkCircularArcs(&s.roller, x.data(), y.data(), 0, 0, kR, 1e-12);
  EXPECT_EQ(arcs, notch > 0 ? kRim - 4 : kRim);
  EXPECT_EQ(MarkCircularArcs(&s.bore, s.state.x.data(), s.state.y.data(), 0, 0, kBore, 1e-12),
            kRace);
  return s;
}

// Roller at centre distance d along direction theta, rotated by phi (notch kept).
void PlaceRoller(Scene* s, double d, double theta, double phi, double notch = 0.0) {
  for (int i = 0; i < kRim; ++i) {
    const double a = 2 * kPi * i / kRim + phi;
    const double r = (i == 0 || i == 1 || i == kRim - 1) ? kR - notch : kR;
    s->state.x[i] = d * std::cos(theta) + r * std::cos(a);
    s->state.y[i] = d * std::sin(theta) + r * std::sin(a);
  }
}

ContactPairOptions Options(bool smooth = true) {
  ContactPairOptions o;
  o.penalty_law = PenaltyLaw::kConstant;
  o.constant_stiffness = kK;
  o.smooth_surfaces = smooth;
  return o;
}

struct Force {
  double fx = 0, fy = 0, moment = 0, stored = 0;  // on the roller; moment about its centre
};

Force Evaluate(ContactPair& pair, Scene* s, double d, double theta) {
  std::fill(s->state.fx.begin(), s->state.fx.end(), 0.0);
  std::fill(s->state.fy.begin(), s->state.fy.end(), 0.0);
  pair.AddForces(s->state, 0.0, 1e-9);
  Force f;
  const double cx = d * std::cos(theta), cy = d * std::sin(theta);
  for (int i = 0; i < kRim; ++i) {
    f.fx += s->state.fx[i];
    f.fy += s->state.fy[i];
    f.moment += (s->state.x[i] - cx) * s->state.fy[i] - (s->state.y[i] - cy) * s->state.fx[i];
  }
  f.stored = pair.StoredEnergy();
  return f;
}

TEST(SmoothContactTest, SplineOfACircleIsAnOffsetCircle) {
  Scene s = MakeScene();
  PlaceRoller(&s, 0.0, 0.0, 0.0);
  const SplineSurface roller = MakeSplineSurface(s.roller, s.state.x.data(), s.state.y.data());
  const SplineSurface bore = MakeSplineSurface(s.bore, s.state.x.data(), s.state.y.data());
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
  Scene s = MakeScene();
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
  Scene s = MakeScene();
  ContactPair pair("roller/bore", s.roller, s.bore, Options());
  const int n = 4000;
  double work = 0, e0 = 0, e1 = 0;
  std::vector<double> fx_prev, fy_prev, x_prev, y_prev;
  for (int step = 0; step <= n; ++step) {
    const double u = static_cast<double>(step) / n;
    const double d = kBore - kR + 5e-6 + 10e-6 * std::sin(kPi * u);
    const double theta = -1.2 + 0.05 * u, phi = 0.7 * u;  // rolls over ~4.5 rim segments
    PlaceRoller(&s, d, theta, phi);
    const Force f = Evaluate(pair, &s, d, theta);
    if (step == 0) e0 = f.stored;
    if (step == n) e1 = f.stored;
    if (step > 0)
      for (int i = 0; i < kRim; ++i)
        work += 0.5 * (s.state.fx[i] + fx_prev[i]) * (s.state.x[i] - x_prev[i]) +
                0.5 * (s.state.fy[i] + fy_prev[i]) * (s.state.y[i] - y_prev[i]);
    fx_prev.assign(s.state.fx.begin(), s.state.fx.begin() + kRim);
    fy_prev.assign(s.state.fy.begin(), s.state.fy.begin() + kRim);
    x_prev.assign(s.state.x.begin(), s.state.x.begin() + kRim);
    y_prev.assign(s.state.y.begin(), s.state.y.begin() + kRim);
  }
  const double scale = 0.5 * kK * 15e-6 * 15e-6;
  std::printf("rolling path: work %.3e J, -dE %.3e J\n", work, -(e1 - e0));
  EXPECT_GT(e1, 0.0);
  EXPECT_NEAR(work, -(e1 - e0), 1e-5 * scale) << "work " << work << " dE " << e1 - e0;
}

TEST(SmoothContactTest, ForcesAreConservativeWhileTheSurfacesDeform) {
  // Closed cycle: press, stretch both surfaces tangentially out of phase, release; the work on
  // all nodes comes back to zero.
  Scene s = MakeScene();
  ContactPair pair("roller/bore", s.roller, s.bore, Options());
  const double theta = -1.2;
  std::vector<double> bx(s.state.x.begin() + kRim, s.state.x.end());
  std::vector<double> by(s.state.y.begin() + kRim, s.state.y.end());
  const int n = 4000, nodes = kRim + kRace;
  double work = 0, peak = 0;
  std::vector<double> fx_prev, fy_prev, x_prev, y_prev;
  for (int step = 0; step <= n; ++step) {
    const double u = static_cast<double>(step) / n;
    const double d = kBore - kR + 10e-6 + 5e-6 * std::sin(2 * kPi * u);
    const double strain = 2e-3 * std::cos(2 * kPi * u);
    PlaceRoller(&s, d, theta, 0.013);
    const double cx = d * std::cos(theta), cy = d * std::sin(theta);
    for (int i = 0; i < kRim; ++i) {
      const double a = std::atan2(s.state.y[i] - cy, s.state.x[i] - cx);
      const double b = a + strain * std::sin(a - theta);
      s.state.x[i] = cx + kR * std::cos(b);
      s.state.y[i] = cy + kR * std::sin(b);
    }
    for (int j = 0; j < kRace; ++j) {
      const double a = std::atan2(by[j], bx[j]);
      const double b = a - 0.5 * strain * std::sin(a - theta);
      s.state.x[kRim + j] = kBore * std::cos(b);
      s.state.y[kRim + j] = kBore * std::sin(b);
    }
    const Force f = Evaluate(pair, &s, d, theta);
    peak = std::max(peak, f.stored);
    if (step > 0)
      for (int i = 0; i < nodes; ++i)
        work += 0.5 * (s.state.fx[i] + fx_prev[i]) * (s.state.x[i] - x_prev[i]) +
                0.5 * (s.state.fy[i] + fy_prev[i]) * (s.state.y[i] - y_prev[i]);
    fx_prev.assign(s.state.fx.begin(), s.state.fx.end());
    fy_prev.assign(s.state.fy.begin(), s.state.fy.end());
    x_prev.assign(s.state.x.begin(), s.state.x.end());
    y_prev.assign(s.state.y.begin(), s.state.y.end());
  }
  std::printf("deform cycle: work %.3e J, peak stored %.3e J\n", work, peak);
  EXPECT_GT(peak, 0.0);
  EXPECT_NEAR(work, 0.0, 1e-6 * peak) << "work over the cycle " << work << " J, peak " << peak;
}

// Largest second difference of any roller node's force along a roll of one and a half rim
// segments in `steps` steps at constant overlap: ~ h^2 F'' where the weights are C2, ~ h x the
// slope jump where they kink.
double LargestSecondDifference(bool smooth, int steps) {
  Scene s = MakeScene();
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
  Scene s = MakeScene(notch);
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
}  // namespace spallkit::contact
