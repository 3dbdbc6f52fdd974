#include "identify/load_zone.h"

#include <cmath>

#include "core/constants.h"
#include "core/error.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::identify {

double LoadZone::Relative(double psi_rad) const {
  return RelativeLoad(std::remainder(psi_rad, 2.0 * kPi), half_angle_rad);
}

LoadZone SolveLoadZone(const BearingGeometry& bearing,
                       double radial_load_n,
                       double shaft_hz,
                       double diametral_clearance_m,
                       double roller_length_m) {
  sim::LoadDistributionOptions o;
  o.radial_load_n = radial_load_n;
  o.inner_ring_speed_rad_s = 2.0 * kPi * shaft_hz;
  o.diametral_clearance_m = diametral_clearance_m;
  o.roller_length_m = roller_length_m;
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  sim::LoadDistributionSummary s;
  sim::SolveLoadDistribution(o, bearing, &s);
  if (!s.IsSolutionUsable())
    throw NumericalError("load distribution for " + std::to_string(radial_load_n) +
                         " N did not converge: " + s.message);
  LoadZone z;
  z.half_angle_rad = s.load_zone_half_angle_rad;
  z.q_max_n = s.q_max_n;
  z.from_load = true;
  return z;
}

}  // namespace spallkit::identify
