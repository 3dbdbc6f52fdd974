// Smooth (cubic B-spline) contact surfaces: the race contact of `model.race_contact = "smooth"`.
//
// Why: a point contact force applied to FE nodes with the chord's linear weights (1 - xi, xi), or
// the arc contact's, changes its slope every time the contact crosses a node. On the full-FE
// bearing that broadband excitation drives the rings' 5-8 kHz modes (docs/BEARING_MODEL.md,
// "Limits"); on the hybrid model, spreading its raceway contact over two nodes with a hat is 10x
// louder than a C2 kernel over four.
//
// What: the nodes of a smooth part of a surface (both neighbouring segments arcs of the same sense:
// a roller rim, a raceway) are the control points of a uniform cubic B-spline c(u). On nodes
// spaced evenly on a circle of radius r the curve is a circle of radius r - r (1 - cos(dphi)) / 3
// to within r dphi^4 / 100 (0.04 um on a 0.5 mm roller rim), so the true surface is c + o n with
// a constant signed offset o per surface (+ convex, - concave), measured on the reference nodes.
// Two such surfaces touch where c_s(u) - c_m(v) is normal to the master (the projection) and the
// two tangents are parallel (the deepest point): SplineClosestPoints solves that by Newton. There
// the gap g = (c_s - c_m) . n_m - o_s - o_m is stationary in u and v, so its gradient is the
// B-spline weights times the normal: a force f n on the slave's control points B_j(u) f n and
// -B_k(v) f n on the master's is exactly -grad(k g^2 / 2) (conservative), and its weights are C2
// in the contact's position.
#pragma once

#include <array>
#include <vector>

#include "sim/contact/surface.h"

namespace spallkit::sim::contact {

// A surface's B-spline view. Span i runs from local node i to the next node along the chain; its
// control points are the node before i, i, and the two after. A span is valid when all four are
// smooth nodes.
struct SplineSurface {
  std::vector<int> next, previous;  // per local node: neighbours along the chain (-1 at open ends)
  std::vector<char> smooth;         // per local node: both segments arcs of the same sense
  std::vector<char> valid_span;     // per local node: span starting there is valid
  double offset = 0.0;              // m, true surface = c + offset * outward normal

  // Control points (local node indices) of span i.
  std::array<int, 4> Controls(int i) const {
    const int b = next[i];
    return {previous[i], i, b, next[b]};
  }
};

// Builds the view (neighbours, smooth nodes, valid spans) of a curved surface (segment_curvature
// set); offset 0 until MeasureSplineOffset.
SplineSurface MakeSplineSurface(const ContactSurface& surface);
// The surface's offset (m) from its spline on the positions x, y (the reference ones: for nodes
// evenly spaced on a circle of radius r, +-r (1 - cos dphi) / 3), averaged over the smooth nodes.
double MeasureSplineOffset(const ContactSurface& surface,
                           const SplineSurface& spline,
                           const double* x,
                           const double* y);

// The uniform cubic B-spline B3(u) (support |u| < 2, C2) and its derivative: the shape that
// SplineBasis evaluates span by span, for kernels at arbitrary positions (the hybrid's raceway).
double CubicBSpline(double u, double* derivative);

// Uniform cubic B-spline basis at t in [0, 1]: weights, first and second derivatives.
struct SplineBasis {
  double b[4], db[4], ddb[4];
  explicit SplineBasis(double t);
};

// A point of a span: position, d/dt, d2/dt2 (global coordinates).
struct SplinePoint {
  double x, y, dx, dy, ddx, ddy;
};
SplinePoint EvaluateSpan(const ContactSurface& surface,
                         const SplineSurface& spline,
                         int span,
                         double t,
                         const double* x,
                         const double* y);

// Where two spline surfaces touch (or come closest): span and parameter on each side, the gap
// between the true surfaces (negative: overlap) along n, the master's outward unit normal.
struct SplineContactPoint {
  int slave_span = -1, master_span = -1;
  double t = 0.0, s = 0.0;
  double gap = 0.0, nx = 0.0, ny = 0.0;
};

// Newton from the start in *point (spans and parameters); moves across spans as the parameters
// leave [0, 1]. Returns false when it leaves the valid spans or does not converge; then *point
// keeps the last iterate.
// A surface and its B-spline view.
struct SplineSide {
  const ContactSurface& surface;
  const SplineSurface& spline;
};
bool SplineClosestPoints(SplineSide slave,
                         SplineSide master,
                         const double* x,
                         const double* y,
                         SplineContactPoint* point);

}  // namespace spallkit::sim::contact
