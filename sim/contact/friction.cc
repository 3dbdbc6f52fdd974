#include "sim/contact/friction.h"

#include <cmath>
#include <sstream>

namespace spallkit::sim::contact {

double FrictionLaw::Coefficient(double slip_speed) const {
  if (decay == 0.0) return static_coefficient;
  return dynamic_coefficient +
         (static_coefficient - dynamic_coefficient) * std::exp(-decay * std::abs(slip_speed));
}

bool FrictionLaw::IsValid(std::string* error) const {
  std::ostringstream os;
  if (!(static_coefficient >= 0.0) || !std::isfinite(static_coefficient)) {
    os << "friction static coefficient must be finite and >= 0, got " << static_coefficient;
  } else if (!(dynamic_coefficient >= 0.0) || !std::isfinite(dynamic_coefficient)) {
    os << "friction dynamic coefficient must be finite and >= 0, got " << dynamic_coefficient;
  } else if (!(decay >= 0.0) || !std::isfinite(decay)) {
    os << "friction decay coefficient must be finite and >= 0 s/m, got " << decay;
  } else {
    return true;
  }
  if (error) *error = os.str();
  return false;
}

FrictionUpdate ReturnMap(double previous_force,
                         double slip_increment,
                         double stiffness,
                         double cap) {
  FrictionUpdate out;
  const double trial = previous_force - stiffness * slip_increment;
  const double magnitude = std::abs(trial);
  if (magnitude <= cap) {
    out.force = trial;
    return out;
  }
  out.sliding = true;
  out.force = std::copysign(cap, trial);
  out.dissipation = stiffness > 0.0 ? cap * (magnitude - cap) / stiffness : 0.0;
  return out;
}

}  // namespace spallkit::sim::contact
