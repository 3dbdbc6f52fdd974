// Lubricant (EHL) traction of a rolling-sliding contact, the alternative to Coulomb friction for
// the roller-race contacts of the rigid-roller models (sim/bearing/roller_contacts.h).
//
// In an elastohydrodynamic contact the film carries the tangential force, not asperities: the
// traction is zero in pure rolling and grows with the slide-to-roll ratio
//   s = |u_1 - u_2| / u_e,  u_e = |u_1 + u_2| / 2 (entrainment speed),
// u_1, u_2 the two surfaces' speeds relative to the contact point, until the film's shear stress
// reaches its limit. The film follows the limiting-shear-stress law of Bair & Winer (J. Lubr.
// Technol. 101 (1979) 258-264), tau = tau_L (1 - exp(-eta gamma' / tau_L)), with the limit
// proportional to pressure, tau_L = Lambda p. Over a film of thickness h sheared at
// gamma' = s u_e / h, with one effective viscosity and pressure for the contact, the traction
// coefficient is
//   mu(s) = Lambda (1 - exp(-s / s_0)),   s_0 = Lambda p h / (eta u_e)
// (the initial slope Lambda / s_0 is the film's Newtonian viscous drag; the limit Lambda the
// limiting traction). Bearing oils reach their limiting traction at slide-to-roll ratios of a few
// per cent with Lambda about 0.05-0.1 (Evans & Johnson, Proc. IMechE C 200 (1986) 313-324);
// shear heating, which lowers the traction at large s, is not modelled.
#pragma once

#include <string>

namespace spallkit::sim::contact {

// How a roller-race contact transmits tangential force.
enum class TractionModel {
  kCoulomb,  // friction.h: mu(|v|) |F_n| with a stick spring (the paper's LS-DYNA law)
  kEhl,      // EhlTraction: lubricant film, mu(slide-to-roll ratio) |F_n|, no stick
};
const char* TractionModelName(TractionModel model);  // "coulomb", "ehl"
bool ParseTractionModel(const std::string& name, TractionModel* model);

struct EhlTraction {
  double limiting_coefficient = 0.08;  // Lambda = tau_L / p, in (0, 1)
  double slide_roll_scale = 0.01;      // s_0 > 0: mu reaches 63 % of Lambda at s = s_0

  // mu(s) for slide-to-roll ratio s (the sign is ignored).
  double Coefficient(double slide_to_roll) const;

  // Tangential force (along the slip direction's axis; opposes `slip_speed`) for one explicit
  // step of a contact carrying `normal_force` (N) with slip speed u_1 - u_2 and entrainment
  // speed u_e (m/s). u_e = 0 with slip counts as pure sliding (mu = Lambda). The force is at
  // most tangential_mass |slip| / (2 dt) (kg, s): the part of the curve steeper than the step
  // resolves (its viscous slope Lambda |F_n| / (s_0 u_e) can exceed m / dt) stops the slip
  // within a step instead of overshooting it, so the update stays stable; the force never
  // does positive work.
  double Force(double normal_force,
               double slip_speed,
               double entrainment_speed,
               double tangential_mass,
               double dt) const;

  bool IsValid(std::string* error) const;
};

}  // namespace spallkit::sim::contact
