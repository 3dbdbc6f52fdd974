// The rigid half of the hybrid and lumped bearing models (docs/BEARING_MODEL.md): rollers,
// cage and inner ring (shaft) as RIGID bodies with exact profiles (roller_profile.h), in contact
// with an outer race that each model supplies (OuterRace: the FE ring's raceway nodes in the
// hybrid model, a rigid ring on the housing's stiffness in the lumped model).
//
// Why: in the full FE model a roller contact is carried by one or two mesh nodes, much softer
// than Palmgren's line contact and laterally unstable, and the small O-grid elements inside the
// rollers set the time step (docs/BEARING_MODEL.md). Here every roller is a circle of radius r
// with an exact flat-bottomed spall (chord w at the surface, depth h), its mass and inertia
// integrated from that profile, and each roller-race contact follows Palmgren's law
// Q = K_c delta^(10/9) (K_c = 8.06e4 l^(8/9) N/mm^(10/9), the law Harris-Jones uses).
//
// Contact geometry (docs/BEARING_MODEL.md, "The hybrid model"):
//  - roller-outer race: along the line from the bearing centre through the roller centre. If
//    that direction is on the intact circle, one contact point at r; if it falls inside the spall
//    (the spall faces the race), the roller rests on the spall's two rim edges, each checked
//    against the race (the race curvature included): the force drop of a spall passage. The
//    two edges' contact zones overlap where the intact circle would touch: with d_c the
//    circle's penetration there and d_s = d_1 + d_2 - d_c (> 0 only when both edges lie in the
//    zone the circle would load, i.e. the spall is narrower than the contact), the pair's
//    potential is V(d_1) + V(d_2) - V(d_s). A narrow spall is thus bridged (its load is the
//    intact roller's, acting at the circle's point), a wide one rests on two independent
//    edges, and the load is continuous as the spall turns into and out of the race.
//  - roller-inner race: the inner ring is rigid (on the shaft): exact circle of the raceway
//    radius around the shaft centre; the shaft translates freely under the radial load and turns
//    at the prescribed (ramped) speed.
//  - roller-cage: the pocket walls are straight lines (W = D + pocket clearance apart), the
//    roller's extent towards a wall is its support function (the spall corners when the spall
//    faces the wall); linear spring. Radially each pocket holds its roller within
//    +-radial_play of the pitch radius (roller-guided cage, CageGuideOptions in constraints.h,
//    the same assumption as the FE model's), linear spring beyond.
//  - every contact: normal damping (fraction of critical of the contact's two-body oscillator:
//    reduced mass of the roller and the counter body), friction by the contact module's law
//    (sim/contact/friction.h: mu = mu_d + (mu_s - mu_d) exp(-decay |v|), a stick spring capped
//    at mu Q) plus a damper on the stick spring; with friction.model = "ehl" the race contacts
//    take the lubricant traction curve of their slide-to-roll ratio instead
//    (sim/contact/traction.h).
// Time integration: central differences (rigid_body.h), inside Step().
// Energies, all at t^n (the forces' time, as the solver's balance: central differences conserve
// energy measured there to second order, while kinetic energy at v^(n+1/2) is off by half a
// step of the contact forces' power, a first-order error that swings with every impact):
// StoredEnergy() = contact potentials at x^n + the rigid bodies' kinetic energy
// 1/2 m v^(n-1/2) . v^(n+1/2); DissipatedEnergy() = friction + contact damping, ExternalWork()
// = radial load + shaft drive, each force's work f^k . (v^(k-1/2) + v^(k+1/2)) dt_avg / 2 up to
// t^n (step n's force over its first half step).
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "sim/bearing/constraints.h"
#include "sim/bearing/mesher.h"
#include "sim/bearing/palmgren_power.h"
#include "sim/bearing/rigid_body.h"
#include "sim/bearing/roller_profile.h"
#include "sim/bearing/scene.h"
#include "sim/contact/film_lift.h"
#include "sim/contact/friction.h"
#include "sim/contact/traction.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit::sim {

struct HybridOptions {
  double palmgren_coefficient = 8.06e4;     // K_c = coefficient * l_mm^(8/9), N/mm^(10/9)
  double contact_damping_ratio = 0.1;       // normal contact damping, fraction of critical
  double tangential_stiffness_ratio = 1.0;  // stick spring / normal tangent stiffness
  double cage_stiffness_n_per_m = 2e8;      // pocket wall spring (whole section)
  // Half-width L of the kernel that spreads an outer-race contact over raceway nodes; 0: the
  // larger of 1 mm and 2 raceway node spacings (raceway_kernel.h; hybrid model only).
  double spread_half_width_m = 0.0;
  // Keep the per-step energy books (contact potentials, kinetic energies, friction, damping and
  // external work). Off only when nothing reads them (Simulation: no "energy" output and no
  // energy guard); then every energy below is NaN. About 8 % of a lumped step.
  bool energy_books = true;

  bool IsValid(std::string* error) const;
};

// One contact point of a roller with a race.
struct RacePoint {
  double px, py;  // world
  double nx, ny;  // unit normal, direction of the force ON the roller
  double delta;   // penetration (> 0: in contact)
};

// The outer race as the rollers see it.
class RigidOuterRace;

class OuterRace {
 public:
  virtual ~OuterRace() = default;
  // Contact of a circle (centre (qx, qy), radius rad; world) with the race from inside: fills
  // the penetration, the unit normal of the force on the roller (the deformed race's normal) and
  // the surface point q - rad n.
  virtual void Gap(double qx, double qy, double rad, RacePoint* p) const = 0;
  // Velocity of the race's material at world point (px, py).
  virtual void Velocity(double px, double py, double* vx, double* vy) const = 0;
  // Adds a force on the race acting at (px, py).
  virtual void Apply(double px, double py, double fx, double fy) = 0;
  // False only when a circle (centre, radius) certainly does not touch the race (a cheap
  // bound that lets the rollers skip the contact).
  virtual bool MayTouch(double /*cx*/, double /*cy*/, double /*radius*/) const { return true; }
  // The lumped model's rigid ring (rigid_outer_race.h), else null: RollerContacts then calls its
  // inline methods directly instead of through this interface.
  virtual RigidOuterRace* AsRigid() { return nullptr; }
};

class RollerContacts {
 public:
  using Body = PlanarBody;

  // Geometry from `housing` (raceway, pitch and roller radii, roller angles; its mesh is not
  // used). `outer_race_mass`: the outer race's effective mass for one contact (kg; the FE
  // kernel's, or the rigid ring's). Throws InputError.
  RollerContacts(const Scene& scene,
                 const BearingMesh& housing,
                 double outer_race_mass,
                 const HybridOptions& options,
                 const CageGuideOptions& cage_guide);

  // One step: contact forces at time t (positions x^n, velocities v^(n-1/2)), the reactions
  // applied to `race`, then the rigid bodies advanced to x^(n+1), v^(n+1/2).
  void Step(OuterRace& race, double t, double dt);
  // Largest stable step of the contacts (safety factor included).
  double StableTimeStep() const { return dt_limit_; }

  // The energy books (NaN when HybridOptions::energy_books is off).
  double StoredEnergy() const { return Kept(potential_ + centred_kinetic_); }
  double DissipatedEnergy() const { return Kept(friction_work_ + damping_work_); }
  double ExternalWork() const { return Kept(external_work_ - external_half_); }
  // The same terms apart: rigid bodies' kinetic energy at v^(n+1/2), contact potentials (at
  // x^n), friction and contact damping work.
  double KineticEnergy() const { return Kept(kinetic_); }
  // The rigid bodies' kinetic energy at t^n, 1/2 m v^(n-1/2) . v^(n+1/2).
  double CentredKineticEnergy() const { return Kept(centred_kinetic_); }
  double ContactEnergy() const { return Kept(potential_); }
  double FrictionWork() const { return Kept(friction_work_); }
  double DampingWork() const { return Kept(damping_work_); }
  std::string SaveState() const;
  void LoadState(const std::string& bytes);  // throws InputError on a size mismatch

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
  double outer_race_mass() const { return race_mass_; }
  // Contact stable steps (s, before the safety factor 0.8): roller side and ring side.
  double roller_time_step() const { return roller_dt_; }
  double ring_time_step() const { return ring_dt_; }
  // Normal tangent stiffness of one Palmgren contact at twice the radial load (N/m): the bound
  // the stable steps are computed with.
  double bound_normal_stiffness() const { return bound_normal_stiffness_; }
  // Circle centre of roller j (world).
  void RollerCentre(int j, double* x, double* y) const;
  // Whether roller j is spalled and its spall faces a race within `margin` (rad) of roller
  // rotation while the roller turns relative to its orbit faster than `min_relative_spin`
  // (rad/s): a spall passage (edge contacts and the exit impact) under way or about to start.
  bool SpallNearRace(int j, double margin, double min_relative_spin) const;
  // Normal contact force magnitudes on roller j at the last step (N, whole section).
  double OuterForce(int j) const { return outer_force_[j]; }
  double InnerForce(int j) const { return inner_force_[j]; }
  double CageForce(int j) const { return cage_force_[j]; }
  double ShaftSpeed(double t) const { return speed_(t); }
  // Radial load on the shaft at t (N, along +y; negative: downwards).
  double ShaftLoad(double t) const { return load_(t); }

 private:
  enum class Counter { kOuterRace, kShaft, kCage };
  // Circle centre of roller j from its body and the kept cos_ / sin_ of its angle (the per-step
  // form of RollerCentre).
  void CircleCentre(int j, double* x, double* y) const;
  // model.start = "seated": how far the shaft is lowered (m, along the load) to touch the
  // first roller, the rollers already on the outer raceway.
  double SeatedShaftDrop() const;
  // Roller j's distance from the bearing centre (m) at which its profile along angle phi
  // touches a rigid raceway circle of outer_radius from inside.
  double SeatOnOuterRace(int j, double phi, double outer_radius) const;
  // The circles of roller j (circle centre (cx, cy), body angle 0) that face the world unit
  // direction (ux, uy): the intact circle, and the two rim fillets where the spall faces it
  // (then the circle only for a spall shorter than the roller); out[k] = {x, y, radius}.
  // Returns how many.
  int ContactCircles(int j, double cx, double cy, double ux, double uy, double out[3][3]) const;
  // Candidate points of roller j against the outer (which = 0) or inner (1) race: positions of
  // the circle centre or the two rim fillet centres, normal along the centre line. With the rim
  // pair (returns 2), out[2] is the intact circle's point towards the race.
  int RacePoints(int j,
                 int which,
                 const RollerProfile& profile,
                 const ProfileDirections& dirs,
                 RacePoint out[3]) const;
  void CounterVelocity(Counter body, double px, double py, double* vx, double* vy) const;
  void ApplyCounter(Counter body, double px, double py, double fx, double fy);
  // One contact (1 or 2 points) of roller j with a counter body: normal force (Palmgren or the
  // cage's linear spring), damping and friction on the stick spring *spring; forces added to
  // the roller and the counter body. `scale`: the contact's share of the Palmgren stiffness.
  // A Palmgren rim pair may come with a third point, the intact circle's (RaceContacts): the
  // pair then shares the zone the circle would load (see there). Returns the normal force.
  double Contact(int j,
                 Counter body,
                 bool palmgren,
                 RacePoint* pts,
                 int npts,
                 double* spring,
                 double scale = 1.0);
  // Both race contacts of roller j for one profile carrying `scale` of the Palmgren stiffness;
  // stick springs friction_[slot], friction_[slot + 1]. Adds to outer_force_ / inner_force_.
  void RaceContacts(
      int j, const RollerProfile& profile, const ProfileDirections& dirs, double scale, int slot);
  // Pocket walls and the radial guide of roller j.
  void CageContacts(int j);
  // The lubricated race contacts of roller j that Contact set aside (friction.model = "ehl"):
  // their traction forces, solved implicitly once every other force on the roller is known
  // (contact::SolveImplicitTraction), applied to the roller and the counter bodies.
  void SolveTraction(int j);
  // Keeps a friction (1) or damping (0) force of roller j at world point (px, py) for the
  // second half of its work (FinishDissipation).
  void DeferDissipation(
      int j, Counter body, double px, double py, double fx, double fy, int friction);
  // Central-difference update of every rigid body and the energy books.
  void Integrate(double t, double dt);
  // Palmgren's d^(10/9) at penetration d > 0 for contact point `anchor` (3 per friction slot;
  // sim/bearing/palmgren_power.h).
  double PalmgrenPower(double d, int anchor);
  // The per-roller state vectors in checkpoint order (SaveState, LoadState).
  template <class Self>
  static auto StateVectors(Self& self) {
    return std::array{&self.friction_,
                      &self.outer_force_,
                      &self.inner_force_,
                      &self.cage_force_,
                      &self.cos_,
                      &self.sin_,
                      &self.anchor_depth_,
                      &self.anchor_power_,
                      &self.film_coefficient_};
  }
  double Kept(double energy) const {
    return options_.energy_books ? energy : std::numeric_limits<double>::quiet_NaN();
  }
  // Work of step n-1's friction and damping forces on the velocities v^(n-1/2) (the second half
  // of the central-difference work f . (v^(n-3/2) + v^(n-1/2)) / 2 dt_avg).
  void FinishDissipation();

  // A friction or damping force of one contact at step n, kept for the second half of its work
  // (FinishDissipation at the next step, when every body's v^(n+1/2) is known).
  struct DissipativeForce {
    double fx, fy;  // on the roller (N)
    double ax, ay;  // contact point - roller mass centre (x^n)
    double px, py;  // contact point (world, x^n): the outer race's velocity is read there
    double bx, by;  // contact point - counter body's centre (x^n)
    double omega;   // counter body's spin used (the shaft's prescribed speed at t^n)
    double weight;  // dt_avg / 2 of step n
    int roller, counter, friction;  // friction: 1, damping: 0
  };

  // A lubricated race contact of the current roller, waiting for SolveTraction.
  struct TractionContact {
    Counter body;
    double tx, ty;       // slip axis (the force on the roller is f (tx, ty))
    double arm;          // sum_k w_k (p_k - roller centre) x t: the force's torque per newton
    double normal;       // normal force (N)
    double slip;         // slip speed at v^(n-1/2)
    double entrainment;  // entrainment speed
    double* spring;      // friction slot: keeps the secant per newton, the next step's guess
    int npts;
    double px[3], py[3], w[3];  // points and their shares q_k / q of the force
  };

  Scene scene_;
  HybridOptions options_;
  CageGuideOptions cage_guide_;
  contact::FrictionLaw friction_law_;
  solver::TimeFunction angle_, speed_, load_;
  std::vector<RollerProfile> profiles_;
  std::vector<RollerProfile> intact_profiles_;  // the same circles without their spalls
  std::vector<ProfileDirections> directions_, intact_directions_;
  std::vector<double> spall_fraction_;
  std::vector<double> roller_mass_, roller_inertia_, centroid_x_, centroid_y_;  // body frame
  std::vector<double> pocket_angle_;  // pocket j centre line in the cage frame
  std::vector<double> pocket_cos_, pocket_sin_;
  double cage_mass_ = 0, cage_inertia_ = 0, shaft_mass_ = 0, race_mass_ = 0;
  double pocket_half_width_ = 0, pitch_radius_ = 0, inner_radius_ = 0;
  double k_c_ = 0, dt_limit_ = 0, roller_dt_ = 0, ring_dt_ = 0, bound_normal_stiffness_ = 0;
  // The lubricant film's normal load (contact/film_lift.h; lubricated race contacts only):
  // 4.9 eta L R per unit entrainment speed, per Counter (outer race, inner race; 0: no film),
  // its ceiling (A at twice the inner race's surface speed), and the race contacts' reach (the
  // gap beyond which they carry nothing).
  double film_per_speed_[2] = {0, 0};
  double film_ceiling_ = 0, race_reach_ = 0;
  std::vector<double> reduced_mass_, reduced_mass_t_;  // per (roller, Counter)
  double inverse_counter_mass_[3] = {0, 0, 0};         // per Counter, for a tangential force
  std::vector<double> inverse_roller_mass_, inverse_roller_inertia_;

  // State (checkpointed).
  std::vector<Body> rollers_;
  Body cage_, shaft_;
  std::vector<double> friction_;  // per (roller, contact): outer, inner, leading wall, trailing
                                  // wall; the stick spring's force (Coulomb), or a lubricated
                                  // race contact's last traction secant per newton (SolveTraction)
  // PalmgrenPowerNear's expansion points per contact point: depth d0 and d0^(10/9) exactly.
  std::vector<double> anchor_depth_, anchor_power_;
  // The lubricant film's coefficient A per contact point at its last evaluation: the elastic
  // energy that a change of A moves is booked with the film's work.
  std::vector<double> film_coefficient_;
  // The film law's memory per contact point (its last root and expansion points).
  std::vector<contact::FilmContactMemory> film_memory_;
  std::vector<double> outer_force_, inner_force_, cage_force_;
  double dt_prev_ = 0, potential_ = 0, kinetic_ = 0, friction_work_ = 0, damping_work_ = 0,
         external_work_ = 0;
  // The last step's second half of the load and drive work (in external_work_, not yet in
  // ExternalWork()), and the rigid bodies' kinetic energy at t^n.
  double external_half_ = 0, centred_kinetic_ = 0;
  std::vector<DissipativeForce> pending_;  // this step's, for their second half

  // Per step.
  OuterRace* race_ = nullptr;
  RigidOuterRace* rigid_race_ = nullptr;  // race_->AsRigid(), set with race_
  // f(race) with the race's own type when it is the rigid ring (direct, inlined calls).
  template <class F>
  decltype(auto) WithRace(F&& f) const;
  double dt_ = 0, omega_s_ = 0, step_potential_ = 0;
  double shaft_fx_ = 0, shaft_fy_ = 0, shaft_torque_ = 0, cage_fx_ = 0, cage_fy_ = 0,
         cage_torque_ = 0;
  std::vector<double> fx_, fy_, torque_;  // per roller
  // SpallNearRace's cosines of each spall's contact cone widened by widened_margin_ (derived
  // from the profiles, computed on the first call with a margin).
  mutable std::vector<double> widened_cos_;
  mutable double widened_margin_ = std::numeric_limits<double>::quiet_NaN();
  TractionContact traction_[contact::kMaxImplicitContacts];
  int num_traction_ = 0;
  // SolveTraction's arrays (scratch, not state).
  struct TractionSolveArrays {
    static constexpr int kN = contact::kMaxImplicitContacts;
    double normal[kN], free_slip[kN], entrainment[kN], compliance[kN * kN], force[kN], secant[kN];
  } solve_;
  double cage_cos_ = 1, cage_sin_ = 0;  // of the cage's angle at x^n
  // Per roller at x^n: cos and sin of its angle (advanced with it in Integrate and
  // checkpointed: not recomputed from the angle), circle centre.
  std::vector<double> cos_, sin_, centre_x_, centre_y_;
};

}  // namespace spallkit::sim
