// Arc-blend contact: the point-contact strategy of a ContactPair for a curved slave surface
// (ContactSurface::segment_curvature, arc_geometry.h) when the surfaces are not smooth splines.
//
// A slave node projects onto the master's arcs instead of its chords (node contact, in the pair).
// A convex slave arc (a roller rim between two nodes) touches too: its closest point to a master
// arc lies on the line through the two circles' centres (or along a straight master's normal);
// where it falls inside both spans the pair of segments is an arc contact point. A roller touches
// a race at one place, so a pass keeps one arc contact: the deepest point and the points of the
// slave arcs chained to it. On the undeformed circle that is one point; where the rim is dented
// under load at a node (a valley between two arcs) it is two, and taking only the deeper one
// flips between them every step, which pumps energy into the dent. So the points are blended:
// penetration p = sum a_i p_i with weights a_i = S_i omega_i: the slave span factor
// [xi (1 - xi)]^2 times the point's share of its slave arc's master span factors [xi_m (1 -
// xi_m)]^2 (both vanish at span ends, so a point enters and leaves the blend continuously; the
// share keeps an arc's weight whole while its point crosses a master node), normal force
// -f_n grad p (the gradient of k p^2 / 2, weights included), one stick spring for the contact,
// its force spread at the arc points with the same weights. Ridge nodes (where two arcs of one
// surface kink towards the other: beside a dented node) touch as points of the blend too,
// weighted by their place in the wedge between the two arcs' end normals. The blend's nodes take
// no node contact, nor do nodes between two convex arcs; a vertex next to a straight segment (a
// spall's corner) keeps node-to-arc contact, and so does every node when no arc finds its closest
// point in span (a spall facing the master). The spring moves to or from a node's when contact
// passes between nodes and arcs. docs/CONTACT.md, "Curved surfaces".
#pragma once

#include <array>
#include <vector>

#include "sim/contact/arc_geometry.h"
#include "sim/contact/contact_law.h"
#include "sim/contact/contact_pass.h"
#include "sim/fe/nodal_state.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::contact {

class ArcBlendContact {
 public:
  // Sizes the buffers for the pass's surfaces (no allocation in the time loop).
  explicit ArcBlendContact(const ContactPass& pass);

  // Before the node loop: this step's blended arc contact; marks the nodes it stands for in
  // pass.node_owned.
  void Find(ContactPass& pass, const double* x, const double* y);
  // After the node loop: the contact law at the blended point into pass.point_slot (with the
  // spring hand-over to and from nodes).
  void Forces(ContactPass& pass, const ContactLaw& law, const fe::NodalState& state, double dt);
  // The point slot's forces on the nodes: -f_n grad p, friction at the arc points.
  void Scatter(const ContactPass& pass,
               const double* x,
               const double* y,
               solver::ForceLog* forces) const;
  // Surfaces far apart: no contact this step.
  void Clear() { blend_.clear(); }

 private:
  static constexpr int kCoordinates = 10;  // an arc contact point's gradient: 5 nodes x, y
  // A convex slave arc's closest point to one master segment (in both spans) or, at a ridge, a
  // node's: the master node ending that segment (master_node; xi_master = 1), or the slave node
  // ending slave_segment against the master segment (slave_node; xi = 1).
  struct Point {
    int slave_segment = -1, master_segment = -1;
    bool slave_node = false, master_node = false;
    ArcPair<double> at{};  // gap, normal, points, chord parameters
    double weight = 0.0;   // share in the blended contact (the blend's sum to 1)
    // d(penetration)/d(slave a, slave b, master a, master b, third node; x, y each)
    double grad[kCoordinates] = {};
    // A ridge point's wedge: the node beyond the ridge that bounds it (the next slave or master
    // arc's end; -1 otherwise), that arc's curvature, the point's place in the wedge (0 .. 1).
    int third_node = -1;
    double third_curvature = 0.0, wedge = 0.0;
    // Blend(): the point's share of its slave arc's master factors, and their sum.
    double omega = 0.0, master_sum = 0.0;
  };

  // Global node ids of a point's segments: slave a, slave b, master a, master b.
  static std::array<int, 4> Nodes(const ContactPass& pass, const Point& c);
  // Every arc's candidate points, then the blend: the deepest point's chain of slave arcs.
  void FindCandidates(ContactPass& pass, const double* x, const double* y);
  void ChainDeepest(ContactPass& pass);
  // Weights of the blend's points and the gradient of the blended penetration (Point::grad).
  void Blend(const ContactPass& pass, const double* x, const double* y);

  std::vector<Point> candidates_, blend_;
  std::vector<char> rim_node_;            // per slave node: between two convex arcs (fixed)
  std::vector<Arc<double>> master_arcs_;  // curved master: its arcs, computed once per step
  std::vector<long> master_arc_stamp_;    // the step (stamp_) each was computed at
  long stamp_ = 0;
};

}  // namespace spallkit::sim::contact
