#include "sim/contact/traction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace spallkit::sim::contact {

const char* TractionModelName(TractionModel model) {
  switch (model) {
    case TractionModel::kCoulomb:
      return "coulomb";
    case TractionModel::kEhl:
      return "ehl";
  }
  return "coulomb";
}

bool ParseTractionModel(const std::string& name, TractionModel* model) {
  for (TractionModel m : {TractionModel::kCoulomb, TractionModel::kEhl})
    if (name == TractionModelName(m)) {
      *model = m;
      return true;
    }
  return false;
}

double EhlTraction::Coefficient(double slide_to_roll) const {
  // -expm1 keeps the viscous slope exact at small s.
  return -limiting_coefficient * std::expm1(-std::abs(slide_to_roll) / slide_roll_scale);
}

double EhlTraction::Force(double normal_force,
                          double slip_speed,
                          double entrainment_speed,
                          double tangential_mass,
                          double dt) const {
  const double v = std::abs(slip_speed);
  if (!(v > 0.0) || !(normal_force > 0.0)) return 0.0;
  const double ue = std::abs(entrainment_speed);
  // The force that stops the slip within the step (no step: no limit).
  const double stop =
      dt > 0.0 ? 0.5 * tangential_mass * v / dt : std::numeric_limits<double>::infinity();
  // 1 - exp(-x) >= x / (1 + x) with x = s / s_0 = v / (u_e s_0): where the stopping force
  // m v / (2 dt) is below that bound of the curve, i.e. m (u_e s_0 + v) / 2 <= Lambda N dt
  // (multiplied out: no division in the test), the minimum is the stopping force and the
  // exponential is not needed (a rolling roller's small slip, where the curve is steeper than
  // the step resolves).
  if (dt > 0.0 && 0.5 * tangential_mass * (ue * slide_roll_scale + v) <=
                      limiting_coefficient * normal_force * dt)
    return -std::copysign(stop, slip_speed);
  const double s = ue > 0.0 ? v / ue : std::numeric_limits<double>::infinity();
  return -std::copysign(std::min(Coefficient(s) * normal_force, stop), slip_speed);
}

bool EhlTraction::IsValid(std::string* error) const {
  std::ostringstream os;
  if (!(limiting_coefficient > 0.0 && limiting_coefficient < 1.0)) {
    os << "EHL limiting traction coefficient must be in (0, 1), got " << limiting_coefficient;
  } else if (!(slide_roll_scale > 0.0) || !std::isfinite(slide_roll_scale)) {
    os << "EHL slide-to-roll scale s_0 must be finite and > 0, got " << slide_roll_scale;
  } else {
    return true;
  }
  if (error) *error = os.str();
  return false;
}

}  // namespace spallkit::sim::contact
