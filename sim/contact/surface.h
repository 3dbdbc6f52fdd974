// A contact surface: the chain of boundary nodes of one body, as the contact search sees it.
//
// Built from a fe::BoundaryCurve (body on the LEFT of the walk). Segment s joins local nodes
// segment_a[s] -> segment_b[s]; its outward normal is (b - a) rotated by -90 degrees, i.e.
// (dy, -dx) / L. Every segment also carries the geometric part of the bulk-modulus penalty,
// K * L^2 / A_elem * t, from the quad it bounds (set at build time from the reference mesh),
// so that the pair only multiplies by its scale factor.
#pragma once

#include <string>
#include <vector>

#include "sim/fe/mesh.h"

namespace spallkit::sim::contact {

struct ContactSurface {
  std::string name;
  bool closed = false;
  std::vector<int> nodes;      // global node ids in chain order
  std::vector<int> segment_a;  // local index (into nodes) of each segment's first node
  std::vector<int> segment_b;  // local index of each segment's second node
  // Per local node: the segment ending at it (-1 at an open start) and the one starting at it
  // (-1 at an open end). Used for vertex normals where a node projects onto a corner.
  std::vector<int> segment_before, segment_after;
  // K * L^2 / A_elem * t per segment (N/m before the scale factor); empty if unknown (surfaces
  // built from bare node chains), in which case only the mass and constant laws apply.
  std::vector<double> bulk_stiffness;
  // Curved surfaces (arc_geometry.h): per segment signed curvature 1/rho (1/m) of the circular arc
  // through its two nodes; > 0 convex (bulges along the outward normal: a roller rim, the inner
  // raceway), < 0 concave (the outer raceway), 0 straight. Empty: every segment is straight (the
  // chord). A pair projects onto the arcs and, on a curved slave surface, also lets the slave arcs
  // touch (contact_pair.h), so a polygon of nodes on a circle contacts as the circle itself.
  std::vector<double> segment_curvature;

  bool curved() const { return !segment_curvature.empty(); }
  int num_nodes() const { return static_cast<int>(nodes.size()); }
  int num_segments() const { return static_cast<int>(segment_a.size()); }
  double MeanSegmentLength(const double* x, const double* y) const;
};

// A surface from a bare chain of node ids (no stiffness data). Needs >= 1 node (>= 3 if closed);
// a single node or a node set makes a slave-only surface (no segments).
ContactSurface MakeSurfaceFromChain(const std::string& name,
                                    const std::vector<int>& nodes,
                                    bool closed);

// A surface from mesh.curves[curve_name]. bulk_modulus is per part (size mesh.num_parts()) or a
// single value for all parts; thickness is the section thickness (m). Each segment must be an
// edge of a quad walked counter-clockwise (the body on the left); otherwise InputError names the
// curve and the segment.
ContactSurface MakeSurface(const fe::Mesh& mesh,
                           const std::string& curve_name,
                           const std::vector<double>& bulk_modulus,
                           double thickness);

// A circle in the section plane (m).
struct Circle {
  double cx = 0, cy = 0, radius = 0;
};

// Marks the segments of `surface` whose two nodes lie on `circle` within `tolerance` (m,
// reference positions x, y) as arcs of that circle: curvature +1/radius where the centre is on
// the body side (convex), -1/radius where it is outside (concave). Other segments stay straight.
// Returns the number of arcs.
int MarkCircularArcs(ContactSurface* surface,
                     const double* x,
                     const double* y,
                     const Circle& circle,
                     double tolerance);

}  // namespace spallkit::sim::contact
