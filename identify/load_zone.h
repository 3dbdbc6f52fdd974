// The load zone a defective roller crosses once per cage revolution, as the identification's
// hump shape: the roller load Q(psi) relative to its maximum, from the Harris-Jones load
// distribution (sim/quasistatic/harris_jones.h).
//
// With the total approach s(psi) = delta_r cos(psi) - P_d/2 = delta_r (cos psi - cos psi_l) and
// Palmgren's Q ~ s^(10/9), the relative load is
//     q(psi) = [(cos psi - cos psi_l) / (1 - cos psi_l)]^(10/9)   for |psi| < psi_l, else 0,
// so the shape depends on the half angle psi_l alone, which the solver gives for the record's
// radial load, clearance and speed. (The centrifugal force, which keeps a small outer-race load
// outside the zone, is neglected: at 900-1800 rpm it is < 1 % of Q_max for an N205EM.)
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "core/bearing.h"

namespace spallkit::identify {

struct LoadZone {
  double half_angle_rad = 0.0;  // psi_l
  double q_max_n = 0.0;         // largest roller load (0 when no load was given)
  bool from_load = false;       // true: psi_l solved for a given radial load

  // q(psi) in [0, 1], psi from the load line (any real angle; wrapped).
  double Relative(double psi_rad) const;
};

// The load zone for a radial load (N) on the inner ring at shaft_hz, clearance P_d (m), effective
// roller length (m). Throws InputError for a non-physical input or when the solver does not
// converge.
LoadZone SolveLoadZone(const BearingGeometry& bearing,
                       double radial_load_n,
                       double shaft_hz,
                       double diametral_clearance_m,
                       double roller_length_m);

// Relative load at psi for a half angle psi_l (the formula above); templated for ceres::Jet.
template <typename T>
T RelativeLoad(const T& psi, const T& half_angle) {
  using std::cos;
  using std::pow;
  const T c = cos(psi), cl = cos(half_angle);
  if (!(c > cl)) return T(0.0);
  return pow((c - cl) / (T(1.0) - cl), T(10.0 / 9.0));
}

}  // namespace spallkit::identify
