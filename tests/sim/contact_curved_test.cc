// Curved contact surfaces (contact_pair.h, arc_geometry.h): a polygon of nodes on a circle pressed
// into a circular bore touches as the circle does. Checked against the analytic overlap of two
// circles: the force is k * overlap along the line of centres whatever the polygon's rotation
// (the faceted surfaces' force swings with it), it has no moment about the roller's centre, and it
// is conservative (work along a rolling-and-sliding path = change of the stored energy).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sim/contact/contact_pair.h"
#include "sim/contact/surface.h"
#include "sim/fe/nodal_state.h"
#include "tests/sim/roller_in_bore.h"

namespace spallkit::sim::contact {
namespace {

using namespace roller_in_bore;  // Scene, MakeScene, PlaceRoller, Evaluate, constants

TEST(CurvedContactTest, PolygonRollerTouchesABoreAsTheCircleDoesAtEveryRotation) {
  const double overlap = 10e-6, d = kBore - kR + overlap, theta = -1.2;
  for (bool curved : {false, true}) {
    Scene s = MakeScene(curved);
    ContactPair pair("roller/bore", s.roller, s.bore, ConstantPenalty());
    double fmin = 1e300, fmax = 0;
    for (int k = 0; k < 16; ++k) {
      const double phi = 2 * kPi / kRim * k / 16.0;
      PlaceRoller(&s, d, theta, phi);
      const Force f = Evaluate(pair, &s, d, theta);
      const double fn = std::hypot(f.fx, f.fy);
      fmin = std::min(fmin, fn);
      fmax = std::max(fmax, fn);
      if (curved) {
        SCOPED_TRACE(k);
        EXPECT_NEAR(fn, kK * overlap, 1e-6 * kK * overlap);  // one point, k * overlap
        // Along the line of centres, towards the bore's centre; no moment about the roller's.
        EXPECT_NEAR(f.fx / fn, -std::cos(theta), 1e-9);
        EXPECT_NEAR(f.fy / fn, -std::sin(theta), 1e-9);
        EXPECT_NEAR(f.moment, 0.0, 1e-9 * fn * kR);
        EXPECT_NEAR(f.stored, 0.5 * kK * overlap * overlap, 1e-6 * f.stored);
      }
    }
    // The faceted pair's force swings with the rotation (vertex sag 9.5 um ~ the overlap).
    if (curved) {
      EXPECT_LT(fmax - fmin, 1e-6 * kK * overlap);
    } else {
      EXPECT_GT(fmax - fmin, 0.5 * kK * overlap);
    }
  }
}

TEST(CurvedContactTest, ContactThroughARimNodeIsStillOneArcContact) {
  // A 512-node rim pressed 1 um into a 3072-node bore with a node of each exactly on the line of
  // centres (as a bearing mesh has at t = 0 on the load line): rounding can put the closest point a
  // hair outside both neighbouring arcs' spans; the in-span tolerance keeps it one arc contact
  // (node contact there would be three nodes at k each: 2.4 x the force).
  const int n = 512, m = 6 * n;
  const double r = 5e-3, bore = 30e-3, overlap = 1e-6, cy = -(bore - r) - overlap;
  fe::NodalState state;
  state.Resize(n + m);
  std::vector<int> rn(n), bn(m);
  for (int i = 0; i < n; ++i) {
    state.x[i] = r * std::cos(2 * kPi * i / n);
    state.y[i] = cy + r * std::sin(2 * kPi * i / n);
    rn[i] = i;
  }
  for (int j = 0; j < m; ++j) {
    state.x[n + j] = bore * std::cos(-2 * kPi * j / m);
    state.y[n + j] = bore * std::sin(-2 * kPi * j / m);
    bn[j] = n + j;
  }
  state.mass.assign(n + m, 1e-4);
  ContactSurface roller = MakeSurfaceFromChain("roller", rn, true);
  ContactSurface bore_surface = MakeSurfaceFromChain("bore", bn, true);
  ASSERT_EQ(MarkCircularArcs(&roller, state.x.data(), state.y.data(), {0, cy, r}, 1e-12), n);
  ASSERT_EQ(MarkCircularArcs(&bore_surface, state.x.data(), state.y.data(), {0, 0, bore}, 1e-12),
            m);
  ContactPair pair("roller/bore", roller, bore_surface, ConstantPenalty());
  pair.AddForces(state, 0.0, 1e-9);
  EXPECT_EQ(pair.Resultant().active_nodes, 1);
  EXPECT_NEAR(pair.Resultant().NormalMagnitude(), kK * overlap, 1e-6 * kK * overlap);
}

TEST(CurvedContactTest, ForcesAreConservativeAlongARollingPath) {
  // Work done on the roller's nodes along a path that rolls, slides and presses (frictionless,
  // trapezoidal rule) equals minus the change of the stored energy (the bore does not move).
  double energy_change = 0;
  const double work = RollingPathWork(ConstantPenalty(), &energy_change);
  const double scale = 0.5 * kK * 15e-6 * 15e-6;
  EXPECT_GT(energy_change, 0.5 * scale);  // pressed from 5 to 15 um
  EXPECT_NEAR(work, -energy_change, 1e-4 * scale) << "work " << work << " dE " << energy_change;
}

TEST(CurvedContactTest, ForcesAreConservativeWhileTheSurfacesDeform) {
  // A rigid path cannot tell how the force is shared between an arc's two nodes beyond its
  // resultant and moment; a deforming one can: stretching a chord of fixed curvature moves its arc
  // (the sagitta grows with the chord), so the pair of forces along the chord does work. Over the
  // closed cycle the work on all nodes must come back to zero.
  double peak = 0;
  const double work = DeformCycleWork(ConstantPenalty(), &peak);
  EXPECT_NEAR(work, 0.0, 1e-5 * peak)
      << "work over the cycle " << work << " J, peak stored " << peak;
}

// A rim node dented by the load (the valley a coarse mesh gets under a point load): near it two
// arcs find their closest point in span and the contact blends them. Rolling the dent through the
// contact and back, pressing and releasing, the nodal forces change smoothly (halving the steps
// halves the largest change between two steps; taking only the deeper point jumped from one arc's
// nodes to the other's) and the work over the closed path is zero.
struct PathResult {
  double work = 0, peak = 0, max_change = 0;
};
PathResult RollOverADent(int n) {
  Scene s = MakeScene(true);
  ContactPair pair("roller/bore", s.roller, s.bore, ConstantPenalty());
  const double theta = -1.2, dent = 1.5e-6;
  PathResult r;
  std::vector<double> fx_prev, fy_prev, x_prev, y_prev;
  for (int step = 0; step <= n; ++step) {
    const double u = static_cast<double>(step) / n;
    const double d = kBore - kR + 6e-6 + 3e-6 * std::sin(2 * kPi * u);
    const double phi = theta + 0.12 * std::sin(2 * kPi * u + 0.3);  // node 0 sweeps past theta
    PlaceRoller(&s, d, theta, phi);
    const double cx = d * std::cos(theta), cy = d * std::sin(theta);
    s.state.x[0] -= dent * (s.state.x[0] - cx) / kR;
    s.state.y[0] -= dent * (s.state.y[0] - cy) / kR;
    const Force f = Evaluate(pair, &s, d, theta);
    r.peak = std::max(r.peak, f.stored);
    if (step > 0) {
      double change = 0;
      for (int i = 0; i < kRim + kRace; ++i) {
        r.work += 0.5 * (s.state.fx[i] + fx_prev[i]) * (s.state.x[i] - x_prev[i]) +
                  0.5 * (s.state.fy[i] + fy_prev[i]) * (s.state.y[i] - y_prev[i]);
        change =
            std::max(change, std::hypot(s.state.fx[i] - fx_prev[i], s.state.fy[i] - fy_prev[i]));
      }
      r.max_change = std::max(r.max_change, change);
    }
    fx_prev.assign(s.state.fx.begin(), s.state.fx.end());
    fy_prev.assign(s.state.fy.begin(), s.state.fy.end());
    x_prev.assign(s.state.x.begin(), s.state.x.end());
    y_prev.assign(s.state.y.begin(), s.state.y.end());
  }
  return r;
}

TEST(CurvedContactTest, ADentedNodeRollsThroughTheContactSmoothlyAndConservatively) {
  const PathResult coarse = RollOverADent(2000), fine = RollOverADent(4000);
  EXPECT_NEAR(fine.work, 0.0, 1e-6 * fine.peak) << "work over the cycle " << fine.work;
  EXPECT_LT(fine.max_change, 0.6 * coarse.max_change)
      << "largest nodal force change per step: " << coarse.max_change << " N at 2000 steps, "
      << fine.max_change << " N at 4000";
}

// The paper's 0.25 mm mesh: a 0.25 mm rim in a 0.25 mm bore with a rim node dented 3 um by the
// load, rolled and orbited through the contact and back (the dent sweeps through, the contact
// crosses bore nodes). The nodal forces must change in proportion to the motion: the largest
// force change per step over the largest nodal displacement that step stays below twice the
// penalty stiffness, and the work over the closed path is zero. Plain product weights S * M
// without ridge points fail both: a slave arc crossing a bore node has both its points at a master
// span end, its weight ~ 0 beside another arc's point near its own end, and at the ridges beside
// the dent no arc point is in span, so the load falls to node contact with a different force.
struct FinePath {
  double stiffness = 0, work = 0, peak = 0;
};
FinePath RollAFineDentedRim(int steps, double rim_dent) {
  const int nr = 82, nb = 565;  // 0.249 and 0.250 mm spacing
  fe::NodalState st;
  st.Resize(nr + nb);
  std::vector<int> rn(nr), bn(nb);
  std::vector<double> x0(nr + nb), y0(nr + nb);
  for (int i = 0; i < nr; ++i) {
    rn[i] = i;
    x0[i] = kR * std::cos(2 * kPi * i / nr);
    y0[i] = kR * std::sin(2 * kPi * i / nr);
  }
  for (int j = 0; j < nb; ++j) {
    bn[j] = nr + j;
    st.x[nr + j] = x0[nr + j] = kBore * std::cos(-2 * kPi * j / nb);
    st.y[nr + j] = y0[nr + j] = kBore * std::sin(-2 * kPi * j / nb);
  }
  st.mass.assign(nr + nb, 1e-5);
  ContactSurface roller = MakeSurfaceFromChain("roller", rn, true);
  ContactSurface bore = MakeSurfaceFromChain("bore", bn, true);
  EXPECT_EQ(MarkCircularArcs(&roller, x0.data(), y0.data(), {0, 0, kR}, 1e-12), nr);
  EXPECT_EQ(MarkCircularArcs(&bore, x0.data(), y0.data(), {0, 0, kBore}, 1e-12), nb);
  ContactPair pair("roller/bore", roller, bore, ConstantPenalty());
  FinePath r;
  std::vector<double> fx_prev, fy_prev, x_prev, y_prev;
  for (int step = 0; step <= steps; ++step) {
    const double u = static_cast<double>(step) / steps;
    const double theta = -1.2 + 0.01 * std::sin(2 * kPi * u);  // orbits over ~1 bore segment
    const double d = kBore - kR + 9e-6 + 1e-6 * std::sin(4 * kPi * u);
    const double phi = theta + 0.08 * std::sin(2 * kPi * u + 0.3);  // the dent sweeps past
    const double cx = d * std::cos(theta), cy = d * std::sin(theta);
    for (int i = 0; i < nr; ++i) {
      const double a = 2 * kPi * i / nr + phi;
      const double rad = i == 0 ? kR - rim_dent : kR;
      st.x[i] = cx + rad * std::cos(a);
      st.y[i] = cy + rad * std::sin(a);
    }
    std::fill(st.fx.begin(), st.fx.end(), 0.0);
    std::fill(st.fy.begin(), st.fy.end(), 0.0);
    pair.AddForces(st, 0.0, 1e-9);
    r.peak = std::max(r.peak, pair.StoredEnergy());
    if (step > 0) {
      double df = 0, dx = 0;
      for (int i = 0; i < nr + nb; ++i) {
        r.work += 0.5 * (st.fx[i] + fx_prev[i]) * (st.x[i] - x_prev[i]) +
                  0.5 * (st.fy[i] + fy_prev[i]) * (st.y[i] - y_prev[i]);
        df = std::max(df, std::hypot(st.fx[i] - fx_prev[i], st.fy[i] - fy_prev[i]));
        dx = std::max(dx, std::hypot(st.x[i] - x_prev[i], st.y[i] - y_prev[i]));
      }
      r.stiffness = std::max(r.stiffness, df / dx);
    }
    fx_prev.assign(st.fx.begin(), st.fx.end());
    fy_prev.assign(st.fy.begin(), st.fy.end());
    x_prev.assign(st.x.begin(), st.x.end());
    y_prev.assign(st.y.begin(), st.y.end());
  }
  return r;
}

TEST(CurvedContactTest, AFineDentedRimKeepsItsContactStiffnessBounded) {
  const FinePath p = RollAFineDentedRim(40000, 3e-6);
  EXPECT_LT(p.stiffness, 2 * kK) << "largest force change per unit of nodal motion, N/m";
  EXPECT_NEAR(p.work, 0.0, 1e-6 * p.peak) << "work over the closed path, J";
}

}  // namespace
}  // namespace spallkit::sim::contact
