#include "sim/contact/contact_options.h"

#include <cmath>
#include <sstream>

namespace spallkit::sim::contact {

bool ContactPairOptions::IsValid(std::string* error) const {
  std::ostringstream os;
  if (!(penalty_scale > 0.0) || !std::isfinite(penalty_scale)) {
    os << "penalty_scale must be finite and > 0, got " << penalty_scale;
  } else if (penalty_law == PenaltyLaw::kConstant && !(constant_stiffness > 0.0)) {
    os << "constant_stiffness must be > 0 N/m for the constant penalty law, got "
       << constant_stiffness;
  } else if (!(reference_time_step >= 0.0)) {
    os << "reference_time_step must be >= 0 s, got " << reference_time_step;
  } else if (!friction.IsValid(error)) {
    return false;
  } else if (!(tangential_stiffness_ratio > 0.0)) {
    os << "tangential_stiffness_ratio must be > 0, got " << tangential_stiffness_ratio;
  } else if (!(normal_damping_ratio >= 0.0)) {
    os << "normal_damping_ratio must be >= 0, got " << normal_damping_ratio;
  } else if (!(search_margin >= 0.0) || !(capture_depth >= 0.0)) {
    os << "search_margin and capture_depth must be >= 0 m";
  } else if (search_margin > 0.0 && capture_depth > 0.5 * search_margin) {
    os << "capture_depth (" << capture_depth << " m) must be <= search_margin / 2 ("
       << 0.5 * search_margin << " m)";
  } else if (!(stable_step_safety > 0.0 && stable_step_safety <= 1.0)) {
    os << "stable_step_safety must be in (0, 1], got " << stable_step_safety;
  } else {
    return true;
  }
  if (error) *error = os.str();
  return false;
}

}  // namespace spallkit::sim::contact
