// Coulomb friction law with a slip-rate dependent coefficient (LS-DYNA *CONTACT FS/FD/DC form).
//
//   mu(v) = mu_d + (mu_s - mu_d) * exp(-decay * |v|),   v = tangential slip rate (m/s)
//
// so mu(0) = mu_s (static) and mu(v -> inf) = mu_d (dynamic); decay * |v| = 0.693 is halfway.
// decay = 0 means mu = mu_s at every slip rate. (OpenRadioss PR #3349 fixed a version of this law
// with the two coefficients swapped: the unit tests pin both limits.)
//
// The contact pair uses it as the cap of an elastic trial force: a tangential spring per slave
// node, F_t <- F_t - k_t * v_t * dt, returned to mu(|v_t|) * |F_n| when it exceeds it.
#pragma once

#include <string>

namespace spallkit::sim::contact {

struct FrictionLaw {
  double static_coefficient = 0.0;   // mu_s, >= 0
  double dynamic_coefficient = 0.0;  // mu_d, >= 0 (usually <= mu_s)
  double decay = 0.0;                // dc, s/m, >= 0

  // mu at slip rate `slip_speed` (m/s; the sign is ignored).
  double Coefficient(double slip_speed) const;

  // True when friction is switched off (both coefficients zero).
  bool IsFrictionless() const { return static_coefficient == 0.0 && dynamic_coefficient == 0.0; }

  bool IsValid(std::string* error) const;
};

// Result of one return mapping of the elastic trial force.
struct FrictionUpdate {
  double force = 0.0;        // new tangential force (signed, along the tangent)
  double dissipation = 0.0;  // energy dissipated by slip in this step, J (>= 0)
  bool sliding = false;      // the trial force exceeded the cap
};

// One step of the incremental tangential spring: trial = previous_force - stiffness *
// slip_increment, capped at `cap` = mu |F_n| (>= 0). Dissipation |F| * (|trial| - |F|) / stiffness
// is the work of the capped force on the slip part of the increment (the return mapping's plastic
// slip).
FrictionUpdate ReturnMap(double previous_force,
                         double slip_increment,
                         double stiffness,
                         double cap);

}  // namespace spallkit::sim::contact
