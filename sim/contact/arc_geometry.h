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

namespace spallkit::sim::contact {

// The helpers are templates so that arc_blend_contact.cc can evaluate the same geometry on
// automatic-differentiation numbers (ceres::Jet) for the exact gradient of a penetration; T =
// double elsewhere. (Unqualified sqrt: std's for double, ceres' by argument lookup for Jet. Lengths
// are sqrt(x^2 + y^2), not hypot: coordinates are metres, nothing to overflow, and hypot is much
// slower.)

// Outward unit normal (dy, -dx) / L of the chord a -> b (body on the left); returns L. Zero
// normal for a zero-length chord.
template <typename T>
T ChordNormal(const T& ax, const T& ay, const T& bx, const T& by, T* nx, T* ny) {
  using std::sqrt;
  const T ex = bx - ax, ey = by - ay, l = sqrt(ex * ex + ey * ey);
  *nx = l > 0.0 ? T(ey / l) : T(0.0);
  *ny = l > 0.0 ? T(-ex / l) : T(0.0);
  return l;
}

template <typename T = double>
struct Arc {
  T cx = T(0.0), cy = T(0.0);  // centre
  double radius = 0.0;
  bool convex = true;
};

template <typename T>
Arc<T> ArcThrough(const T& ax, const T& ay, const T& bx, const T& by, double kappa) {
  using std::sqrt;
  Arc<T> arc;
  arc.radius = 1.0 / std::abs(kappa);
  arc.convex = kappa > 0.0;
  T nx, ny;
  const T l = ChordNormal(ax, ay, bx, by, &nx, &ny);
  const T h2 = arc.radius * arc.radius - 0.25 * l * l;
  const T h = h2 > 0.0 ? T(sqrt(h2)) : T(0.0);
  const T side = arc.convex ? T(-h) : h;
  arc.cx = 0.5 * (ax + bx) + side * nx;
  arc.cy = 0.5 * (ay + by) + side * ny;
  return arc;
}

// Outward unit normal of the arc at its point (qx, qy): radial, away from the centre when convex.
inline void ArcNormal(const Arc<double>& arc, double qx, double qy, double* nx, double* ny) {
  const double dx = qx - arc.cx, dy = qy - arc.cy;
  const double l = std::hypot(dx, dy);
  const double s = arc.convex ? 1.0 : -1.0;
  *nx = l > 0.0 ? s * dx / l : 0.0;
  *ny = l > 0.0 ? s * dy / l : 0.0;
}

// Chord parameter of a point q of segment a -> b: 0 at a, 1 at b (projection on the chord; monotone
// along the arc, so q lies on the arc's span iff 0 <= xi <= 1).
template <typename T>
T ChordParameter(const T& ax, const T& ay, const T& bx, const T& by, const T& qx, const T& qy) {
  const T ex = bx - ax, ey = by - ay;
  const T l2 = ex * ex + ey * ey;
  return l2 > 0.0 ? T(((qx - ax) * ex + (qy - ay) * ey) / l2) : T(0.0);
}

// Closest points of a convex slave arc s (curvature ks > 0) and a master segment m (an arc of
// curvature km, or straight when km = 0): on the line through the two centres (straight master:
// along its normal). gap < 0 is overlap, measured along n, the master's outward normal there.
template <typename T>
struct ArcPair {
  T gap, nx, ny;
  T px, py, qx, qy;  // on the slave arc / the master segment
  T xi, xi_master;   // their chord parameters (in both spans iff both in [0, 1])
};
// `marc` is the master's arc, or null for a straight master segment m.
template <typename T>
bool ArcClosestPoints(const Arc<T>& arc, const T m[4], const Arc<T>* marc, ArcPair<T>* out) {
  using std::sqrt;
  ArcPair<T>& c = *out;
  if (marc) {
    const T dx = arc.cx - marc->cx, dy = arc.cy - marc->cy, d2 = dx * dx + dy * dy;
    if (!(d2 > 0.0)) return false;
    const T d = sqrt(d2), ux = dx / d, uy = dy / d;
    c.qx = marc->cx + marc->radius * ux;
    c.qy = marc->cy + marc->radius * uy;
    if (marc->convex) {  // two convex circles: outside each other
      c.gap = d - arc.radius - marc->radius;
      c.nx = ux, c.ny = uy;
    } else {  // the slave circle inside the master's
      c.gap = marc->radius - d - arc.radius;
      c.nx = -ux, c.ny = -uy;
    }
    c.px = arc.cx - arc.radius * c.nx;
    c.py = arc.cy - arc.radius * c.ny;
  } else {
    if (!(ChordNormal(m[0], m[1], m[2], m[3], &c.nx, &c.ny) > 0.0)) return false;
    c.px = arc.cx - arc.radius * c.nx;
    c.py = arc.cy - arc.radius * c.ny;
    c.gap = (c.px - m[0]) * c.nx + (c.py - m[1]) * c.ny;
    c.qx = c.px - c.gap * c.nx;
    c.qy = c.py - c.gap * c.ny;
  }
  c.xi_master = ChordParameter(m[0], m[1], m[2], m[3], c.qx, c.qy);
  return true;
}
// Closest points of a convex slave arc and a master NODE (nx_, ny_): where the master surface has a
// ridge (two arcs meeting at an angle pointing at the slave), the slave circle's closest master
// point is the node itself for every centre in the wedge between the two arcs' end normals. The
// gap is the node's distance from the circle, along the line from the node to the circle's centre;
// at the wedge's edges it equals, with its gradient, the neighbouring arc's (the distance to a
// curve is C1 across a ridge), so contact passes arc -> node -> arc without a jump. xi_master is 1:
// the node is the end (b) of the master segment the candidate is filed under.
template <typename T>
bool ArcNodeClosestPoints(const Arc<T>& arc, const T& nx_, const T& ny_, ArcPair<T>* out) {
  using std::sqrt;
  ArcPair<T>& c = *out;
  const T dx = arc.cx - nx_, dy = arc.cy - ny_, d2 = dx * dx + dy * dy;
  if (!(d2 > 0.0)) return false;
  const T d = sqrt(d2);
  c.nx = dx / d, c.ny = dy / d;
  c.gap = d - arc.radius;
  c.px = arc.cx - arc.radius * c.nx;
  c.py = arc.cy - arc.radius * c.ny;
  c.qx = nx_, c.qy = ny_;
  c.xi_master = T(1.0);
  return true;
}

// Closest points of a slave NODE (px_, py_) and a master segment (its arc `marc`, or the straight
// segment m when null): the same ridge, on the slave side (a rim node between two arcs that kink
// towards the master, the neighbours of a dented node). xi is 1 (the node ends the slave segment
// the candidate is filed under).
template <typename T>
bool NodeArcClosestPoints(
    const T& px_, const T& py_, const T m[4], const Arc<T>* marc, ArcPair<T>* out) {
  using std::sqrt;
  ArcPair<T>& c = *out;
  c.px = px_, c.py = py_;
  if (marc) {
    const T dx = px_ - marc->cx, dy = py_ - marc->cy, d2 = dx * dx + dy * dy;
    if (!(d2 > 0.0)) return false;
    const T d = sqrt(d2), ux = dx / d, uy = dy / d;
    c.qx = marc->cx + marc->radius * ux;
    c.qy = marc->cy + marc->radius * uy;
    if (marc->convex) {
      c.gap = d - marc->radius;
      c.nx = ux, c.ny = uy;
    } else {
      c.gap = marc->radius - d;
      c.nx = -ux, c.ny = -uy;
    }
  } else {
    if (!(ChordNormal(m[0], m[1], m[2], m[3], &c.nx, &c.ny) > 0.0)) return false;
    c.gap = (px_ - m[0]) * c.nx + (py_ - m[1]) * c.ny;
    c.qx = px_ - c.gap * c.nx;
    c.qy = py_ - c.gap * c.ny;
  }
  c.xi_master = ChordParameter(m[0], m[1], m[2], m[3], c.qx, c.qy);
  c.xi = T(1.0);
  return true;
}

// The same from the segments' nodes s (slave, curvature ks > 0) and m (curvature km, 0: straight),
// with the slave's chord parameter too.
template <typename T>
bool ArcClosestPoints(const T s[4], double ks, const T m[4], double km, ArcPair<T>* out) {
  const Arc<T> arc = ArcThrough(s[0], s[1], s[2], s[3], ks);
  Arc<T> marc;
  if (km != 0.0) marc = ArcThrough(m[0], m[1], m[2], m[3], km);
  if (!ArcClosestPoints(arc, m, km != 0.0 ? &marc : nullptr, out)) return false;
  out->xi = ChordParameter(s[0], s[1], s[2], s[3], out->px, out->py);
  return true;
}
// The same for a slave node (p: its x, y) and a master segment m of curvature km.
template <typename T>
bool NodeArcClosestPoints(const T p[2], const T m[4], double km, ArcPair<T>* out) {
  Arc<T> marc;
  if (km != 0.0) marc = ArcThrough(m[0], m[1], m[2], m[3], km);
  return NodeArcClosestPoints(p[0], p[1], m, km != 0.0 ? &marc : nullptr, out);
}
// The same for a slave arc and a master node (n: its x, y).
template <typename T>
bool ArcNodeClosestPoints(const T s[4], double ks, const T n[2], ArcPair<T>* out) {
  const Arc<T> arc = ArcThrough(s[0], s[1], s[2], s[3], ks);
  if (!ArcNodeClosestPoints(arc, n[0], n[1], out)) return false;
  out->xi = ChordParameter(s[0], s[1], s[2], s[3], out->px, out->py);
  return true;
}

}  // namespace spallkit::sim::contact
