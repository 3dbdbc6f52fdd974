// The rigid half of the hybrid bearing model (DESIGN.md "Fidelity ladder", level 3): rollers,
// cage and inner ring (shaft) as RIGID bodies with exact profiles, in contact with the FE outer
// ring's raceway nodes. The outer ring and the adapter (the transfer path to the sensor) stay
// flexible FE; sim/bearing/model_builder.h builds both halves when the scene says
// model.fidelity = "hybrid".
//
// Why: in the full FE model a roller contact is carried by one or two mesh nodes, much softer
// than Palmgren's line contact and laterally unstable, and the small O-grid elements inside the
// rollers set the time step (docs/BEARING_MODEL.md). Here every roller is a circle of radius r
// with an exact flat-bottomed spall (chord w at the surface, depth h), its mass and inertia
// integrated from that profile, and each roller-race contact follows Palmgren's law
// Q = K_c delta^(10/9) (K_c = 8.06e4 l^(8/9) N/mm^(10/9), the law Harris-Jones uses), so the time
// step is set by the ring elements.
//
// Contact geometry (docs/BEARING_MODEL.md, "The hybrid model"):
//  - roller-outer race: along the line from the bearing centre through the roller centre. If
//    that direction is on the intact circle, one contact point at r; if it falls inside the spall
//    (the spall faces the race), the roller rests on the spall's two rim corners, each checked
//    against the race (the race curvature included): that is the force drop of bearing-notes §4.
//    The race surface radius at a point is the reference raceway radius plus the radial nodal
//    displacement averaged with a cubic B-spline kernel of half-width L (arc length) around the
//    point; the contact force goes to the same nodes with the same weights (work conjugate).
//    Spreading over L (>= 1 mm, >= 2 node spacings) makes the force independent of where the
//    contact sits between nodes; the ring's elastic response to a load spread over 2L is its
//    structural compliance, the Hertzian part is in K_c.
//  - roller-inner race: the inner ring is rigid (on the shaft): exact circle of the raceway
//    radius around the shaft centre; the shaft translates freely under the radial load and turns
//    at the prescribed (ramped) speed.
//  - roller-cage: the pocket walls are straight lines (W = D + pocket clearance apart), the
//    roller's extent towards a wall is its support function (the spall corners when the spall
//    faces the wall); linear spring. Radially each pocket holds its roller within
//    +-radial_play of the pitch radius (roller-guided cage, CageGuideOptions in constraints.h,
//    the same assumption as the FE model's), linear spring beyond.
//  - every contact: normal damping (fraction of critical of the contact's two-body oscillator:
//    reduced mass of the roller and the counter body, the ring's kernel effective mass for the
//    outer race), regularised Coulomb friction mu = mu_d + (mu_s - mu_d) exp(-decay |v|)
//    with a tangential spring (stick) capped at mu Q.
// Time integration: the same central-difference scheme as the solver, inside AddForces: forces
// at x^n with velocities v^(n-1/2), then v^(n+1/2) and x^(n+1) for every rigid body.
// Energies: StoredEnergy() = contact potentials + the rigid bodies' kinetic energy (the solver
// counts only nodal kinetic energy), DissipatedEnergy() = friction + contact damping,
// ExternalWork() = radial load + shaft drive torque.
#pragma once

#include <string>
#include <vector>

#include "sim/bearing/constraints.h"
#include "sim/bearing/mesher.h"
#include "sim/bearing/scene.h"
#include "sim/solver/explicit_solver.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim {

// Exact section of a roller: circle of radius r, optionally with a flat-bottomed rectangular
// spall (chord width w at the surface, parallel walls, bottom at depth h below the intact
// surface) centred on body-frame direction `angle`. The two rim edges (wall meets circle) are
// sharp (edge_radius = 0) or rounded by a fillet of radius rho tangent to the wall and the
// circle; a race then touches a rim edge on its fillet circle.
struct RollerProfile {
  double radius = 0.0;
  bool spalled = false;
  double width = 0.0, depth = 0.0, angle = 0.0, edge_radius = 0.0;

  // Half the angle the spall cuts out of the circle: asin(w / 2r).
  double HalfAngle() const;
  // Half-angle of the directions in which the spall's hull (the rim edges) rather than the
  // circle is the extreme of the profile: the direction of a fillet centre, atan2(a + rho, v_f);
  // = HalfAngle() for sharp edges.
  double ContactHalfAngle() const;
  // True when body-frame direction a (rad) points into the spall (|a - angle| < ContactHalfAngle).
  bool InSpall(double a) const;
  // The centres of the two rim fillets (body frame, relative to the circle centre); the rim
  // corners themselves for sharp edges. A rim edge is the circle of radius edge_radius there.
  void RimCorners(double cx[2], double cy[2]) const;
  // Support function: max over the profile of p . (cos a, sin a), p from the circle centre.
  double Support(double a) const;
  // The same, and the extreme point itself (body frame, from the circle centre) in *px, *py:
  // a rim edge's surface point when a points into the spall, else radius * (cos a, sin a).
  double SupportPoint(double a, double* px, double* py) const;
  // Section properties: area (m^2), centroid (m, from the circle centre) and polar second
  // moment about the centroid (m^4). Exact up to a 1e-7 quadrature of the spall region.
  struct Properties {
    double area = 0.0, cx = 0.0, cy = 0.0, polar = 0.0;
  };
  Properties SectionProperties() const;
};

struct HybridOptions {
  double palmgren_coefficient = 8.06e4;     // K_c = coefficient * l_mm^(8/9), N/mm^(10/9)
  double contact_damping_ratio = 0.1;       // normal contact damping, fraction of critical
  double tangential_stiffness_ratio = 1.0;  // stick spring / normal tangent stiffness
  double cage_stiffness_n_per_m = 2e8;      // pocket wall spring (whole section)
  // Half-width L of the kernel that spreads an outer-race contact over raceway nodes; 0: the
  // larger of 1 mm and 2 raceway node spacings.
  double spread_half_width_m = 0.0;

  bool IsValid(std::string* error) const;
};

class HybridRollers : public solver::ForceContributor {
 public:
  // Pose and velocity of a rigid body: mass centre (x, y), rotation angle from the initial pose,
  // velocities at t^(n-1/2) (after a step: n+1/2).
  struct Body {
    double x = 0, y = 0, angle = 0, vx = 0, vy = 0, omega = 0;
  };

  // `housing`: the mesh from MeshBearingHousing (its "outer_ring.raceway" curve must have
  // uniformly spaced nodes); `state`: the solver's nodal state (masses set). Throws InputError.
  HybridRollers(const Scene& scene,
                const BearingMesh& housing,
                const fe::NodalState& state,
                const HybridOptions& options,
                const CageGuideOptions& cage_guide);

  void AddForces(fe::NodalState& state, double t, double dt) override;
  double StableTimeStep(const fe::NodalState& state) const override;
  double StoredEnergy() const override { return potential_ + kinetic_; }
  double DissipatedEnergy() const override { return friction_work_ + damping_work_; }
  double ExternalWork() const override { return external_work_; }
  std::string Name() const override { return "hybrid_rollers"; }
  std::string SaveState() const override;
  void LoadState(const std::string& bytes) override;

  int num_rollers() const { return static_cast<int>(rollers_.size()); }
  const Body& roller(int j) const { return rollers_[j]; }
  const Body& cage() const { return cage_; }
  const Body& shaft() const { return shaft_; }
  const RollerProfile& profile(int j) const { return profiles_[j]; }
  // Fraction of roller j's length that carries its spall (1: through-length or healthy).
  double spall_length_fraction(int j) const { return spall_fraction_[j]; }
  double roller_mass(int j) const { return roller_mass_[j]; }
  double roller_inertia(int j) const { return roller_inertia_[j]; }
  double cage_mass() const { return cage_mass_; }
  double shaft_mass() const { return shaft_mass_; }
  double contact_stiffness() const { return k_c_; }  // K_c, N/m^(10/9)
  double spread_half_width() const { return spread_; }
  // Effective mass of the raceway under one contact's kernel, 1 / max sum_i w_i^2 / m_i (kg).
  double ring_contact_mass() const { return ring_mass_; }
  // Contact stable steps (s, before the safety factor 0.8): roller side and ring side.
  double roller_time_step() const { return roller_dt_; }
  double ring_time_step() const { return ring_dt_; }
  // Circle centre of roller j (world).
  void RollerCentre(int j, double* x, double* y) const;
  // Normal contact force magnitudes on roller j at the last step (N, whole section).
  double OuterForce(int j) const { return outer_force_[j]; }
  double InnerForce(int j) const { return inner_force_[j]; }
  double CageForce(int j) const { return cage_force_[j]; }
  double ShaftSpeed(double t) const { return speed_(t); }

 private:
  struct Point {    // one contact point of a roller with a race
    double px, py;  // world
    double nx, ny;  // unit normal, direction of the force ON the roller
    double delta;   // penetration (> 0: in contact)
  };
  // Candidate points of roller j against the outer (which = 0) or inner (1) race.
  int RacePoints(int j, int which, const RollerProfile& profile, Point out[2]) const;
  // Kernel weights of the raceway nodes around angle th: indices into ring_nodes_ and weights.
  // With dw != nullptr also the weights' derivatives dw_i/dth.
  int Kernel(double th, int* idx, double* w, double* dw = nullptr) const;
  // Deformed raceway radius at angle th (reference raceway radius + kernel-averaged radial
  // displacement) and, when slope != nullptr, its derivative dR/dth (m/rad).
  double RaceRadius(const fe::NodalState& s, double th, double* slope = nullptr) const;

  Scene scene_;
  HybridOptions options_;
  CageGuideOptions cage_guide_;
  solver::TimeFunction angle_, speed_, load_;
  std::vector<RollerProfile> profiles_;
  std::vector<RollerProfile> intact_profiles_;  // the same circles without their spalls
  std::vector<double> spall_fraction_;
  std::vector<double> roller_mass_, roller_inertia_, centroid_x_, centroid_y_;  // body frame
  std::vector<double> pocket_angle_;  // pocket j centre line in the cage frame
  double cage_mass_ = 0, cage_inertia_ = 0, shaft_mass_ = 0;
  double pocket_half_width_ = 0, pitch_radius_ = 0, outer_radius_ = 0, inner_radius_ = 0;
  double k_c_ = 0, spread_ = 0, dt_limit_ = 0, ring_mass_ = 0, roller_dt_ = 0, ring_dt_ = 0;
  // Raceway nodes sorted by reference angle (uniform): ids, theta0, spacing, radial unit vectors.
  std::vector<int> ring_nodes_;
  std::vector<double> ring_ex_, ring_ey_;
  double ring_theta0_ = 0, ring_dtheta_ = 0;

  // State (checkpointed).
  std::vector<Body> rollers_;
  Body cage_, shaft_;
  std::vector<double> friction_;  // tangential spring force per (roller, contact): outer,
                                  // inner, leading wall, trailing wall
  std::vector<double> outer_force_, inner_force_, cage_force_;
  double dt_prev_ = 0, potential_ = 0, kinetic_ = 0, friction_work_ = 0, damping_work_ = 0,
         external_work_ = 0;

  // Scratch.
  std::vector<double> fx_, fy_, torque_;  // per roller
};

}  // namespace spallkit::sim
