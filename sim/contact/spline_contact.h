// Spline contact: the point-contact strategy of a ContactPair with options.smooth_surfaces. Both
// surfaces are cubic B-splines of their smooth nodes (spline_surface.h) and touch at one point per
// pass, found by Newton from the last step's (from the slave node nearest the master on the first
// step or after a miss). Its force goes to the four control points on each side with the B-spline
// weights, which are C2 in the contact's position (the arcs' linear weights kink at every node),
// and is the exact -grad of k g^2 / 2. Nodes whose every span is smooth take no node contact; near
// a kink (a spall's corners) they do, unless the spline contact's current span uses them.
// docs/CONTACT.md, "Smooth surfaces".
#pragma once

#include <array>
#include <vector>

#include "core/checkpoint_io.h"
#include "sim/contact/contact_law.h"
#include "sim/contact/contact_pass.h"
#include "sim/contact/spline_surface.h"
#include "sim/fe/nodal_state.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::contact {

class SplineContact {
 public:
  // Both of the pass's surfaces must be curved (the pair checks).
  explicit SplineContact(const ContactPass& pass);

  // Each spline's offset from its surface, on the reference positions (the first step).
  void MeasureOffsets(const ContactPass& pass, const double* x, const double* y);
  // Before the node loop: this step's contact point; marks the nodes it stands for in
  // pass.node_owned.
  void Find(ContactPass& pass, const double* x, const double* y);
  // After the node loop: the contact law at the point into pass.point_slot (with the spring
  // hand-over to and from nodes).
  void Forces(ContactPass& pass, const ContactLaw& law, const fe::NodalState& state, double dt);
  // The point slot's force on the control points, by their B-spline weights.
  void Scatter(const ContactPass& pass, solver::ForceLog* forces) const;
  // Surfaces far apart: no contact, and no Newton start for the next step.
  void Clear() { found_ = active_ = false; }

  // Checkpoint: the measured offsets and the Newton start.
  void Save(CheckpointWriter* out) const;
  void Load(CheckpointReader* in);

 private:
  SplineSurface slave_spline_, master_spline_;
  std::vector<char> interior_;  // per slave node: every span it controls is valid
  // This step's point (the last one found is the next step's Newton start) and, while in
  // contact, its control points (global ids) and weights.
  SplineContactPoint point_;
  bool found_ = false, active_ = false;
  std::array<int, 4> slave_nodes_{}, master_nodes_{};
  std::array<double, 4> slave_weights_{}, master_weights_{};
};

}  // namespace spallkit::sim::contact
