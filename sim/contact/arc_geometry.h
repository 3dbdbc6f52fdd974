// Circular-arc segments of a curved contact surface (ContactSurface::segment_curvature).
//
// A segment a -> b with signed curvature kappa is the arc of radius rho = 1/|kappa| through a and b
// on the side its sign says: convex (kappa > 0) bulges along the segment's outward normal
// n = (dy, -dx) / L, so its centre lies behind the chord, c = m - h n; concave (kappa < 0) bulges
// into the body, c = m + h n; h = sqrt(rho^2 - L^2/4), m the chord's midpoint. Nodes placed on a
// circle then give back that circle exactly under any rigid motion, which the chord polygon does
// not: a faceted roller has to lift its centre by r (1 - cos(pi/N)) to roll over a vertex, and that
// bump comes back N times per turn with an acceleration ~ 2 pi^4 r f_spin^2 whatever N is.
#pragma once

#include <algorithm>
#include <cmath>

namespace spallkit::contact {

// Outward unit normal (dy, -dx) / L of the chord a -> b (body on the left); returns L. Zero
// normal for a zero-length chord.
inline double ChordNormal(double ax, double ay, double bx, double by, double* nx, double* ny) {
  const double ex = bx - ax, ey = by - ay, l = std::hypot(ex, ey);
  *nx = l > 0.0 ? ey / l : 0.0;
  *ny = l > 0.0 ? -ex / l : 0.0;
  return l;
}

struct Arc {
  double cx = 0.0, cy = 0.0;  // centre
  double radius = 0.0;
  bool convex = true;
};

inline Arc ArcThrough(double ax, double ay, double bx, double by, double kappa) {
  Arc arc;
  arc.radius = 1.0 / std::abs(kappa);
  arc.convex = kappa > 0.0;
  double nx, ny;
  const double l = ChordNormal(ax, ay, bx, by, &nx, &ny);
  const double h = std::sqrt(std::max(0.0, arc.radius * arc.radius - 0.25 * l * l));
  const double side = arc.convex ? -h : h;
  arc.cx = 0.5 * (ax + bx) + side * nx;
  arc.cy = 0.5 * (ay + by) + side * ny;
  return arc;
}

// Outward unit normal of the arc at its point (qx, qy): radial, away from the centre when convex.
inline void ArcNormal(const Arc& arc, double qx, double qy, double* nx, double* ny) {
  const double dx = qx - arc.cx, dy = qy - arc.cy;
  const double l = std::hypot(dx, dy);
  const double s = arc.convex ? 1.0 : -1.0;
  *nx = l > 0.0 ? s * dx / l : 0.0;
  *ny = l > 0.0 ? s * dy / l : 0.0;
}

// Chord parameter of a point q of segment a -> b: 0 at a, 1 at b (projection on the chord; monotone
// along the arc, so q lies on the arc's span iff 0 <= xi <= 1).
inline double ChordParameter(double ax, double ay, double bx, double by, double qx, double qy) {
  const double ex = bx - ax, ey = by - ay;
  const double l2 = ex * ex + ey * ey;
  return l2 > 0.0 ? ((qx - ax) * ex + (qy - ay) * ey) / l2 : 0.0;
}

}  // namespace spallkit::contact
