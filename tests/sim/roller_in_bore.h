// Shared scene of the curved and smooth contact tests (contact_curved_test.cc,
// contact_smooth_test.cc): a 40-node roller rim (r = 3.25 mm) in a 283-node bore (22.5 mm), the
// 0.5 mm bearing mesh's counts, constant penalty k = 1e9 N/m; and the two energy checks both
// contact kinds must pass (work along a rolling path, work over a closed deform cycle).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/constants.h"
#include "sim/contact/contact_pair.h"
#include "sim/contact/surface.h"
#include "sim/fe/nodal_state.h"

namespace spallkit::sim::contact::roller_in_bore {

constexpr double kR = 3.25e-3, kBore = 22.5e-3, kK = 1e9;  // roller, bore radii (m); N/m
constexpr int kRim = 40, kRace = 283;

// Nodes 0..kRim-1: the roller (CCW, body on the left), then the bore (CW, ring body on the left).
struct Scene {
  fe::NodalState state;
  ContactSurface roller, bore;
};

// The rim radius of node i: nodes kRim-1, 0 and 1 sit `notch` deeper (a flat-bottomed pit: the
// segments around them are straight and its corners kinks).
inline double RimRadius(int i, double notch) {
  return (i == 0 || i == 1 || i == kRim - 1) ? kR - notch : kR;
}

// curved: mark the rim's and the bore's arcs (MarkCircularArcs), else both stay faceted.
inline Scene MakeScene(bool curved, double notch = 0.0) {
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
  if (curved) {
    // Roller curvature is marked on its reference pose, the circle at the origin.
    std::vector<double> x(kRim), y(kRim);
    for (int i = 0; i < kRim; ++i) {
      x[i] = RimRadius(i, notch) * std::cos(2 * kPi * i / kRim);
      y[i] = RimRadius(i, notch) * std::sin(2 * kPi * i / kRim);
    }
    EXPECT_EQ(MarkCircularArcs(&s.roller, x.data(), y.data(), {0, 0, kR}, 1e-12),
              notch > 0 ? kRim - 4 : kRim);
    EXPECT_EQ(MarkCircularArcs(&s.bore, s.state.x.data(), s.state.y.data(), {0, 0, kBore}, 1e-12),
              kRace);
    EXPECT_GT(s.roller.segment_curvature[2], 0);  // convex
    EXPECT_LT(s.bore.segment_curvature[0], 0);    // concave
  }
  return s;
}

// Roller at centre distance d along direction theta, rotated by phi.
inline void PlaceRoller(Scene* s, double d, double theta, double phi, double notch = 0.0) {
  for (int i = 0; i < kRim; ++i) {
    const double a = 2 * kPi * i / kRim + phi;
    s->state.x[i] = d * std::cos(theta) + RimRadius(i, notch) * std::cos(a);
    s->state.y[i] = d * std::sin(theta) + RimRadius(i, notch) * std::sin(a);
  }
}

inline ContactPairOptions ConstantPenalty(bool smooth = false) {
  ContactPairOptions o;
  o.penalty_law = PenaltyLaw::kConstant;
  o.constant_stiffness = kK;
  o.smooth_surfaces = smooth;
  return o;
}

struct Force {
  double fx = 0, fy = 0, moment = 0, stored = 0;  // on the roller; moment about its centre
};

inline Force Evaluate(ContactPair& pair, Scene* s, double d, double theta) {
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

// Trapezoidal work of the nodal forces between two evaluations, accumulated.
struct WorkMeter {
  std::vector<double> fx, fy, x, y;
  double work = 0;
  void Step(const fe::NodalState& st, int nodes) {
    if (!fx.empty())
      for (int i = 0; i < nodes; ++i)
        work += 0.5 * (st.fx[i] + fx[i]) * (st.x[i] - x[i]) +
                0.5 * (st.fy[i] + fy[i]) * (st.y[i] - y[i]);
    fx.assign(st.fx.begin(), st.fx.begin() + nodes);
    fy.assign(st.fy.begin(), st.fy.begin() + nodes);
    x.assign(st.x.begin(), st.x.begin() + nodes);
    y.assign(st.y.begin(), st.y.begin() + nodes);
  }
};

// A path that rolls, slides and presses the roller (over ~4.5 rim segments, overlap 5 -> 15 um,
// frictionless) in a fixed bore: returns the work on the roller and sets the change of the stored
// energy (0.1 J).
inline double RollingPathWork(const ContactPairOptions& options, double* energy_change) {
  Scene s = MakeScene(true);
  ContactPair pair("roller/bore", s.roller, s.bore, options);
  const int n = 4000;
  double e0 = 0, e1 = 0;
  WorkMeter meter;
  for (int step = 0; step <= n; ++step) {
    const double u = static_cast<double>(step) / n;
    const double d = kBore - kR + 5e-6 + 10e-6 * std::sin(0.5 * kPi * u);  // 5 -> 15 um
    const double theta = -1.2 + 0.05 * u, phi = 0.7 * u;
    PlaceRoller(&s, d, theta, phi);
    const Force f = Evaluate(pair, &s, d, theta);
    if (step == 0) e0 = f.stored;
    if (step == n) e1 = f.stored;
    meter.Step(s.state, kRim);
  }
  *energy_change = e1 - e0;
  return meter.work;
}

// A closed cycle: press, stretch both surfaces tangentially out of phase (a chord of fixed
// curvature that stretches moves its arc outwards by the growing sagitta), release. Returns the
// work on all nodes (zero for a conservative contact) and sets the peak stored energy.
inline double DeformCycleWork(const ContactPairOptions& options, double* peak) {
  Scene s = MakeScene(true);
  ContactPair pair("roller/bore", s.roller, s.bore, options);
  const double theta = -1.2;
  const std::vector<double> bx(s.state.x.begin() + kRim, s.state.x.end());
  const std::vector<double> by(s.state.y.begin() + kRim, s.state.y.end());
  const int n = 4000;
  *peak = 0;
  WorkMeter meter;
  for (int step = 0; step <= n; ++step) {
    const double u = static_cast<double>(step) / n;
    const double d = kBore - kR + 10e-6 + 5e-6 * std::sin(2 * kPi * u);
    const double strain = 2e-3 * std::cos(2 * kPi * u);  // tangential, near the contact
    PlaceRoller(&s, d, theta, 0.013);
    const double cx = d * std::cos(theta), cy = d * std::sin(theta);
    for (int i = 0; i < kRim; ++i) {  // slide each node along the rim by strain R sin(a - theta)
      const double a = std::atan2(s.state.y[i] - cy, s.state.x[i] - cx);
      const double b = a + strain * std::sin(a - theta);
      s.state.x[i] = cx + kR * std::cos(b);
      s.state.y[i] = cy + kR * std::sin(b);
    }
    for (int j = 0; j < kRace; ++j) {  // and the bore's, out of phase
      const double a = std::atan2(by[j], bx[j]);
      const double b = a - 0.5 * strain * std::sin(a - theta);
      s.state.x[kRim + j] = kBore * std::cos(b);
      s.state.y[kRim + j] = kBore * std::sin(b);
    }
    const Force f = Evaluate(pair, &s, d, theta);
    *peak = std::max(*peak, f.stored);
    meter.Step(s.state, kRim + kRace);
  }
  return meter.work;
}

}  // namespace spallkit::sim::contact::roller_in_bore
