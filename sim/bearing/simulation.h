// The run driver behind `spall simulate`: builds the bearing model of a scene, runs the explicit
// solver to [run] duration_s with a progress callback, writes checkpoints, resumes from one, and
// writes the results (HDF5, optional CSV) atomically.
//
// Checkpoints: every [solver] checkpoint_interval_s of simulated time (0: never) the solver and
// the recorder are saved to `<output>.ckpt` (atomically; one file, also holding the effective
// scene text so a checkpoint is never resumed with a different scene). With `resume` the run
// continues from it; the results are bit-identical to an uninterrupted run's (the solver and
// contact pairs are deterministic and the run is cut into Run() calls whose boundaries do not
// change any step). The checkpoint is removed once the results are written.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "sim/bearing/bearing_model.h"
#include "sim/bearing/recorder.h"
#include "sim/bearing/scene.h"

namespace spallkit::sim {

struct SimulationProgress {
  double time = 0.0, duration = 0.0;  // simulated, s
  long steps = 0;                     // total so far
  double time_step = 0.0;             // last, s
  double wall_seconds = 0.0;          // this process
  double start_time = 0.0;  // simulated time this process started at (a resume's checkpoint)
};

struct SimulationOptions {
  std::string output_path;  // HDF5 results; empty: keep in memory only (tests)
  std::string csv_path;     // accelerations as CSV (time, accel_y, accel_z); empty: none
  bool resume = false;      // continue from output_path + ".ckpt"
  // Checkpoint file; empty: output_path + ".ckpt" (needs an output_path when checkpointing).
  std::string checkpoint_path;
  // Stop (after writing a checkpoint) once the simulated time reaches this: an "interruption"
  // for tests and for splitting long runs into jobs. Results are written only when complete.
  double stop_after_s = std::numeric_limits<double>::infinity();
  double progress_interval_s = 0.0;  // simulated time between progress calls; 0: duration / 200
  std::function<void(const SimulationProgress&)> progress;
  BearingModelOptions model;
  int fine_factor = 8;  // acceleration fine grid / output rate
};

struct SimulationSummary {
  bool completed = false;  // reached duration_s and wrote the outputs
  bool resumed = false;
  double resumed_from_s = 0.0;
  double time = 0.0;
  long steps = 0;  // total, including steps before a resume
  long steps_this_run = 0;
  double min_time_step = 0.0, max_time_step = 0.0;
  double wall_seconds = 0.0;          // this process, time loop only
  double ns_per_element_cycle = 0.0;  // wall / (steps this run x elements)
  int elements = 0, nodes = 0, threads = 1;
  solver::Energies energies;
  double energy_balance_error = 0.0;
  double hourglass_to_internal = 0.0;
  // Cage after the ramp (samples with t >= 2 ramp_s, or the last half if that is empty); its
  // centre's mean distance from the bearing's (m): a roller-guided cage runs off-centre by about
  // its radial play (docs/BEARING_MODEL.md, "Cage").
  double cage_omega_mean = 0.0, cage_omega_theory = 0.0, cage_slip_mean = 0.0;
  double cage_offset_mean = 0.0, cage_radial_play = 0.0;  // m
  // Per contact pair / constraint energy accounts (options.model.track_contributor_work only).
  std::vector<solver::ContributorLedger> ledger;
  std::string BriefReport() const;
};

class Simulation {
 public:
  Simulation(const Scene& scene, SimulationOptions options);
  SimulationSummary Run();

  const BearingModel& model() const { return *model_; }
  BearingModel& model() { return *model_; }
  const Recorder& recorder() const { return *recorder_; }
  // Which fidelity runs and why (model.fidelity = "auto" resolved by ChooseFidelity); one line,
  // also stored in the HDF5 file (attributes "fidelity", "fidelity_reason").
  const std::string& fidelity_reason() const { return fidelity_reason_; }

 private:
  void SaveCheckpoint(const std::string& path) const;
  void LoadCheckpoint(const std::string& path);
  void WriteOutputs(const SimulationSummary& summary) const;
  void CheckEnergyBalance() const;  // throws NumericalError past solver.max_energy_error_percent

  SimulationOptions options_;
  std::unique_ptr<BearingModel> model_;
  std::unique_ptr<Recorder> recorder_;
  std::string fidelity_reason_;
};

}  // namespace spallkit::sim
