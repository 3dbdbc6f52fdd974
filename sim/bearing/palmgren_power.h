// Palmgren's d^(10/9) for a penetration that moves little from one call to the next.
//
// Why: the rigid-roller models evaluate Palmgren's law Q = K d^(10/9) at every contact point at
// every step, and std::pow was the largest single cost of a lumped step. A contact's penetration
// moves by a small fraction of itself per step, so d^(10/9) is a quartic Taylor expansion about
// the last exactly computed point d0 while |d / d0 - 1| <= kPalmgrenSpan (truncation below 5e-13
// relative: the next term is 0.005 r^5), and std::pow only when the penetration has moved
// further (on the paper scene 18 % of the calls, nine in ten of them the unloaded rollers'
// rattling micrometre-scale contacts). The expansion point is the caller's state (checkpointed
// with the model, so a resumed run takes the same branches).
#pragma once

#include "sim/contact/near_power.h"

namespace spallkit::sim {

inline constexpr double kPalmgrenSpan = 1e-2;

// d^(10/9) for d > 0; *d0, *p0: the expansion point and d0^(10/9), updated when d is out of
// reach (start with *d0 = 0).
inline double PalmgrenPowerNear(double d, double* d0, double* p0) {
  return contact::NearPower<10, 9>(d, kPalmgrenSpan, d0, p0);
}

}  // namespace spallkit::sim
