// The central-difference stability limit of a damped oscillator: a step below
// 2 / omega (sqrt(1 + zeta^2) - zeta) (omega its undamped angular frequency, zeta its damping
// ratio) keeps x'' + 2 zeta omega x' + omega^2 x = 0 stable (Belytschko, Liu & Moran, section 6.3).
#pragma once

#include <cmath>

namespace spallkit::sim::solver {

inline double DampedStableStep(double omega, double zeta) {
  return 2.0 / omega * (std::sqrt(1 + zeta * zeta) - zeta);
}

}  // namespace spallkit::sim::solver
