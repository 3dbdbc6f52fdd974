// The lumped bearing model (the rung below the hybrid, docs/BEARING_MODEL.md): the
// hybrid's rigid rollers, cage and inner ring (roller_contacts.h: exact spall profiles, Palmgren
// line contact, traction, pocket contact) on a RIGID outer ring carried by the housing's
// stiffness; each sensor channel reads a gain times the ring's velocity (or the FE housing's
// impulse responses when LumpedOptions::sensor_response_s > 0). No mesh is stepped, so
// the time step is the roller contacts' and a simulated second costs a few seconds of one core
// (docs/PERFORMANCE.md, "Fidelity ladder").
//
// Housing fit (FitHousing, once per geometry and cached in the process): the scene's FE housing
// (outer ring tied to the elastic or rigid adapter, the hybrid model's mesh at
// LumpedOptions::fit_mesh_size_m) is loaded on its raceway by a Stribeck roller-load pattern
// (Q_j ~ cos^(10/9) psi_j over the loaded half, through the hybrid's raceway kernel) along -y
// and +x, and relaxed to rest with heavy mass damping. Per direction d:
//  - stiffness K_d = F / c_d, c_d = sum_j Q_j (u_j . e_j) / F the load-weighted radial approach
//    of the raceway (the displacement of a rigid ring that does the same work);
//  - mass M_d = sum_i m_i |u_i|^2 / c_d^2, the Rayleigh mass of the static shape (the housing's
//    fundamental radial mode in that direction, frequency sqrt(K_d / M_d));
//  - damping C_d = 4 pi zeta f_ref M_d, the scene's mass-proportional damping on that mass;
//  - sensor gain g_c = u_c / c_d of each channel in its direction's load case.
// The ring moves as two independent oscillators (x and y) under the roller reactions.
// Sensor path: the FE housing (the scene's damping) is hit once per geometry by a force held for
// one sample on the raceway at the load line, along -y and along +x; each channel's velocity
// records are its impulse responses, and in the run the channel reads the convolution of the
// rollers' resultant force on the ring (its -y and +x parts, averaged over each sample) with
// them: the housing's modes and wave paths as the FE model has them, linear, one way (they do
// not act back on the rollers). With sensor_response_s = 0 channel c reads g_c times the ring's
// velocity. Limits (docs/BEARING_MODEL.md, "The lumped model"): the sensor sees the resultant
// force as if it acted at the load line; no local raceway deflection under a roller in the
// contacts; no ring rotation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sim/bearing/bearing_model.h"
#include "sim/bearing/rigid_outer_race.h"
#include "sim/bearing/roller_contacts.h"

namespace spallkit::sim {

struct HousingFit {
  double stiffness[2] = {0, 0};     // K_x, K_y (N/m)
  double mass[2] = {0, 0};          // M_x, M_y (kg)
  double damping[2] = {0, 0};       // C_x, C_y (N s/m)
  std::vector<double> sensor_gain;  // per sensor channel (scene order)
  // Sensor path (sensor_response_s > 0): response[c][p][i], channel c's mean velocity along its
  // axis over [i h, (i + 1) h] (m/s) per newton of a force held for one sample h = 1 /
  // sensor_sample_hz on the raceway at the load line, along -y (p = 0) or +x (p = 1); tapered
  // over its last quarter and corrected to sum to zero (no velocity under a constant force).
  std::vector<std::vector<std::vector<double>>> sensor_response;
  // Relative change of c_d over the last fifth of the relaxation (0: fully at rest).
  double residual_motion = 0.0;
  double fit_wall_s = 0.0;        // wall time of the fit (0 when it came from the cache)
  double Frequency(int d) const;  // sqrt(K_d / M_d) / 2 pi (Hz)
};

// Fits the housing of `scene` (see above); cached by the scene's housing geometry, materials,
// damping, adapter, sensors and the options. Throws InputError.
HousingFit FitHousing(const Scene& scene, const BearingModelOptions& options);
// The scene whose FE housing the fit runs (the hybrid's housing mesh at fit_mesh_size_m).
Scene HousingFitScene(const Scene& scene, const LumpedOptions& options);
// Channel c's sensor-path velocity (m/s) after the newest force sample: the convolution of the
// force histories (N, mean over each sample; along -y and +x; ring buffers of the responses'
// length with the newest sample at `newest`) with the channel's impulse responses.
double SensorPathVelocity(const HousingFit& fit,
                          int channel,
                          const std::vector<double>& f_down,
                          const std::vector<double>& f_x,
                          long newest);

class LumpedBearingModel : public BearingModel {
 public:
  // Fits (or takes from the cache) the housing and builds the rigid parts. Throws InputError.
  explicit LumpedBearingModel(const Scene& scene, const BearingModelOptions& options = {});

  Fidelity fidelity() const override { return Fidelity::kLumped; }
  solver::SolverSummary Run(double end_time) override;
  double time() const override { return time_; }
  long step() const override { return step_; }
  double time_step() const override { return dt_; }
  solver::Energies energies() const override;
  void SetObserver(std::function<void()> observer) override { observer_ = std::move(observer); }
  std::string SaveState() const override;
  void LoadState(const std::string& bytes) override;

  double RollerOuterForce(int j) const override { return rollers_.OuterForce(j); }
  double RollerInnerForce(int j) const override { return rollers_.InnerForce(j); }
  double RollerCageForce(int j) const override { return rollers_.CageForce(j); }
  BodyMotion RollerMotion(int j) const override;
  BodyMotion CageMotion() const override;
  BodyMotion InnerRingMotion() const override;
  BodyMotion OuterRingMotion() const override {
    return {race_.x_, race_.y_, race_.vx_, race_.vy_, 0.0};
  }
  double SensorVelocity(int channel) const override;
  const BearingMesh& bearing_mesh() const override { return housing_; }
  int num_elements() const override { return 0; }
  int num_nodes() const override { return 0; }
  std::string Describe() const override;

  const HousingFit& housing() const { return fit_; }
  const RollerContacts& rollers() const { return rollers_; }
  // Outer ring centre and its velocity at n-1/2.
  const RigidOuterRace& outer_ring() const { return race_; }
  // Stable step (s): the roller contacts' and the ring oscillators'.
  double stable_time_step() const { return dt_stable_; }

 private:
  void Step();
  // Adds the step's force to the sensor sample being filled; completes it every 1 /
  // sensor_sample_hz.
  void SensorSample(double f_down, double f_x, double dt);

  BearingMesh housing_;  // the fit's housing mesh: geometry only, not stepped
  HousingFit fit_;
  RollerContacts rollers_;
  RigidOuterRace race_;
  std::function<void()> observer_;
  double dt_stable_ = 0, dt_spall_ = 0;  // step, and step in spall passages
  double spall_min_load_ = 0;            // N: a passage counts from this roller load on
  std::vector<int> spalled_;             // the spalled rollers
  // State (checkpointed).
  double time_ = 0, dt_ = 0, dt_prev_ = 0;
  // Per roller: whether its current spall passage has carried spall_min_load_ (1) or not (0);
  // and the time until which the short step is kept (the end of the last loaded passage plus
  // LumpedOptions::spall_step_linger_s).
  std::vector<std::uint8_t> loaded_passage_;
  double short_step_until_ = -1.0;
  long step_ = 0;
  double spring_energy_ = 0, housing_damping_work_ = 0;
  bool started_ = false;
  double ring_v_old_[2] = {0, 0};  // ring velocity at n-1/2 of the last step (energy at t^n)
  // Sensor convolution: force history per probe direction (ring buffers, newest at
  // history_pos_), the force integral and time of the sample being filled, and each channel's
  // velocity at the last two sample instants.
  std::vector<double> history_[2];
  long history_pos_ = 0;
  double sample_force_[2] = {0, 0}, sample_time_ = 0;
  std::vector<double> sensor_prev_, sensor_last_;
  // The last step's second half (t^n to t^(n+1/2)) of the housing spring's and damper's work,
  // left out of energies() (at t^n).
  double spring_half_ = 0, damping_half_ = 0;
};

}  // namespace spallkit::sim
