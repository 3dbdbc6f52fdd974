// Uniform-grid bucket sort of surface segments, so that finding the segments near a point costs
// O(1) and a whole contact search O(n).
//
// Build() puts every segment into each cell its bounding box, grown by `margin`, overlaps
// (counting sort into one flat array: no per-cell allocation; storage is reused between builds).
// Candidates(p) then returns every segment whose grown box may contain p, i.e. a superset of the
// segments within `margin` of p at build time. The contact pair rebuilds the grid when some master
// node has moved more than margin/2 since the last build, so candidates stay complete for the
// capture distance (<= margin/2) without sorting every step.
//
// Cell size: the mean segment length grown by the margin, enlarged where needed so the grid has at
// most ~4 cells per segment (a large ring with a fine surface would otherwise need millions).
#pragma once

#include <span>
#include <vector>

#include "sim/contact/surface.h"

namespace spallkit::sim::contact {

class SegmentGrid {
 public:
  // Bins the segments of `surface` at positions (x, y) (indexed by global node id).
  void Build(const ContactSurface& surface, const double* x, const double* y, double margin);

  // Segment indices whose grown bounding box overlaps the cell of (px, py); empty outside the grid.
  std::span<const int> Candidates(double px, double py) const {
    const int ix = static_cast<int>((px - x_min_) * inv_cell_);
    const int iy = static_cast<int>((py - y_min_) * inv_cell_);
    if (px < x_min_ || py < y_min_ || ix >= nx_ || iy >= ny_) return {};
    const int cell = iy * nx_ + ix;
    return {entries_.data() + start_[cell], entries_.data() + start_[cell + 1]};
  }

  bool built() const { return nx_ > 0; }
  double cell_size() const { return cell_; }
  int num_cells() const { return nx_ * ny_; }
  int num_entries() const { return static_cast<int>(entries_.size()); }

 private:
  double x_min_ = 0.0, y_min_ = 0.0, cell_ = 1.0, inv_cell_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> start_;    // CSR offsets, size num_cells + 1
  std::vector<int> entries_;  // segment ids, cell by cell
  std::vector<int> box_;      // scratch: per segment ix0, iy0, ix1, iy1
};

// Closest point of a surface to a point, over a set of candidate segments.
struct Projection {
  int segment = -1;           // closest segment (-1: none)
  double xi = 0.0;            // parameter on it, 0 at node a, 1 at node b (clamped)
  double distance = 0.0;      // Euclidean distance to the closest point
  double gap = 0.0;           // signed: (p - c) . n, negative = penetration
  double nx = 0.0, ny = 0.0;  // unit outward normal used (segment normal, or vertex normal at ends)
  double cx = 0.0, cy = 0.0;  // closest point
};

// Closest point over `candidates` (ties broken by the lower segment index, so results do not
// depend on candidate order). Where the closest point is a vertex (xi clamped to 0 or 1) the normal
// is the normalised sum of the normals of the segments meeting there.
Projection ProjectOntoSurface(const ContactSurface& surface,
                              const double* x,
                              const double* y,
                              double px,
                              double py,
                              std::span<const int> candidates);

}  // namespace spallkit::sim::contact
