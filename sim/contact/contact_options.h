// Settings of a contact pair (ContactPair): penalty law, friction, damping, search, surface model.
#pragma once

#include <string>

#include "sim/contact/friction.h"
#include "sim/contact/penalty.h"

namespace spallkit::sim::contact {

struct ContactPairOptions {
  PenaltyLaw penalty_law = PenaltyLaw::kBulkModulus;
  double penalty_scale = 0.1;        // f (bulk modulus law) or s (mass / time-step law)
  double constant_stiffness = 0.0;   // N/m, kConstant law only
  double reference_time_step = 0.0;  // s, mass / time-step law; 0: dt of the first AddForces

  FrictionLaw friction;                     // frictionless by default
  double tangential_stiffness_ratio = 1.0;  // k_t / k (stick stiffness)

  double normal_damping_ratio = 0.0;  // fraction of critical, 2 sqrt(k m*), m* reduced mass
  bool symmetric = false;             // second pass with the surfaces swapped

  // Search. 0 = automatic: margin = mean master segment length, capture depth = margin / 2.
  double search_margin = 0.0;  // m, grid growth; rebuild after margin/2 of master motion
  double capture_depth = 0.0;  // m, deepest penetration still treated as contact (<= margin / 2)

  // Both surfaces curved: touch as cubic B-splines of their smooth nodes (spline_surface.h)
  // instead of the arcs' blend; nodes near a kink (a spall's corners) keep node contact.
  bool smooth_surfaces = false;

  double stable_step_safety = 0.9;  // factor on 2 / omega in StableTimeStep()
  int parallel_min_nodes = 2048;    // OpenMP only for passes with at least this many slave nodes

  bool IsValid(std::string* error) const;
};

}  // namespace spallkit::sim::contact
