// Normal force of a lubricated roller-race line contact: Palmgren's elastic law in series with
// the lubricant film, the normal counterpart of the film's traction (traction.h).
//
// Why: a dry penalty contact's force starts and ends at one point of the approach with a
// slope step (Palmgren's Q = K delta_P^(10/9) rises almost linearly from delta_P = 0). Where a
// healthy bearing's rollers enter and leave the load zone that step strikes the rings at fixed
// places, Z f_c times a second: a noise-free record then carries an outer-race comb that a real
// healthy bearing does not (docs/DIAGNOSIS.md, "Empirical false-alarm rate"). In a lubricated
// contact the film carries the load before the surfaces meet: at light load the rigid-
// isoviscous (hydrodynamic) film of a cylinder on a plane is
//   h = 4.9 eta u_e R L / Q                                   (Martin, 1916)
// (eta the inlet viscosity, u_e the entrainment speed, R the reduced radius, L the length), so
// the load fades as A / h over micrometres of gap instead of stopping at zero gap.
//
// The law: the approach delta of the undeformed profiles is the elastic approach less the film,
//   delta = delta_P(Q) - A / Q,   Q = K delta_P^(10/9),   A = 4.9 eta u_e R L.
// In units of delta_s = (A / K)^(9/19) (where the two terms are equal; about 0.2 um and 40 N for
// the N205EM at 1200 rpm with eta 0.05 Pa s) it is one curve, x = y - y^(-10/9) with
// x = delta / delta_s, y = delta_P / delta_s: Palmgren's law for x >> 1, Martin's film for
// x << -1, smooth in between. The EHL film's own thickness (a fraction of a micrometre, nearly
// independent of the load) only shifts the approach and is left out. Beyond a gap of
// kFilmTaperStart delta_s (the film then carries 4 % of its load at delta_s) the load is tapered
// smoothly to zero at twice that gap, so a contact has a finite reach (FilmReach).
//
// Energy: the elastic part, Q d(delta_P)/d(delta), is conservative with potential
// 9/19 Q delta_P; the rest of Q is the film's and its work is booked with the contact damping.
#pragma once

namespace spallkit::sim::contact {

inline constexpr double kFilmTaperStart = 25.0;  // gap, in delta_s, where the taper starts

// A = 4.9 eta u_e R L (N m): the film carries Q = A / h at gap h (Martin's rigid-isoviscous line
// contact). Zero for a zero entrainment speed or viscosity.
double MartinFilmCoefficient(double viscosity_pa_s,
                             double entrainment_speed,
                             double reduced_radius,
                             double length);

struct FilmContactLoad {
  double load = 0.0;               // Q (N), tapered; 0 beyond the reach
  double stiffness = 0.0;          // dQ / d delta (N/m)
  double conservative_load = 0.0;  // the elastic part Q d(delta_P)/d(delta) (N)
  double potential = 0.0;          // 9/19 Q delta_P (J): the elastic energy
  // d(potential)/dA at this approach: the elastic energy a change of A (the entrainment speed)
  // moves in or out of the contact without work, booked by the caller with the film's work.
  double potential_per_film = 0.0;
};

// What a contact point keeps from one evaluation to the next (all zero at first), so that the
// next one starts near the last: the root y of the last solve (Halley's start) and the expansion
// points of the three powers, each evaluated by a quartic Taylor expansion while its argument
// stays within 0.5 % of the point (a few 1e-12 relative), by std::pow otherwise. A contact's
// approach and entrainment move little per step, so most evaluations need no std::pow at all.
struct FilmContactMemory {
  double root = 0.0;                            // y of the last solve; 0: none
  double root0 = 0.0, root0_power = 0.0;        // y0 and y0^(-10/9)
  double ratio0 = 0.0, scale0 = 0.0;            // (A/K)_0 and delta_s = (A/K)_0^(9/19)
  double elastic0 = 0.0, elastic0_power = 0.0;  // delta_P0 and delta_P0^(10/9)
};

// The load at approach delta (m; < 0: a gap) for film coefficient A >= 0 (N m) and Palmgren
// constant K > 0 (N / m^(10/9)). A = 0: Palmgren's law alone (zero for delta <= 0). With a
// memory (one per contact point) the result agrees with the one without to 1e-9 or better.
FilmContactLoad FilmLineContact(double approach,
                                double film_coefficient,
                                double palmgren_k,
                                FilmContactMemory* memory = nullptr);

// The gap (m, >= 0) beyond which FilmLineContact gives no load: 2 kFilmTaperStart delta_s.
double FilmReach(double film_coefficient, double palmgren_k);

}  // namespace spallkit::sim::contact
