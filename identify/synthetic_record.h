// Synthetic accelerometer records of spalled rollers with a known answer, for the identification's
// tests, benchmark and tuning. Not a dynamic model: an impulse-train signal model with the
// physics the identification relies on, each piece switchable:
//   - each defective roller sits in its cage slot s (angle 2 pi s / Z ahead of roller 0 in the
//     direction of rotation) and goes round at the cage rate f_c; its spall meets the outer race
//     when the roller's spin phase (relative to the cage) passes phi_k and the inner race half a
//     turn later, i.e. at 2 x spin = f_b;
//   - a passage over a race is two events: entry (the roller drops into the spall: a weaker,
//     lower-frequency ring-down) and exit (the trailing edge strikes: the main impulse), the
//     exit dt = chord angle / spin rate after the entry, w = d sin(pi f_s dt) (w = chord);
//   - both scale with the roller load (Harris-Jones, identify/load_zone.h) as q(psi)^exponent,
//     with a small floor outside the load zone; inner-race hits reach the sensor weaker; with a
//     sensor direction, each event reaches it with cos(psi - sensor angle) (an impact along the
//     roller's radius at orbit angle psi);
//   - slip: cage and spin rates off the kinematic ones by fixed fractions, plus a random walk of
//     each defective roller's spin phase once per cage revolution (it slides while unloaded) and
//     a small jitter of every event;
//   - structural resonances (damped sines) and white Gaussian noise at a given SNR in a band.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "core/bearing.h"
#include "core/record.h"
#include "dsp/band.h"

namespace spallkit::identify {

struct SyntheticRoller {
  int slot = 0;                 // cage slot, 0..Z-1
  double width_m = 1.38e-3;     // spall chord in the rolling direction
  double spin_phase_rad = 0.0;  // spin phase (from the outer-race contact) of the spall at t = 0
  double gain = 1.0;            // event amplitude factor
};

struct SyntheticResonance {
  double hz = 3000.0;
  double damping_ratio = 0.05;
  double gain = 1.0;
};

struct SyntheticRecordSpec {
  BearingGeometry bearing;  // default: N205EM (set in the constructor)
  double shaft_hz = 20.0;
  double sample_rate_hz = 20000.0;
  double duration_s = 1.0;
  double radial_load_n = 10000.0;
  double diametral_clearance_m = 20e-6;
  double roller_length_m = 9e-3;
  double cage_slip = -0.005;       // f_c = kinematic x (1 + cage_slip)
  double spin_slip = -0.005;       // f_s = kinematic x (1 + spin_slip)
  double roller0_angle_rad = 0.0;  // roller 0 from the load line at t = 0
  std::vector<SyntheticRoller> rollers;
  std::vector<SyntheticResonance> resonances = {{3000.0, 0.05, 1.0}, {6200.0, 0.04, 0.5}};
  double load_exponent = 0.5;    // event amplitude ~ q^load_exponent (squared envelope ~ q^(2x))
  double unloaded_floor = 0.05;  // relative amplitude outside the load zone
  // The sensor's direction from the load line (rad; pi/2: horizontal under a vertical load);
  // unset: every event reaches the sensor whole, wherever the roller is.
  std::optional<double> sensor_angle_rad;
  double inner_race_ratio = 0.6;  // inner-race events relative to outer-race events
  // Inner-race events reach the sensor with the outer ones' projection; false: whole, wherever
  // the roller is (through the shaft), so that the two races' impacts have different cage-angle
  // patterns, as in spallkit's simulator (identify/count_fit.h, feature B).
  bool inner_race_projected = true;
  double entry_ratio = 0.35;        // entry amplitude relative to exit
  double entry_resonance_hz = 0.0;  // entry rings this (lower) resonance; 0: the exit's ones
  double entry_damping_ratio = 0.08;
  double spin_phase_walk_rad = 0.05;  // std of the spin phase step per cage revolution
  double event_jitter_s = 10e-6;      // std of each event's time
  double snr_db = std::numeric_limits<double>::infinity();  // signal / noise power in snr_band
  dsp::Band snr_band;                                       // {0, 0}: the first resonance +/- 25 %
  unsigned seed = 1;

  SyntheticRecordSpec();
};

// What the record holds (for tests): kinematic and actual rates, and per roller its exit delay.
struct SyntheticTruth {
  double cage_hz = 0.0;
  double spin_hz = 0.0;  // roller spin relative to the cage (f_b = 2 x spin_hz)
  double surface_speed_m_s = 0.0;
  std::vector<double> exit_delay_s;  // per roller: exit - entry
  double noise_rms = 0.0;
  double load_zone_half_angle_rad = 0.0;
};

// The record (channel "synthetic", units "m/s^2"). Throws InputError for an invalid spec (slot
// out of range, two spalls in one slot, width >= roller diameter, non-positive rates).
Record MakeSyntheticRecord(const SyntheticRecordSpec& spec, SyntheticTruth* truth = nullptr);

}  // namespace spallkit::identify
