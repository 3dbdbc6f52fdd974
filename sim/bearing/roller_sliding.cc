#include "sim/bearing/roller_sliding.h"

#include <cmath>
#include <cstdio>

#include "core/constants.h"
#include "core/error.h"

namespace spallkit::sim {

bool RollerSlidingOptions::Validate(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (!(rolling_threshold > 0 && rolling_threshold < 1))
    return fail("roller sliding: rolling_threshold must be in (0, 1)");
  if (!(min_episode_s >= 0)) return fail("roller sliding: min_episode_s must be >= 0");
  if (!std::isfinite(from_s)) return fail("roller sliding: from_s must be finite");
  return true;
}

std::string RollerSlidingSummary::BriefReport() const {
  char buf[256];
  std::snprintf(buf,
                sizeof buf,
                "rolling %.1f %% of %.1f ms, %d sliding episodes (%.2f per cage revolution), "
                "mean spin %.3f of rolling%s",
                100.0 * rolling_fraction,
                1e3 * duration_s,
                sliding_episodes,
                episodes_per_cage_rev,
                mean_spin_ratio,
                resumed_rolling ? ", resumed rolling" : "");
  return buf;
}

double PureRollingRelativeSpin(const BearingGeometry& bearing, double inner_ring_rad_s) {
  const double gamma =
      bearing.element_diameter_m * std::cos(bearing.contact_angle_rad) / bearing.pitch_diameter_m;
  return -bearing.pitch_diameter_m / (2.0 * bearing.element_diameter_m) * (1 - gamma * gamma) *
         inner_ring_rad_s;
}

RollerSlidingSummary MeasureRollerSliding(const std::vector<double>& time,
                                          const std::vector<double>& spin,
                                          const std::vector<double>& cage_omega,
                                          double pure_rolling_spin,
                                          const RollerSlidingOptions& o) {
  std::string err;
  if (!o.Validate(&err)) throw InputError(err);
  if (spin.size() != time.size() || cage_omega.size() != time.size())
    throw InputError("roller sliding: time, spin and cage speed must have the same length");
  if (!(std::abs(pure_rolling_spin) > 0) || !std::isfinite(pure_rolling_spin))
    throw InputError("roller sliding: the pure-rolling spin must be finite and non-zero");
  size_t first = 0;
  while (first < time.size() && time[first] < o.from_s) ++first;
  const size_t n = time.size() - first;
  if (n < 2) throw InputError("roller sliding: fewer than 2 samples after from_s");

  // Classify each sample, then give short sliding runs back to rolling.
  std::vector<char> rolling(n);
  double ratio_sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const double ratio = (spin[first + i] - cage_omega[first + i]) / pure_rolling_spin;
    ratio_sum += ratio;
    rolling[i] = ratio >= o.rolling_threshold;
  }
  const double dt = (time.back() - time[first]) / static_cast<double>(n - 1);
  for (size_t i = 0; i < n;) {
    if (rolling[i]) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < n && !rolling[end]) ++end;
    // A run bounded by rolling on both sides and shorter than min_episode_s is a dip.
    if (i > 0 && end < n && static_cast<double>(end - i) * dt < o.min_episode_s)
      for (size_t k = i; k < end; ++k) rolling[k] = 1;
    i = end;
  }

  RollerSlidingSummary s;
  s.duration_s = time.back() - time[first];
  size_t rolled = 0;
  for (size_t i = 0; i < n; ++i) {
    rolled += rolling[i] ? 1 : 0;
    if (i > 0 && rolling[i - 1] && !rolling[i]) ++s.sliding_episodes;
    if (i > 0 && !rolling[i - 1] && rolling[i]) s.resumed_rolling = true;
  }
  s.rolling_fraction = static_cast<double>(rolled) / static_cast<double>(n);
  double angle = 0;
  for (size_t i = first + 1; i < time.size(); ++i)
    angle += 0.5 * (cage_omega[i] + cage_omega[i - 1]) * (time[i] - time[i - 1]);
  s.cage_revolutions = std::abs(angle) / (2 * kPi);
  s.episodes_per_cage_rev = s.cage_revolutions > 0 ? s.sliding_episodes / s.cage_revolutions : 0;
  s.mean_spin_ratio = ratio_sum / static_cast<double>(n);
  return s;
}

}  // namespace spallkit::sim
