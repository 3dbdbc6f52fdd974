#include "sim/contact/spline_surface.h"

#include <algorithm>
#include <cmath>

#include "sim/contact/arc_geometry.h"

namespace spallkit::sim::contact {

SplineSurface MakeSplineSurface(const ContactSurface& surface) {
  SplineSurface s;
  const int n = surface.num_nodes();
  s.next.assign(n, -1);
  s.previous.assign(n, -1);
  s.smooth.assign(n, 0);
  s.valid_span.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const int before = surface.segment_before[i], after = surface.segment_after[i];
    if (after >= 0) s.next[i] = surface.segment_b[after];
    if (before >= 0) s.previous[i] = surface.segment_a[before];
    if (surface.curved() && before >= 0 && after >= 0) {
      const double kb = surface.segment_curvature[before], ka = surface.segment_curvature[after];
      s.smooth[i] = kb * ka > 0.0;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (s.previous[i] < 0 || s.next[i] < 0 || s.next[s.next[i]] < 0) continue;
    bool ok = true;
    for (int c : s.Controls(i)) ok = ok && s.smooth[c];
    s.valid_span[i] = ok;
  }
  return s;
}

double MeasureSplineOffset(const ContactSurface& surface,
                           const SplineSurface& spline,
                           const double* x,
                           const double* y) {
  // At a node the curve passes through (x_prev + 4 x_i + x_next) / 6; the offset is the node's
  // distance from there along its outward normal (the mean of its two chords' normals).
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < surface.num_nodes(); ++i) {
    if (!spline.smooth[i]) continue;
    const int gi = surface.nodes[i], gp = surface.nodes[spline.previous[i]],
              gn = surface.nodes[spline.next[i]];
    double ax, ay, bx, by;
    ChordNormal(x[gp], y[gp], x[gi], y[gi], &ax, &ay);
    ChordNormal(x[gi], y[gi], x[gn], y[gn], &bx, &by);
    const double nx = ax + bx, ny = ay + by, l = std::sqrt(nx * nx + ny * ny);
    if (!(l > 0.0)) continue;
    const double cx = (x[gp] + 4.0 * x[gi] + x[gn]) / 6.0, cy = (y[gp] + 4.0 * y[gi] + y[gn]) / 6.0;
    sum += ((x[gi] - cx) * nx + (y[gi] - cy) * ny) / l;
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

double CubicBSpline(double u, double* derivative) {
  const double au = std::abs(u), sign = u > 0.0 ? 1.0 : -1.0;
  if (au < 1.0) {
    *derivative = -2.0 * u + 1.5 * u * au;
    return 2.0 / 3.0 - u * u + 0.5 * au * au * au;
  }
  if (au < 2.0) {
    *derivative = -0.5 * (2.0 - au) * (2.0 - au) * sign;
    return (2.0 - au) * (2.0 - au) * (2.0 - au) / 6.0;
  }
  *derivative = 0.0;
  return 0.0;
}

SplineBasis::SplineBasis(double t) {
  const double u = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b[0] = u * u * u / 6.0;
  b[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
  b[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
  b[3] = t3 / 6.0;
  db[0] = -0.5 * u * u;
  db[1] = 1.5 * t2 - 2.0 * t;
  db[2] = -1.5 * t2 + t + 0.5;
  db[3] = 0.5 * t2;
  ddb[0] = u;
  ddb[1] = 3.0 * t - 2.0;
  ddb[2] = 1.0 - 3.0 * t;
  ddb[3] = t;
}

SplinePoint EvaluateSpan(const ContactSurface& surface,
                         const SplineSurface& spline,
                         int span,
                         double t,
                         const double* x,
                         const double* y) {
  const SplineBasis basis(t);
  const std::array<int, 4> c = spline.Controls(span);
  SplinePoint p{};
  for (int j = 0; j < 4; ++j) {
    const int g = surface.nodes[c[j]];
    p.x += basis.b[j] * x[g], p.y += basis.b[j] * y[g];
    p.dx += basis.db[j] * x[g], p.dy += basis.db[j] * y[g];
    p.ddx += basis.ddb[j] * x[g], p.ddy += basis.ddb[j] * y[g];
  }
  return p;
}

namespace {
// Moves (span, t) along the chain until t is in [0, 1]; false if it leaves the valid spans.
bool Normalise(const SplineSurface& s, int* span, double* t) {
  while (*t < 0.0) {
    *span = s.previous[*span];
    if (*span < 0 || !s.valid_span[*span]) return false;
    *t += 1.0;
  }
  while (*t > 1.0) {
    *span = s.next[*span];
    if (*span < 0 || !s.valid_span[*span]) return false;
    *t -= 1.0;
  }
  return true;
}
double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
}  // namespace

bool SplineClosestPoints(SplineSide slave,
                         SplineSide master,
                         const double* x,
                         const double* y,
                         SplineContactPoint* point) {
  const SplineSurface& slave_spline = slave.spline;
  const SplineSurface& master_spline = master.spline;
  SplineContactPoint& p = *point;
  if (p.slave_span < 0 || p.master_span < 0 || !slave_spline.valid_span[p.slave_span] ||
      !master_spline.valid_span[p.master_span])
    return false;
  constexpr int kMaxIterations = 40;
  constexpr double kTolerance = 1e-11;  // in span parameters (a span is one node spacing)
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const SplinePoint a = EvaluateSpan(slave.surface, slave_spline, p.slave_span, p.t, x, y);
    const SplinePoint b = EvaluateSpan(master.surface, master_spline, p.master_span, p.s, x, y);
    const double dx = a.x - b.x, dy = a.y - b.y;
    // G1: the slave point projects onto the master point; G2: the tangents are parallel.
    const double g1 = dx * b.dx + dy * b.dy;
    const double g2 = Cross(a.dx, a.dy, b.dx, b.dy);
    const double j11 = a.dx * b.dx + a.dy * b.dy;
    const double j12 = -(b.dx * b.dx + b.dy * b.dy) + dx * b.ddx + dy * b.ddy;
    const double j21 = Cross(a.ddx, a.ddy, b.dx, b.dy);
    const double j22 = Cross(a.dx, a.dy, b.ddx, b.ddy);
    const double det = j11 * j22 - j12 * j21;
    if (!(std::abs(det) > 0.0)) return false;
    double step_t = -(j22 * g1 - j12 * g2) / det;
    double step_s = -(-j21 * g1 + j11 * g2) / det;
    if (!std::isfinite(step_t) || !std::isfinite(step_s)) return false;
    step_t = std::clamp(step_t, -0.5, 0.5);
    step_s = std::clamp(step_s, -0.5, 0.5);
    p.t += step_t;
    p.s += step_s;
    if (!Normalise(slave_spline, &p.slave_span, &p.t) ||
        !Normalise(master_spline, &p.master_span, &p.s))
      return false;
    if (std::abs(step_t) < kTolerance && std::abs(step_s) < kTolerance) {
      if (!(j11 < 0.0)) return false;  // tangents the same way: the far side, not facing
      const SplinePoint sa = EvaluateSpan(slave.surface, slave_spline, p.slave_span, p.t, x, y);
      const SplinePoint sb = EvaluateSpan(master.surface, master_spline, p.master_span, p.s, x, y);
      const double l = std::sqrt(sb.dx * sb.dx + sb.dy * sb.dy);
      if (!(l > 0.0)) return false;
      p.nx = sb.dy / l, p.ny = -sb.dx / l;
      p.gap =
          (sa.x - sb.x) * p.nx + (sa.y - sb.y) * p.ny - slave_spline.offset - master_spline.offset;
      return true;
    }
  }
  return false;
}

}  // namespace spallkit::sim::contact
