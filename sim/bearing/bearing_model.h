// The bearing model of a scene behind one interface, whatever its fidelity (docs/BEARING_MODEL.md
// "Choosing the fidelity"). The run driver (simulation.h) and the recorder (recorder.h) see only
// this:
//  - Fidelity::kFe      every part meshed (FeBearingModel, model_builder.h);
//  - Fidelity::kHybrid  FE outer ring and adapter, rigid rollers / cage / inner ring with exact
//                       profiles (FeBearingModel with HybridRollers);
//  - Fidelity::kLumped  the hybrid's rigid parts on a rigid outer ring carried by the housing's
//                       fitted stiffness, with the sensors on that fit (LumpedBearingModel,
//                       lumped_model.h).
// MakeBearingModel builds the one the scene asks for.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/bearing/constraints.h"
#include "sim/bearing/mesher.h"
#include "sim/bearing/roller_contacts.h"
#include "sim/bearing/scene.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit::sim {

// Housing fit of the lumped model (lumped_model.h).
struct LumpedOptions {
  // Element size of the FE housing mesh the stiffness and sensor gains are fitted on (m).
  double fit_mesh_size_m = 2e-3;
  // Simulated time of the fit's damped (dynamic-relaxation) FE runs, and its damping ratio
  // (fraction of critical at the housing's first radial mode, mass proportional).
  double fit_duration_s = 4e-3;
  double fit_damping_ratio = 0.7;
  // Stable-step safety on the roller contacts (the FE models use the solver's) of a healthy
  // bearing, and of one with spalled rollers between their passages (their impacts keep the
  // contacts' stiff modes ringing, whose error, and the error of every change of the step,
  // grow as the step squared); and the safety while the speed and load ramp up (t < twice the
  // longer ramp: the rollers are spun up by sliding) and in loaded spall passages: a spalled
  // roller's spall faces a race within spall_step_margin_rad of roller rotation while it turns
  // relative to its orbit faster than spall_step_min_spin_ratio x the shaft's speed, from the
  // moment in the passage it carries spall_step_min_load_fraction of the mean roller load
  // F_r / Z (an unloaded roller's passage strikes nothing) until spall_step_linger_s after the
  // passage. The ramps, the rim edges' contact and the exit impact lose energy as the step
  // squared, nearly all the model's energy error, while the friction, slip and kinematics are
  // converged at the larger step (docs/BEARING_MODEL.md, "The lumped model").
  double time_step_safety = 0.9;
  double spalled_time_step_safety = 0.7;
  double spall_time_step_safety = 0.15;
  // The fast step rule (the scene's [solver] lumped_step = "fast"): every bearing takes
  // time_step_safety of the two-spring limit between its passages (one Palmgren spring per race:
  // a passage below spall_step_min_load_fraction of the mean roller load needs no more, the
  // stiffness going as Q^0.1) and fast_spall_time_step_safety of the three-spring limit in the
  // ramps and loaded passages: the paper scene's simulated second in about 1.8x fewer steps, its
  // energy balance 0.28 % against 0.074 %, the signal, cage speed and slip within the same
  // run-to-run scatter (docs/BEARING_MODEL.md, "The lumped model").
  double fast_spall_time_step_safety = 0.35;
  double spall_step_margin_rad = 0.02;
  double spall_step_min_spin_ratio = 0.1;
  double spall_step_min_load_fraction = 0.02;
  double spall_step_linger_s = 200e-6;
  // Sensor path: length of the FE housing's impulse responses the sensor channels convolve
  // the rollers' force with (e.g. 8e-3), and their sample rate. Off (0, the sensor reads the
  // rigid ring's motion times its static gain) by default: with it, a spalled roller's record
  // loses the roller comb the diagnosis finds (docs/BEARING_MODEL.md, "The lumped model").
  double sensor_response_s = 0;
  double sensor_sample_hz = 100e3;

  bool IsValid(std::string* error) const;
};

struct BearingModelOptions {
  // Bulk-modulus penalty scale f (k = f K L^2 / A t) for roller-race and roller-cage pairs.
  // Larger is stiffer (closer to Hertz/Palmgren) but shortens the contact stable step.
  double race_penalty_scale = 0.3;
  double cage_penalty_scale = 0.1;
  // Normal contact damping, fraction of critical of each contact spring.
  double contact_damping_ratio = 0.1;
  // Rigid-roller contact options (hybrid and lumped models).
  HybridOptions hybrid;
  LumpedOptions lumped;
  // Roller-guided cage's radial guide, every model (constraints.h); its play is the scene's
  // bearing.cage_radial_play_mm (BearingModel sets it).
  CageGuideOptions cage_guide;
  // Diagnostic: the solver keeps a work ledger per contact pair and constraint
  // (solver::SolverOptions::track_contributor_work; slower; FE models).
  bool track_contributor_work = false;
  // The FE solver's per-step energy terms (solver::SolverOptions::energy_terms; the rigid
  // rollers' are HybridOptions::energy_books). Off, the energies read NaN but the kinetic.
  bool energy_books = true;
  // FE housing only (hybrid mesh, no rollers): the lumped model's housing fit.
  bool housing_only = false;

  bool IsValid(std::string* error) const;
};

// One accelerometer channel: a point near the scene's sensor point and a direction.
struct SensorChannel {
  std::string sensor;  // scene sensor name
  Axis direction = Axis::kY;
  int node = -1;          // FE models: nearest outer-ring or adapter node
  double distance_m = 0;  // from the requested point to that node
};

// Rigid-body motion: mass centre, velocity, spin.
struct BodyMotion {
  double cx = 0, cy = 0, vx = 0, vy = 0, omega = 0;
};

class BearingModel {
 public:
  virtual ~BearingModel() = default;
  BearingModel(const BearingModel&) = delete;
  BearingModel& operator=(const BearingModel&) = delete;

  const Scene& scene() const { return scene_; }
  const BearingModelOptions& options() const { return options_; }
  virtual Fidelity fidelity() const = 0;
  int num_rollers() const { return scene_.geometry.bearing.num_elements; }

  // Time stepping: advance to end_time (central differences; the step set by the model).
  virtual solver::SolverSummary Run(double end_time) = 0;
  virtual double time() const = 0;
  virtual long step() const = 0;
  virtual double time_step() const = 0;  // last step taken (s)
  virtual solver::Energies energies() const = 0;
  // Per contributor work ledgers (FE models with track_contributor_work; else empty).
  virtual std::vector<solver::ContributorLedger> ContributorLedgers() const { return {}; }
  // Called at t = 0 and after every step.
  virtual void SetObserver(std::function<void()> observer) = 0;
  // The whole dynamic state as bytes (checkpoints); LoadState throws InputError on a mismatch.
  virtual std::string SaveState() const = 0;
  virtual void LoadState(const std::string& bytes) = 0;

  // Contact normal force on roller j (N, whole section) at the last step. Cage: both pocket
  // walls and the radial guide, summed.
  virtual double RollerOuterForce(int j) const = 0;
  virtual double RollerInnerForce(int j) const = 0;
  virtual double RollerCageForce(int j) const = 0;
  virtual BodyMotion RollerMotion(int j) const = 0;
  virtual BodyMotion CageMotion() const = 0;
  virtual BodyMotion InnerRingMotion() const = 0;  // velocity at n-1/2
  // The outer raceway's centre: its nodes' mean displacement (FE and hybrid), the rigid ring's
  // centre (lumped); velocity likewise at n-1/2; omega 0.
  virtual BodyMotion OuterRingMotion() const = 0;

  const std::vector<SensorChannel>& sensor_channels() const { return channels_; }
  // Velocity of channel c along its direction at t^(n-1/2) (m/s).
  virtual double SensorVelocity(int channel) const = 0;

  // Prescribed inner-ring speed (rad/s) and the pure-rolling cage speed 1/2 w_i (1 - D/d_m) at t.
  double InnerRingSpeed(double t) const { return speed_(t); }
  double TheoreticalCageSpeed(double t) const;

  // The meshed parts (FE: every part; hybrid: the housing; lumped: the housing its fit was made
  // on, not stepped) and the geometry they carry: raceway, pitch and roller radii, roller angles.
  virtual const BearingMesh& bearing_mesh() const = 0;
  // Element and node counts of the stepped mesh (0 for a model without one).
  virtual int num_elements() const = 0;
  virtual int num_nodes() const = 0;
  // Von Mises stress (Pa) at each element's centroid at the last step, in bearing_mesh()'s
  // element order, into out[0, num_elements()) (the "field" output).
  virtual void ElementVonMises(double* /*out*/) const {}
  const MeshQualityReport& mesh_quality() const { return mesh_quality_; }
  // A few lines for logs: parts, sizes, contacts, sensors.
  virtual std::string Describe() const = 0;
  // One line per known way this scene's model will not represent the bearing.
  virtual std::vector<std::string> Warnings() const { return {}; }

 protected:
  BearingModel(const Scene& scene, const BearingModelOptions& options);

  Scene scene_;
  BearingModelOptions options_;
  MeshQualityReport mesh_quality_;
  std::vector<SensorChannel> channels_;
  solver::TimeFunction speed_;
};

// The model for scene.model.fidelity (kFe, kHybrid or kLumped; kAuto must be resolved first,
// fidelity_choice.h). Throws InputError naming the scene key (or option).
std::unique_ptr<BearingModel> MakeBearingModel(const Scene& scene,
                                               const BearingModelOptions& options = {});

}  // namespace spallkit::sim
