// Numerical stability stress test of the bearing simulator (`spall stress`, docs/RELIABILITY.md).
//
// Draws scenes across and beyond the documented ranges (speed 0-20,000 rpm with standing starts,
// radial load 0-50 kN with load steps, clearance 0-0.1 mm, spall width 0-3 mm, depth up to r/2,
// 0-13 spalled rollers, friction 0-0.3, damping 0-0.2, housing mesh 1-5 mm, runs of 1-20 ms;
// about one scene in six takes one key beyond its range). Each scene must either
//   (a) be rejected up front (ParseScene or the model builder throws InputError) with a one-line
//       reason naming the key, or
//   (b) run to the end with every recorded value finite, the energy balance error within
//       options.max_energy_error_percent, and no roller through a race (the centre-distance
//       overlap of each roller with each race at most its spall depth plus max_overlap_fraction
//       of its radius, checked at every progress point).
// Anything else is a failure: a bug to fix or a range to reject. Each case keeps the `--set`
// list that reproduces it (`spall simulate /dev/null -o out.h5 --set ...`).
//
//   sim::stress::StressOptions o;
//   o.scenes = 20;
//   const sim::stress::StressSummary s = sim::stress::RunStress(o);
//   std::printf("%s\n%s", s.BriefReport().c_str(), s.Table().c_str());
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sim/bearing/scene.h"

namespace spallkit::sim::stress {

enum class StressOutcome { kRejected, kPassed, kFailed };
const char* StressOutcomeName(StressOutcome outcome);  // "rejected", "passed", "FAILED"

struct StressCase {
  int index = 0;
  std::vector<std::string> overrides;  // scene keys ("key=value") over the default scene
  bool beyond_range = false;           // drawn with one key outside the documented range
  StressOutcome outcome = StressOutcome::kFailed;
  std::string reason;  // the rejection message, or what failed
  double energy_error_percent = 0.0;
  double max_overlap_fraction = 0.0;  // worst roller-race overlap / roller radius (beyond spalls)
  long steps = 0;
  double wall_seconds = 0.0;
  std::string Reproduce() const;  // "--set a=b --set c=d ..."
};

struct StressOptions {
  int scenes = 200;
  std::uint64_t seed = 1;
  sim::Fidelity fidelity = sim::Fidelity::kHybrid;  // of every scene: hybrid, lumped or fe
  // Upper bound of the simulated time per scene, s (the fixed-seed test subset uses a short one).
  double max_duration_s = 0.02;
  double min_mesh_size_mm = 1.0;  // housing mesh size drawn (hybrid), log-uniform [min, max]
  double max_mesh_size_mm = 5.0;
  double beyond_fraction = 1.0 / 6.0;
  // Checks of a run (b): the documented energy bound and the roller-race overlap bound.
  double max_energy_error_percent = 1.0;
  double max_overlap_fraction = 0.05;
  // Called after each scene (progress output).
  std::function<void(const StressCase&)> progress;

  bool Validate(std::string* error) const;
};

struct StressSummary {
  std::vector<StressCase> cases;
  int rejected = 0, passed = 0, failed = 0;
  double wall_seconds = 0.0;
  std::string BriefReport() const;  // one line: counts and time
  std::string Table() const;        // one row per scene, then every failure with its --set list
  std::string ToJson(int indent = 2) const;
};

// The `--set` list of scene `index` for `seed` (deterministic: the same scene on every machine).
StressCase DrawScene(const StressOptions& options, int index);

// Runs one drawn scene (in memory, nothing written) and fills outcome, reason and the checks.
void RunScene(const StressOptions& options, StressCase* c);

// Draws and runs options.scenes scenes. Throws InputError when the options are not valid.
StressSummary RunStress(const StressOptions& options);

}  // namespace spallkit::sim::stress
