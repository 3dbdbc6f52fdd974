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
  // eta_0 >= 0 (Pa s): the lubricant's viscosity at the contact inlet, for the film's normal
  // load (film_lift.h); 0: the contacts' load is Palmgren's alone. 0.05: an ISO VG 68 mineral
  // oil near 45 C.
  double inlet_viscosity_pa_s = 0.05;

  // mu(s) for slide-to-roll ratio s (the sign is ignored).
  double Coefficient(double slide_to_roll) const;

  // Secant of the traction curve at slip speed v: mu(|v| / u_e) |F_n| / |v| (N s/m); its limit
  // v -> 0 is the viscous slope Lambda |F_n| / (s_0 u_e). An entrainment below 1e-6 m/s counts
  // as 1e-6 m/s: pure sliding (mu = Lambda) for any slip above about 1e-8 m/s.
  double Secant(double normal_force, double slip_speed, double entrainment_speed) const;
  // The curve's force mu(|v| / u_e) |F_n| with the sign of v, and its slope dF/dv >= 0.
  void CurveForce(double normal_force,
                  double slip_speed,
                  double entrainment_speed,
                  double* force,
                  double* slope) const;

  bool IsValid(std::string* error) const;
};

// The tangential forces of n <= kMaxImplicitContacts lubricated contacts that share a body (a
// roller's race contacts) over one central-difference step, implicit in the slip.
//   free_slip[k]: contact k's slip speed u_1 - u_2 at the end of the step without these forces
//                 (every other force of the step applied);
//   compliance:   n x n, row-major: the change of slip k over the step per unit force at
//                 contact l (dt times the contacts' tangential mobility: the shared body's
//                 translation and rotation, plus the counter body's on the diagonal);
//   secant_guess[k]: in, the curve's secant per newton of normal force (s/m) to start from
//                 (the last step's, where the slips change little from step to step; <= 0:
//                 the secant at the free slip); out, the secant at the slip this step leaves;
//   force[k]:     the force on the shared body along contact k's slip axis (opposes the slip).
// The forces solve f_k = -F_k(free_slip_k + sum_l compliance_kl f_l), F_k contact k's curve
// force mu(|v| / u_e) |F_n| sign(v): each force is the curve's at the slip it leaves after the
// step (|f_k| <= Lambda |F_n|, f_k opposing that slip). Newton's method from the linear
// solution with the guessed secants (exact where they are the curve's at the slips left: a
// rolling roller from step to step), to |residual| <= 1e-3 |f_k| + 1e-9 Lambda |F_n|. Why implicit:
// the curve's viscous slope (~1e4-1e5 N s/m for a loaded roller) is far steeper than m / dt, so a
// force from the slip at the step's start has to be capped to stay stable, and a capped force lags
// the other forces by a step: a rolling roller then creeps by about (other forces / m) dt, and the
// film dissipates in proportion to the step. Implicit, the creep is the curve's (force / slope) at
// any step, and the contacts of one roller do not overcorrect each other.
inline constexpr int kMaxImplicitContacts = 4;
void SolveImplicitTraction(const EhlTraction& law,
                           int n,
                           const double* normal_force,
                           const double* free_slip,
                           const double* entrainment_speed,
                           const double* compliance,
                           double* secant_guess,
                           double* force);

}  // namespace spallkit::sim::contact
