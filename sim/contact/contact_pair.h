// Node-to-segment penalty contact with Coulomb friction between two surfaces (a ForceContributor).
//
// Each step, for every slave node p the pair finds the closest point c on the master surface (grid
// candidates, see segment_grid.h) and the signed gap g = (p - c) . n with n the master's outward
// normal. When -capture_depth <= g < 0 the node is in contact:
//   normal:     F_n = k * (-g) + damping, with damping = ratio * 2 sqrt(k m*) * (-v_n), F_n >= 0
//   tangential: a spring per slave node, F_t <- F_t - k_t v_t dt, capped at mu(|v_t|) F_n
// The force acts on the slave node along +n / +t and, split (1 - xi, xi), with opposite sign on
// the master segment's two nodes. With `symmetric` a second pass swaps the roles of the surfaces.
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
// over nodes now in contact; DissipatedEnergy() = friction slip work (return mapping, exact for
// the capped force) + normal damping work (c v_n^2 dt) + tangential spring energy released when a
// node leaves contact.
//
// Curved surfaces (ContactSurface::segment_curvature, arc_geometry.h): a slave node projects onto
// the master's arcs instead of its chords. A convex slave arc (a roller rim between two nodes)
// touches too: its closest point to a master arc lies on the line through the two circles'
// centres (or along a straight master's normal); where it falls inside both spans the pair of
// segments is an arc contact point. A roller touches a race at one place, so a pass keeps one arc
// contact: the deepest point and the points of the slave arcs chained to it. On the undeformed
// circle that is one point; where the rim is dented under load at a node (a valley between two
// arcs) it is two, and taking only the deeper one flips between them every step, which pumps
// energy into the dent (measured: 0.5 % of the total in 7 ms at 0.5 mm). So the points are blended:
// penetration p = sum a_i p_i with weights a_i = S_i omega_i: the slave span factor
// [xi (1 - xi)]^2 times the point's share of its slave arc's master span factors [xi_m (1 -
// xi_m)]^2 (both vanish at span ends, so a point enters and leaves the blend continuously; the
// share keeps an arc's weight whole while its point crosses a master node; BlendArcContacts),
// normal force -f_n grad p (the gradient of k p^2 / 2, weights included), one tangential spring for
// the contact, its force spread at the arc points with the same weights. Ridge nodes (where two
// arcs of one surface kink towards the other: beside a dented node) touch as points of the blend
// too, weighted by their place in the wedge between the two arcs' end normals. The blend's nodes
// take no node contact, nor do nodes between two convex arcs; a vertex next to a straight segment
// (a spall's corner) keeps node-to-arc contact, and so does every node when no arc finds its
// closest point in span (a spall facing the master). The spring moves to or from a node's when
// contact passes between nodes and arcs.
//
// Smooth surfaces (options.smooth_surfaces, spline_surface.h): instead of the arcs' blend, both
// surfaces are cubic B-splines of their smooth nodes and touch at one point per pass, found by
// Newton from the last step's (the slave node nearest the master on the first step or after a
// miss). Its force goes to the four control points on each side with the B-spline weights, which
// are C2 in the contact's position (the arcs' linear weights kink at every node), and is the exact
// -grad of k g^2 / 2. Nodes whose every span is smooth take no node contact; near a kink (a
// spall's corners) they do, unless the spline contact's current span uses them.
//
// Cost: surfaces far apart are rejected by bounding boxes (two min/max passes over the surface
// nodes, no search). The grid is rebuilt only when a master node has moved margin/2. All buffers
// are sized at construction or at the first step: nothing is allocated in the time loop unless a
// rebuild has to grow the grid. Slave nodes are processed in parallel (OpenMP) into per-node slots
// that are scattered in fixed order, so results are bit-identical for any thread count.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "sim/contact/arc_geometry.h"
#include "sim/contact/friction.h"
#include "sim/contact/penalty.h"
#include "sim/contact/segment_grid.h"
#include "sim/contact/spline_surface.h"
#include "sim/contact/surface.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::contact {

struct ContactPairOptions {
  PenaltyLaw penalty_law = PenaltyLaw::kBulkModulus;
  double penalty_scale = 0.1;        // f (bulk modulus law) or s (mass / time-step law)
  double constant_stiffness = 0.0;   // N/m, kConstant law only
  double reference_time_step = 0.0;  // s, mass / time-step law; 0: dt of the first AddForces

  FrictionLaw friction;                     // frictionless by default
  double tangential_stiffness_ratio = 1.0;  // k_t / k (stick stiffness)

  double normal_damping_ratio = 0.0;  // fraction of critical, 2 sqrt(k m*), m* reduced mass
  bool symmetric = false;             // second pass with the surfaces swapped

  // Search. 0 = automatic: margin = mean master segment length, capture depth = margin / 2.
  double search_margin = 0.0;  // m, grid growth; rebuild after margin/2 of master motion
  double capture_depth = 0.0;  // m, deepest penetration still treated as contact (<= margin / 2)

  // Both surfaces curved: touch as cubic B-splines of their smooth nodes (spline_surface.h)
  // instead of the arcs' blend; nodes near a kink (a spall's corners) keep node contact.
  bool smooth_surfaces = false;

  double stable_step_safety = 0.9;  // factor on 2 / omega in StableTimeStep()
  int parallel_min_nodes = 2048;    // OpenMP only for passes with at least this many slave nodes

  bool IsValid(std::string* error) const;
};

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
  // Checkpoint/restart (ForceContributor hook): friction springs, energies, search settings. The
  // grid is rebuilt after a load; candidates are complete either way, so results are identical.
  // (No `override` so this header also builds against a ForceContributor without the hook.)
  std::string SaveState() const;
  void LoadState(const std::string& bytes);

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
  struct Slot {  // per slave node, written in parallel, scattered serially
    int segment = -1;
    double xi = 0.0;
    double fnx = 0.0, fny = 0.0;  // normal force on the slave node
    double ftx = 0.0, fty = 0.0;  // tangential force on the slave node
    double fn = 0.0, penetration = 0.0;
    double stored = 0.0, friction_work = 0.0, damping_work = 0.0;
  };
  static constexpr int kArcCoordinates = 10;  // an arc contact point's gradient: 5 nodes x, y
  // A convex slave arc's closest point to one master segment (in both spans) or, at a ridge, a
  // node's: the master node ending that segment (master_node; xi_master = 1), or the slave node
  // ending slave_segment against the master segment (slave_node; xi = 1).
  struct ArcContact {
    int slave_segment = -1, master_segment = -1;
    bool slave_node = false, master_node = false;
    ArcPair<double> at{};  // gap, normal, points, chord parameters
    double weight = 0.0;   // share in the blended contact (the blend's sum to 1)
    // d(penetration)/d(slave a, slave b, master a, master b, third node; x, y each)
    double grad[kArcCoordinates] = {};
    // A ridge point's wedge (FindArcContacts): the node beyond the ridge that bounds it (the
    // next slave or master arc's end; -1 otherwise), that arc's curvature, the point's place in
    // the wedge (0 .. 1).
    int third_node = -1;
    double third_curvature = 0.0, wedge = 0.0;
    // BlendArcContacts: the point's share of its slave arc's master factors, and their sum.
    double omega = 0.0, master_sum = 0.0;
  };
  struct Pass {
    ContactSurface slave, master;
    // Curved slave surface only: this step's arc contact points (the blend), its forces, spring.
    std::vector<ArcContact> arc_candidates, arc_blend;
    Slot arc_slot;
    double arc_spring = 0.0, arc_spring_stiffness = 0.0;
    std::vector<char> node_owned;          // per slave node: the arc contact stands for it
    std::vector<char> rim_node;            // per slave node: between two convex arcs (fixed)
    std::vector<Arc<double>> master_arcs;  // curved master: its arcs, computed once per step
    std::vector<long> master_arc_stamp;    // the step (arc_stamp) each was computed at
    long arc_stamp = 0;
    SegmentGrid grid;
    // smooth_surfaces: both surfaces' B-spline views, this step's contact point (the last one
    // found is the next step's Newton start), its control points and weights while in contact.
    SplineSurface slave_spline, master_spline;
    SplineContactPoint spline_point;
    bool spline_found = false, spline_active = false;
    std::array<int, 4> spline_slave_nodes{}, spline_master_nodes{};  // global ids
    std::array<double, 4> spline_slave_weights{}, spline_master_weights{};
    std::vector<char> spline_interior;     // per slave node: every span it controls is valid
    std::vector<double> x_built, y_built;  // master node positions at the last grid build
    std::vector<double> tangential_force;  // per slave node, along the master tangent
    std::vector<double> tangential_stiffness;
    std::vector<double> gap;
    std::vector<Slot> slots;
    double margin = 0.0, capture = 0.0;
  };

  void RunPass(Pass& pass, const fe::NodalState& state, double dt, double sign);
  void AddToResultant(const Slot& slot, double sign);  // sign -1: second pass (swapped roles)
  // Global node ids of an arc contact's segments: slave a, slave b, master a, master b.
  static std::array<int, 4> ArcNodes(const Pass& pass, const ArcContact& c);
  // The contact law at one contact point (a slave node or arc point): normal penalty with damping,
  // tangential spring `spring` (updated) capped by Coulomb; fills the slot's forces and energies.
  void ContactLaw(double k,
                  double penetration,
                  double nx,
                  double ny,
                  double rvx,
                  double rvy,
                  double inverse_mass_sum,
                  double dt,
                  double* spring,
                  double* spring_stiffness,
                  Slot* slot) const;
  // Curved slave surface: the blended arc contact (sets node_owned), before the node loop;
  // ArcForces after it (contact law, friction hand-over to and from nodes; serial).
  void FindArcContacts(Pass& pass, const double* x, const double* y);
  // Weights of the blend's points and the gradient of the blended penetration (ArcContact::grad).
  void BlendArcContacts(Pass& pass, const double* x, const double* y) const;
  void ArcForces(Pass& pass, const fe::NodalState& state, double dt);
  // smooth_surfaces: the B-spline contact point (sets node_owned) before the node loop, its
  // contact law after it.
  void FindSplineContact(Pass& pass, const double* x, const double* y);
  void SplineForces(Pass& pass, const fe::NodalState& state, double dt);
  // After ArcForces / SplineForces: the springs of slave nodes not in node contact this step
  // (the point contact may have taken them over) give up their energy.
  static void ReleaseIdleNodeSprings(Pass& pass);
  double SegmentStiffness(const Pass& pass,
                          int segment,
                          double slave_mass,
                          double master_mass) const;

  std::string name_;
  ContactPairOptions options_;
  std::vector<Pass> passes_;
  ContactResultant resultant_;
  double reference_dt_ = 0.0;
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
