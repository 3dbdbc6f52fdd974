// Sliding episodes of a roller from its recorded spin (the paper's Fig. 9: the defective roller
// stops rolling, slides with the cage, then resumes rolling).
//
// A roller rolls when its spin relative to the cage, omega_roller - omega_cage, is at least
// `rolling_threshold` of the pure-rolling value -2 pi BSF (BSF = d_m/(2D) f_i (1 - gamma^2),
// core/bearing.h); otherwise it slides (a roller trapped on its spall orbits with the cage: its
// relative spin is 0). A sliding episode starts where rolling changes to sliding; episodes
// shorter than `min_episode_s` (an edge strike that brakes the spin for a few samples) are not
// counted, neither as sliding time nor as an episode.
#pragma once

#include <string>
#include <vector>

#include "sim/bearing/scene.h"

namespace spallkit::sim {

struct RollerSlidingOptions {
  double rolling_threshold = 0.5;  // fraction of the pure-rolling relative spin, (0, 1)
  double min_episode_s = 0.5e-3;   // shorter dips are not sliding episodes, s (>= 0)
  double from_s = 0.0;             // samples before this time are left out (speed ramp)
  bool Validate(std::string* error) const;
};

struct RollerSlidingSummary {
  double duration_s = 0.0;             // analysed time
  double rolling_fraction = 0.0;       // of the analysed time, [0, 1]
  int sliding_episodes = 0;            // rolling -> sliding changes
  double cage_revolutions = 0.0;       // over the analysed time (from the cage's own spin)
  double episodes_per_cage_rev = 0.0;  // sliding_episodes / cage_revolutions
  double mean_spin_ratio = 0.0;        // mean relative spin / pure-rolling relative spin
  bool resumed_rolling = false;        // rolled again after a sliding episode
  std::string BriefReport() const;
};

// Relative spin of pure rolling, omega_roller - omega_cage = -2 pi BSF (rad/s; negative: the
// rollers turn against the inner ring), for the inner ring turning at `inner_ring_rad_s`.
double PureRollingRelativeSpin(const BearingGeometry& bearing, double inner_ring_rad_s);

// `time`, `spin` (one roller's absolute spin) and `cage_omega` are sampled together (the
// recorder's /time, a column of /rollers/spin, /cage/omega); `pure_rolling_spin` from
// PureRollingRelativeSpin. Throws InputError for mismatched lengths, invalid options, a zero
// pure-rolling spin or no sample after from_s.
RollerSlidingSummary MeasureRollerSliding(const std::vector<double>& time,
                                          const std::vector<double>& spin,
                                          const std::vector<double>& cage_omega,
                                          double pure_rolling_spin,
                                          const RollerSlidingOptions& options = {});

}  // namespace spallkit::sim
