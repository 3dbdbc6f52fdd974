// Penalty contact with Coulomb friction between two surfaces (a ForceContributor).
//
// Each step, for every slave node p the pair finds the closest point c on the master surface (grid
// candidates, see segment_grid.h) and the signed gap g = (p - c) . n with n the master's outward
// normal. When -capture_depth <= g < 0 the node is in contact (contact_law.h):
//   normal:     F_n = k * (-g) + damping, with damping = ratio * 2 sqrt(k m*) * (-v_n), F_n >= 0
//   tangential: a spring per slave node, F_t <- F_t - k_t v_t dt, capped at mu(|v_t|) F_n
// The force acts on the slave node along +n / +t and, split (1 - xi, xi), with opposite sign on
// the master segment's two nodes. With `symmetric` a second pass swaps the roles of the surfaces.
//
// A curved slave surface also touches as one point per pass, by one of two strategies:
//  - arc blend (arc_blend_contact.h): the slave's convex arcs against the master's arcs or chords,
//    the points near the deepest one blended into one conservative contact;
//  - spline (spline_contact.h, options.smooth_surfaces): both surfaces as cubic B-splines, one
//    Newton point with C2 weights.
// Nodes the point contact stands for take no node contact; the stick spring moves between the
// point and the nodes as the contact walks.
//
// Penalty law and stability (see penalty.h, docs/CONTACT.md):
//  - bulk modulus: k = f K L^2 / A t of the master segment; StableTimeStep() returns
//      safety * (2 / omega) * (sqrt(1 + zeta^2) - zeta),  omega^2 = k_max (1/m_s,min + 1/m_m,min)
//    i.e. the largest contact spring between the lightest slave and master nodes (conservative).
//    It bounds contact alone: with f = 0.1 on steel quads that is ~1.8x the element step.
//  - mass / time step: k = s m* / dt_ref^2, dt_ref the step of the first AddForces (or the
//    option); (omega dt_ref)^2 <= 2 s, so the same formula gives a step >= dt_ref / sqrt(2 s).
//  - constant: k given.
//
// Energy (all in J, for the solver's balance): StoredEnergy() = sum 1/2 k g^2 + 1/2 F_t^2 / k_t
// over contacts now closed; DissipatedEnergy() = friction slip work (return mapping, exact for
// the capped force) + normal damping work (c v_n^2 dt) + tangential spring energy released when a
// contact opens.
//
// Cost: surfaces far apart are rejected by bounding boxes (two min/max passes over the surface
// nodes, no search). The grid is rebuilt only when a master node has moved margin/2. All buffers
// are sized at construction or at the first step: nothing is allocated in the time loop unless a
// rebuild has to grow the grid. Slave nodes are processed in parallel (OpenMP) into per-node slots
// that are scattered in fixed order, so results are bit-identical for any thread count.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sim/contact/arc_blend_contact.h"
#include "sim/contact/contact_law.h"
#include "sim/contact/contact_options.h"
#include "sim/contact/contact_pass.h"
#include "sim/contact/friction.h"
#include "sim/contact/penalty.h"
#include "sim/contact/segment_grid.h"
#include "sim/contact/spline_contact.h"
#include "sim/contact/surface.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::contact {

// Forces of one step, summed over the pair, as they act on the FIRST surface given to the pair
// (the slave surface of the first pass): normal and tangential resultants (N, whole thickness).
struct ContactResultant {
  double normal_x = 0.0, normal_y = 0.0;
  double tangential_x = 0.0, tangential_y = 0.0;
  double normal_magnitude_sum = 0.0;  // sum over contact nodes of |F_n| (N)
  int active_nodes = 0;               // slave nodes in contact (both passes)
  double max_penetration = 0.0;       // m, >= 0
  double NormalMagnitude() const;     // |(normal_x, normal_y)|
};

class ContactPair : public solver::ForceContributor {
 public:
  // slave and master are copied. With the bulk modulus law both surfaces used as master need
  // bulk_stiffness (MakeSurface). Throws InputError when options or surfaces are unusable.
  ContactPair(std::string name,
              ContactSurface slave,
              ContactSurface master,
              const ContactPairOptions& options);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  // The pair only reads positions, velocities and masses and only adds nodal forces: its forces
  // are computed into a log (any thread) and applied in order (solver::ForceContributor).
  bool SplitsForces() const override { return true; }
  void ComputeForces(const fe::NodalState& state, double t, double dt) override;
  void ApplyForces(fe::NodalState& state) const override { forces_.ApplyTo(state); }
  double StableTimeStep(const fe::NodalState& state) const override;
  double StoredEnergy() const override { return stored_energy_; }
  double DissipatedEnergy() const override { return friction_dissipation_ + damping_dissipation_; }
  std::string Name() const override { return name_; }
  // Checkpoint/restart: friction springs, energies, search settings. The grid is rebuilt after a
  // load; candidates are complete either way, so results are identical.
  std::string SaveState() const override;
  void LoadState(const std::string& bytes) override;

  double FrictionDissipation() const { return friction_dissipation_; }
  double DampingDissipation() const { return damping_dissipation_; }
  const ContactResultant& Resultant() const { return resultant_; }
  // Signed gap of every node of the first surface against the second (m; negative = penetration,
  // +infinity where no master segment is within the search margin), as of the last step.
  const std::vector<double>& SlaveGaps() const { return passes_[0].gap; }
  // Normal force (N, >= 0) on node i of the first surface from the first pass, as of the last step.
  double SlaveNormalForce(int i) const { return passes_[0].slots[i].fn; }
  const ContactSurface& slave() const { return passes_[0].slave; }
  const ContactSurface& master() const { return passes_[0].master; }
  const ContactPairOptions& options() const { return options_; }
  // Number of grid (re)builds so far, both passes: the search cost diagnostic.
  int num_rebuilds() const { return num_rebuilds_; }

 private:
  // A pass and its point-contact strategy (at most one, for a curved slave surface).
  struct Pass : ContactPass {
    std::optional<ArcBlendContact> arcs;
    std::optional<SplineContact> spline;
  };

  void RunPass(Pass& pass, const fe::NodalState& state, double dt, double sign);
  // Bounding boxes and grid: false (springs released, no contact) when the surfaces are apart.
  bool ReadyPass(Pass& pass, const double* x, const double* y);
  // Node-to-segment contact of every slave node not taken by the point contact (in parallel).
  void NodeContacts(Pass& pass, const fe::NodalState& state, double dt);
  // The pass's forces into the log and its energies into the pair's, in a fixed order.
  void Scatter(const Pass& pass, const double* x, const double* y, double sign);
  void AddToResultant(const ContactSlot& slot, double sign);  // sign -1: second pass

  std::string name_;
  ContactPairOptions options_;
  ContactLaw law_;
  std::vector<Pass> passes_;
  ContactResultant resultant_;
  double stored_energy_ = 0.0, friction_dissipation_ = 0.0, damping_dissipation_ = 0.0;
  solver::ForceLog forces_;  // this step's nodal forces (ComputeForces), added by ApplyForces
  int num_rebuilds_ = 0;
  bool initialised_ = false;
  bool spline_offsets_known_ = false;  // smooth_surfaces: offsets measured (first step) or loaded
  std::vector<double> max_penalty_;    // per pass: largest bulk-modulus penalty of its master
  // StableTimeStep's spring/mass bound for the nodal state it last scanned (masses are constant
  // during a run).
  mutable const fe::NodalState* min_inverse_mass_state_ = nullptr;
  mutable double cached_omega2_ = 0.0;
};

// Convenience for model builders and `spall bench fe`: a pair between two curves of a mesh,
// surfaces built with MakeSurface (one bulk modulus per part or one for all).
ContactPair MakeContactPair(const fe::Mesh& mesh,
                            const std::string& slave_curve,
                            const std::string& master_curve,
                            const std::vector<double>& bulk_modulus,
                            double thickness,
                            const ContactPairOptions& options);

}  // namespace spallkit::sim::contact
