// Harris–Jones quasi-static radial load distribution of a cylindrical roller bearing.
//
// What it solves. The inner ring, loaded by a radial force F_r along the load line, moves by
// delta_r towards the rollers at psi = 0 (the load line; psi is measured from it, roller j sits
// at psi_j = psi_0 + 2 pi j / Z). Roller j is squeezed by the total approach
//
//     s_j = delta_r cos(psi_j) - P_d / 2,
//
// where P_d is the DIAMETRAL clearance (Harris's convention, = ISO radial internal clearance, the
// total play): a centred ring leaves a gap of P_d / 2 at every roller. Many dynamic models write
// "c_r" per roller instead; spallkit's inputs always mean P_d (docs/BEARING_MODEL.md).
//
// Contact law. Palmgren's line contact (Harris & Kotzalas): delta = 3.84e-5 Q^0.9 / l^0.8
// (mm, N), i.e. Q = K_c delta^(10/9) with K_c = 8.06e4 l^(8/9) N/mm^(10/9) per contact. It does
// not depend on the radii, so the inner and outer contacts are equal springs in series:
// without speed Q = K_n s^(10/9), K_n = K_c / 2^(10/9).
//
// Speed (Jones, planar). Only the roller's centrifugal force F_c = 1/2 m d_m omega_c^2 enters:
// Q_o = Q_i + F_c with (Q_i/K_c)^0.9 + (Q_o/K_c)^0.9 = s_j when s_j > (F_c/K_c)^0.9, else the
// roller leaves the inner race (Q_i = 0) and rests on the outer race with Q_o = F_c.
//
// Equilibrium of the inner ring: sum_j Q_ij cos(psi_j) = F_r, solved for delta_r by Newton's
// method kept inside a bracket [P_d/2, hi] (the Jacobian vanishes as s_j -> 0+, so plain Newton
// can jump out of the physical branch; a bisection step is taken whenever it would).
//
// Units: SI everywhere (m, N, rad, rad/s); the catalogue constant 8.06e4 N/mm^(10/9) is
// converted once inside.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/bearing.h"

namespace spallkit::sim {

struct LoadDistributionOptions {
  double radial_load_n = 10000.0;        // F_r on the inner ring, >= 0
  double inner_ring_speed_rad_s = 0.0;   // outer ring fixed; only the centrifugal force uses it
  double roller_length_m = 9e-3;         // effective contact length l (no catalogue value; 9 mm)
  double diametral_clearance_m = 20e-6;  // P_d (total play); P_d / 2 gap per roller
  double phase_rad = 0.0;                // psi_0: angle of roller 0 from the load line, |.| <= 2 pi
  double roller_density_kg_m3 = 7850.0;  // for the roller mass in F_c
  // Palmgren coefficient, N/mm^(10/9) per mm^(8/9) of length: K_c = coefficient * l_mm^(8/9).
  double palmgren_coefficient = 8.06e4;
  int max_iterations = 100;
  // Convergence: |sum Q cos psi - F_r| <= force_tolerance * max(F_r, 1 N).
  double force_tolerance = 1e-12;

  // False (with a one-line reason naming the option) when an input is not physical.
  bool IsValid(std::string* error) const;
};

// One roller of the solution.
struct RollerLoad {
  double angle_rad = 0.0;           // psi_j from the load line, wrapped to (-pi, pi]
  double approach_m = 0.0;          // s_j = delta_r cos psi_j - P_d/2 (negative: gap)
  double inner_load_n = 0.0;        // Q_i, roller on inner race
  double outer_load_n = 0.0;        // Q_o = Q_i + F_c
  double inner_deflection_m = 0.0;  // (Q_i / K_c)^0.9
  double outer_deflection_m = 0.0;  // (Q_o / K_c)^0.9
};

enum class LoadDistributionTermination { kConverged, kNoConvergence };
std::string LoadDistributionTerminationToString(LoadDistributionTermination t);

struct LoadDistributionSummary {
  LoadDistributionTermination termination = LoadDistributionTermination::kNoConvergence;
  std::string message = "SolveLoadDistribution was not called.";
  int iterations = 0;

  double delta_r_m = 0.0;                 // inner-ring displacement along the load line
  double q_max_n = 0.0;                   // largest roller–raceway load (outer race, Q_i + F_c)
  double q_max_inner_n = 0.0;             // largest roller–inner-race load
  double load_zone_half_angle_rad = 0.0;  // psi_l = arccos(P_d / (2 delta_r)), pi/2 at P_d = 0
  double load_distribution_factor = 0.0;  // epsilon = 1/2 (1 - P_d / (2 delta_r))
  double centrifugal_force_n = 0.0;       // F_c per roller
  double roller_mass_kg = 0.0;
  double cage_speed_rad_s = 0.0;      // omega_c (pure rolling)
  double contact_stiffness = 0.0;     // K_c, N/m^(10/9), one contact
  double radial_stiffness_n_m = 0.0;  // dF_r / d delta_r at the solution
  double force_residual_n = 0.0;      // sum Q_i cos psi - F_r
  double lateral_force_n = 0.0;       // sum Q_i sin psi (0 by symmetry only when phase is)
  std::vector<RollerLoad> rollers;

  bool IsSolutionUsable() const { return termination == LoadDistributionTermination::kConverged; }
  std::string BriefReport() const;
};

// Solves the load distribution. Throws InputError (one line naming the option) when
// options.IsValid() fails, the bearing geometry is not physical, the clearance is not below the
// roller diameter or the roller is longer than 10 diameters; non-convergence (including a load
// no finite displacement carries) is reported in the summary, never thrown. Every loop is bounded.
void SolveLoadDistribution(const LoadDistributionOptions& options,
                           const BearingGeometry& bearing,
                           LoadDistributionSummary* summary);

// Harris's radial integral J_r(epsilon) = (1/2 pi) int_{-psi_l}^{psi_l}
// [1 - (1 - cos psi)/(2 epsilon)]^(10/9) cos psi d psi, the continuous-roller limit:
// Q_max = F_r / (Z J_r). epsilon in (0, 1]; J_r(0.5) = 0.2448 (Stribeck's 1/J_r = 4.08).
double RadialIntegral(double epsilon);

// Hertz peak pressure of a line contact (Johnson, Contact Mechanics, 4.3), Pa:
// p0 = sqrt(w E* / (pi R)) with w = Q / l, 1/R = 1/r1 + 1/r2 (r2 < 0 for a concave race) and the
// contact modulus 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (steel on steel: 113 GPa).
double HertzLinePressure(double load_n,
                         double length_m,
                         double r1_m,
                         double r2_m,
                         double contact_modulus_pa = 206e9 / (2.0 * (1.0 - 0.3 * 0.3)));

// The stress ISO 76 takes for the static load rating C0 of roller bearings (Pa): above it the
// races deform plastically and the elastic contact law no longer holds.
constexpr double kStaticCapacityStressPa = 4.0e9;

// K_c in SI (N/m^(10/9)) for a roller of effective length l.
double PalmgrenContactStiffness(double roller_length_m, double coefficient = 8.06e4);

// Palmgren's law inverted: the approach (m) of one line contact of stiffness K_c (N/m^(10/9))
// under load Q (N), delta = (Q / K_c)^0.9.
inline double PalmgrenApproach(double load_n, double contact_stiffness) {
  return std::pow(load_n / contact_stiffness, 0.9);
}

}  // namespace spallkit::sim
