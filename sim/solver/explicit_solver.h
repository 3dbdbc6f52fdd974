// Explicit central-difference solver for 2-D quad meshes.
//
// Step n (positions x^n, velocities v^(n-1/2)):
//   1. element pass (sim/fe/quad_elements.h): stresses to t^n, corner forces, element stable step;
//   2. dt = min(time_step_scale * element step, every ForceContributor::StableTimeStep,
//   max_time_step);
//   3. nodal forces = gathered element forces + every ForceContributor, in insertion order;
//   4. v^(n+1/2) = v^(n-1/2) + dt_avg * a^n with semi-implicit mass damping, then kinematic
//      constraints (rigid bodies with prescribed rotation, velocity conditions, fixed nodes);
//   5. x^(n+1) = x^n + dt * v^(n+1/2).
//
// Mass damping (LS-DYNA *DAMPING_GLOBAL, D_s = 4 pi xi f_ref) acts on each node's velocity
// RELATIVE to the rigid motion (translation + rotation about the mass centre) of its part, so
// spinning rings and rollers are not braked; set damping_relative_to_rigid_motion = false for
// plain (absolute) mass damping. Stiffness damping is a viscous stress beta C:D with
// beta = xi_k / (pi f_k), and shortens the step as documented in docs/FE.md.
//
// Results are bit-identical for any thread count (fixed-order sums everywhere) and a run resumed
// from a checkpoint is bit-identical to an uninterrupted one.
#pragma once

#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sim/fe/mesh.h"
#include "sim/fe/nodal_state.h"
#include "sim/fe/quad_elements.h"
#include "sim/fe/section.h"
#include "sim/solver/energy_ledger.h"
#include "sim/solver/force_contributor.h"

namespace spallkit::sim::solver {

using TimeFunction = std::function<double(double t)>;

// Angle history of a shaft that ramps linearly in speed from 0 to `omega` (rad/s) over
// `ramp_time` (s), then turns at constant speed: theta(t) = omega t^2 / (2 T) for t < T, else
// omega (t - T / 2). E.g. RampedRotation(1200 rpm = 125.66 rad/s, 5e-3).
TimeFunction RampedRotation(double omega, double ramp_time);
// Speed (rad/s) of the same history.
TimeFunction RampedSpeed(double omega, double ramp_time);
// A value rising linearly from 0 at t = 0 to `value` at `ramp_time`, then constant (a ramp time
// of 0 is a step at t = 0). E.g. a radial load applied without the 2x overshoot of a step.
TimeFunction LinearRamp(double value, double ramp_time);

// A node set moving rigidly with a reference point: x_i = X(t) + R(theta(t)) (x0_i - X0).
// Rotation is prescribed; each translation direction is either prescribed (x_motion / y_motion
// give X - X0 as a function of time) or free, driven by the resultant of every force on the
// nodes plus the applied force (force_x / force_y, N) on the total mass (nodes + extra_mass).
struct RigidBody {
  std::string name;
  std::vector<int> nodes;
  double ref_x = 0.0, ref_y = 0.0;  // reference point X0, m
  TimeFunction angle;               // rad, counter-clockwise; empty: no rotation
  TimeFunction x_motion, y_motion;  // m; empty: free in that direction
  TimeFunction force_x, force_y;    // N; empty: none
  double extra_mass = 0.0;          // kg at the reference point (e.g. shaft)
};

// Current state of a rigid body's reference point.
struct RigidBodyState {
  double x = 0.0, y = 0.0;                    // X(t^n), m
  double vx = 0.0, vy = 0.0;                  // V(t^(n-1/2)), m/s
  double angle = 0.0;                         // theta(t^n), rad
  double reaction_x = 0.0, reaction_y = 0.0;  // constraint force on the body at step n, N (free
                                              // directions: 0)
};

// Prescribed nodal velocities: v_i(t) = scale(t) * (vx[i], vy[i]) in the directions set in
// fix_x / fix_y (scale empty: 1). Fixed nodes are the special case vx = vy = 0.
struct VelocityCondition {
  std::vector<int> nodes;
  std::vector<double> vx, vy;  // per node (same length as nodes), m/s
  bool fix_x = true, fix_y = true;
  TimeFunction scale;
};

struct SolverOptions {
  double time_step_scale = 0.9;  // TSSFAC: fraction of the smallest element stable step
  double max_time_step = std::numeric_limits<double>::infinity();  // s
  // Global mass damping: ratio of critical at damping_frequency (Hz): D_s = 4 pi xi f_ref (1/s).
  double mass_damping_ratio = 0.0;
  double damping_frequency = 0.0;
  bool damping_relative_to_rigid_motion = true;
  // Stiffness-proportional damping: ratio of critical at stiffness_damping_frequency (Hz).
  double stiffness_damping_ratio = 0.0;
  double stiffness_damping_frequency = 0.0;
  // Output callback every N steps (0: off) and/or every output_interval seconds (0: off).
  int output_every_steps = 0;
  double output_interval = 0.0;
  // Stop with NumericalError when the energy balance error exceeds this (0: never), checked at
  // output steps once the largest energy exceeds energy_check_floor (J).
  double max_energy_error = 0.0;
  double energy_check_floor = 0.0;
  // OpenMP threads. 0: one per 10,000 elements, at most OpenMP's default (small models run
  // faster on one thread). Results do not depend on it (bit-identical).
  int num_threads = 0;
  // Keep a work ledger per contributor (ContributorLedgers()): finds which contact pair or
  // constraint creates energy when the balance fails. Costs two copies of the nodal forces per
  // contributor per step: a diagnostic, off by default.
  bool track_contributor_work = false;
  // Keep the per-step energy terms: element internal, hourglass and damping energy, mass-damping
  // and constraint work (default). Off, the element and nodal passes skip those sums (positions
  // and velocities are bit-identical) and energies() reads NaN for every term but the kinetic;
  // max_energy_error and track_contributor_work need them on.
  bool energy_terms = true;

  bool IsValid(std::string* error) const;
};

struct SolverSummary {
  long steps = 0;
  double time = 0.0;                                // s
  double min_time_step = 0.0, max_time_step = 0.0;  // s
  double wall_seconds = 0.0;
  double ns_per_element_cycle = 0.0;  // wall time / (steps * elements)
  int threads = 1;
  Energies energies;
  std::string BriefReport() const;
};

class ExplicitSolver {
 public:
  // One Section per mesh part. Reference coordinates and lumped masses come from the mesh.
  // Throws InputError for an invalid mesh, section or options.
  ExplicitSolver(const fe::Mesh& mesh,
                 std::vector<fe::Section> sections,
                 SolverOptions options = {});

  // Initial conditions: modify state().vx / vy before the first step (velocities at t = 0).
  fe::NodalState& state() { return state_; }
  const fe::NodalState& state() const { return state_; }
  const fe::QuadElements& elements() const { return elements_; }
  const SolverOptions& options() const { return options_; }

  // Not owned; called in the order added. Add before the first step.
  void AddContributor(ForceContributor* contributor);
  int AddRigidBody(RigidBody body);  // returns its index
  void AddVelocityCondition(VelocityCondition condition);
  void FixNodes(const std::vector<int>& nodes, bool fix_x, bool fix_y);
  // Sets the velocity of every node of `nodes` to the rigid field V + omega x (x - c).
  void SetRigidVelocity(
      const std::vector<int>& nodes, double vx, double vy, double omega, double cx, double cy);

  // Called at t = 0 (before the first step) and then as set in the options.
  void SetOutputCallback(std::function<void(const ExplicitSolver&)> callback) {
    callback_ = std::move(callback);
  }

  // Advances one step / until time() >= end_time. Run returns a summary of that call.
  void Step();
  SolverSummary Run(double end_time);

  // Time t^n of the positions. Element stresses and energies lag one step: they are at
  // t^(n-1) = time() - time_step() (updated from v^(n-1/2) at the start of the next step).
  double time() const { return time_; }
  long step() const { return step_; }
  double time_step() const { return dt_; }  // last step taken (s)
  // Energy terms at the last completed step (sums in a fixed order).
  Energies energies() const;
  // With SolverOptions::track_contributor_work: the elements' ledger first, then one per
  // contributor in insertion order (empty otherwise).
  std::vector<ContributorLedger> ContributorLedgers() const;
  const RigidBodyState& rigid_body_state(int i) const { return rigid_states_[i]; }
  // Rigid motion of part p (from the last step's velocities): mass-centre velocity and spin.
  void PartRigidMotion(int part, double* vx, double* vy, double* omega) const;

  // Binary checkpoint of the full state (nodes, elements, constraints, contributors, energies,
  // output schedule; solver_checkpoint.cc), as bytes or written atomically to a file. Load into a
  // solver built the same way (same mesh, sections, options, constraints, contributors); throws
  // InputError on mismatch.
  std::string SaveState() const;
  void LoadState(std::string_view bytes);
  void SaveCheckpoint(const std::string& path) const;
  void LoadCheckpoint(const std::string& path);

 private:
  void Initialize();
  // Per-part rigid motion in two pieces: sums over node chunk c (run inside the element pass's
  // parallel region), then the fixed-order reduction over chunks.
  void RigidMotionSums(int c);
  struct UpdateConstants {
    double dt = 0.0, dt_avg = 0.0, c_old = 1.0, c_inv = 1.0;
    bool damp = false, relative = false, energy = true;
  };
  void ElementPass(double h, bool rigid_sums, bool gather);
  double UpdateNodes(int c, bool gather, const UpdateConstants& k);
  void ReducePartRigidMotion();
  void ApplyConstraints(double dt, double dt_avg, double t_half, double t_next);
  void MaybeOutput(bool force);

  fe::QuadElements elements_;
  SolverOptions options_;
  fe::NodalState state_;
  std::vector<ForceContributor*> contributors_;
  std::vector<RigidBody> rigid_bodies_;
  std::vector<RigidBodyState> rigid_states_;
  std::vector<VelocityCondition> velocity_conditions_;
  std::function<void(const ExplicitSolver&)> callback_;

  // Node -> part (first element's part) and per-part rigid motion, in fixed node chunks.
  std::vector<int> node_part_;
  std::vector<char> constrained_;   // node is driven by a constraint (no damping)
  std::vector<double> inv_mass_;    // 1 / lumped mass (no division in the nodal update)
  std::vector<double> part_rigid_;  // per part: vx, vy, omega, cx, cy
  std::vector<double> chunk_sums_;  // per chunk x per part x 7 sums (scratch)
  std::vector<std::exception_ptr> contributor_errors_;  // per thread (AddContributorForces)
  int split_contributors_ = 0;  // leading contributors that SplitsForces (set in Initialize)
  std::vector<double> old_vx_, old_vy_, old_x_, old_y_;  // v^(n-1/2), x^n of constrained nodes

  bool initialized_ = false;
  double time_ = 0.0, dt_ = 0.0, dt_prev_ = 0.0, next_output_time_ = 0.0;
  double last_dt_avg_ = 0.0;  // the last step's (dt_prev + dt) / 2: energies() at t^n
  long step_ = 0, last_output_step_ = -1;
  int threads_ = 1;
  double mass_damping_ = 0.0;  // D_s, 1/s
  double damping_work_ = 0.0, reaction_work_ = 0.0, load_work_ = 0.0, initial_kinetic_ = 0.0;
  double initial_stored_ = 0.0;  // Energies::initial_stored

  // Every contributor's forces, in contributor order; the leading ones that split their forces
  // (ForceContributor::SplitsForces: the contact pairs) compute them on all threads first.
  void AddContributorForces(double dt);
  WorkLedger ledger_;  // track_contributor_work only
};

}  // namespace spallkit::sim::solver
