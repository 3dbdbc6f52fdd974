#include "sim/contact/segment_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/contact/arc_geometry.h"

namespace spallkit::sim::contact {

void SegmentGrid::Build(const ContactSurface& surface,
                        const double* x,
                        const double* y,
                        double margin) {
  const int ns = surface.num_segments();
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  double length_sum = 0.0;
  for (int s = 0; s < ns; ++s) {
    const int a = surface.nodes[surface.segment_a[s]], b = surface.nodes[surface.segment_b[s]];
    x0 = std::min({x0, x[a], x[b]});
    x1 = std::max({x1, x[a], x[b]});
    y0 = std::min({y0, y[a], y[b]});
    y1 = std::max({y1, y[a], y[b]});
    length_sum += std::hypot(x[b] - x[a], y[b] - y[a]);
  }
  x0 -= margin;
  y0 -= margin;
  x1 += margin;
  y1 += margin;
  const double width = x1 - x0, height = y1 - y0;
  double cell = (ns > 0 ? length_sum / ns : 0.0) + margin;
  // At most ~4 cells per segment.
  const double min_cell = std::sqrt(width * height / (4.0 * std::max(ns, 1)));
  cell = std::max({cell, min_cell, 1e-300});
  cell_ = cell;
  inv_cell_ = 1.0 / cell;
  x_min_ = x0;
  y_min_ = y0;
  nx_ = std::max(1, static_cast<int>(width * inv_cell_) + 1);
  ny_ = std::max(1, static_cast<int>(height * inv_cell_) + 1);

  const int num_cells = nx_ * ny_;
  start_.assign(num_cells + 1, 0);
  box_.resize(4 * static_cast<size_t>(ns));
  auto clamp_x = [&](double v) {
    return std::clamp(static_cast<int>((v - x_min_) * inv_cell_), 0, nx_ - 1);
  };
  auto clamp_y = [&](double v) {
    return std::clamp(static_cast<int>((v - y_min_) * inv_cell_), 0, ny_ - 1);
  };
  for (int s = 0; s < ns; ++s) {
    const int a = surface.nodes[surface.segment_a[s]], b = surface.nodes[surface.segment_b[s]];
    int* box = &box_[4 * static_cast<size_t>(s)];
    box[0] = clamp_x(std::min(x[a], x[b]) - margin);
    box[1] = clamp_y(std::min(y[a], y[b]) - margin);
    box[2] = clamp_x(std::max(x[a], x[b]) + margin);
    box[3] = clamp_y(std::max(y[a], y[b]) + margin);
    for (int iy = box[1]; iy <= box[3]; ++iy)
      for (int ix = box[0]; ix <= box[2]; ++ix) ++start_[iy * nx_ + ix + 1];
  }
  for (int c = 0; c < num_cells; ++c) start_[c + 1] += start_[c];
  entries_.resize(start_[num_cells]);
  // Fill in segment order so each cell's list is sorted by segment id (deterministic).
  std::vector<int>& fill = box_;  // reuse: positions appended after the boxes
  const size_t fill_offset = 4 * static_cast<size_t>(ns);
  fill.resize(fill_offset + num_cells);
  std::copy(start_.begin(), start_.end() - 1, fill.begin() + fill_offset);
  for (int s = 0; s < ns; ++s) {
    const int* box = &box_[4 * static_cast<size_t>(s)];
    for (int iy = box[1]; iy <= box[3]; ++iy)
      for (int ix = box[0]; ix <= box[2]; ++ix) entries_[fill[fill_offset + iy * nx_ + ix]++] = s;
  }
}

Projection ProjectOntoSurface(const ContactSurface& surface,
                              const double* x,
                              const double* y,
                              double px,
                              double py,
                              std::span<const int> candidates) {
  Projection best;
  double best_d2 = std::numeric_limits<double>::infinity();
  const bool curved = surface.curved();
  for (int s : candidates) {
    const int a = surface.nodes[surface.segment_a[s]], b = surface.nodes[surface.segment_b[s]];
    double xi, cx, cy;
    if (curved && surface.segment_curvature[s] != 0.0) {
      // Nearest point of the arc's circle, or the nearer end where that falls outside the span.
      const Arc arc = ArcThrough(x[a], y[a], x[b], y[b], surface.segment_curvature[s]);
      const double dx = px - arc.cx, dy = py - arc.cy, d = std::hypot(dx, dy);
      cx = d > 0.0 ? arc.cx + arc.radius * dx / d : x[a];
      cy = d > 0.0 ? arc.cy + arc.radius * dy / d : y[a];
      xi = ChordParameter(x[a], y[a], x[b], y[b], cx, cy);
      if (!(xi >= 0.0 && xi <= 1.0)) {
        xi = xi > 0.5 ? 1.0 : 0.0;
        cx = xi == 0.0 ? x[a] : x[b];
        cy = xi == 0.0 ? y[a] : y[b];
      }
    } else {
      const double ex = x[b] - x[a], ey = y[b] - y[a];
      const double l2 = ex * ex + ey * ey;
      xi = l2 > 0.0 ? ((px - x[a]) * ex + (py - y[a]) * ey) / l2 : 0.0;
      xi = std::clamp(xi, 0.0, 1.0);
      cx = x[a] + xi * ex;
      cy = y[a] + xi * ey;
    }
    const double d2 = (px - cx) * (px - cx) + (py - cy) * (py - cy);
    if (d2 < best_d2 || (d2 == best_d2 && s < best.segment)) {
      best_d2 = d2;
      best.segment = s;
      best.xi = xi;
      best.cx = cx;
      best.cy = cy;
    }
  }
  if (best.segment < 0) return best;
  best.distance = std::sqrt(best_d2);
  // Outward normal of segment s at its point (qx, qy): the chord's, or the arc's radial one.
  auto segment_normal = [&](int s, double qx, double qy, double* nx, double* ny) {
    const int a = surface.nodes[surface.segment_a[s]], b = surface.nodes[surface.segment_b[s]];
    if (curved && surface.segment_curvature[s] != 0.0) {
      ArcNormal(ArcThrough(x[a], y[a], x[b], y[b], surface.segment_curvature[s]), qx, qy, nx, ny);
      return;
    }
    ChordNormal(x[a], y[a], x[b], y[b], nx, ny);
  };
  double nx, ny;
  segment_normal(best.segment, best.cx, best.cy, &nx, &ny);
  int other = -1;
  if (best.xi == 0.0) other = surface.segment_before[surface.segment_a[best.segment]];
  if (best.xi == 1.0) other = surface.segment_after[surface.segment_b[best.segment]];
  if (other >= 0) {
    double mx, my;
    segment_normal(other, best.cx, best.cy, &mx, &my);
    const double sx = nx + mx, sy = ny + my, l = std::hypot(sx, sy);
    if (l > 1e-12) {
      nx = sx / l;
      ny = sy / l;
    }
  }
  best.nx = nx;
  best.ny = ny;
  best.gap = (px - best.cx) * nx + (py - best.cy) * ny;
  return best;
}

}  // namespace spallkit::sim::contact
