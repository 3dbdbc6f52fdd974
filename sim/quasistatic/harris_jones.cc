#include "sim/quasistatic/harris_jones.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/constants.h"
#include "core/error.h"

namespace spallkit::sim {
namespace {

constexpr int kMaxBracketDoublings = 1100;
constexpr double kMaxLengthToDiameter = 10.0;  // needle rollers reach l/d ~ 10

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Inner-race load of one roller squeezed by total approach s (m), with centrifugal force fc:
// solves g(Q) = (Q/K)^0.9 + ((Q+fc)/K)^0.9 - s = 0 for Q >= 0. Returns Q and dQ/ds.
struct RollerSolution {
  double q_inner = 0.0;
  double dq_ds = 0.0;
};

RollerSolution SolveRoller(double s, double k, double fc) {
  RollerSolution r;
  const double s_free = PalmgrenApproach(fc, k);  // approach taken by the outer contact alone
  if (!(s > s_free)) return r;                    // roller off the inner race
  const double q_half = k * std::pow(0.5 * s, 10.0 / 9.0);  // both contacts at s/2
  if (fc == 0.0) {
    r.q_inner = q_half;
    r.dq_ds = (10.0 / 9.0) * q_half / s;
    return r;
  }
  auto g = [&](double q) { return PalmgrenApproach(q, k) + PalmgrenApproach(q + fc, k) - s; };
  auto dg = [&](double q) {
    return 0.9 / k * (std::pow(q / k, -0.1) + std::pow((q + fc) / k, -0.1));
  };
  // g(q_half) >= 0 and g(max(0, q_half - fc)) <= 0: a bracket.
  double lo = std::max(0.0, q_half - fc), hi = q_half;
  double q = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double gq = g(q);
    if (gq > 0)
      hi = q;
    else
      lo = q;
    double next = q - gq / dg(q);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - q) <= 1e-15 * std::max(1.0, q) || hi - lo <= 1e-15 * std::max(1.0, hi)) {
      q = next;
      break;
    }
    q = next;
  }
  r.q_inner = q;
  r.dq_ds = q > 0 ? 1.0 / dg(q) : 0.0;
  return r;
}

}  // namespace

std::string LoadDistributionTerminationToString(LoadDistributionTermination t) {
  switch (t) {
    case LoadDistributionTermination::kConverged:
      return "CONVERGED";
    case LoadDistributionTermination::kNoConvergence:
      return "NO_CONVERGENCE";
  }
  return "UNKNOWN";
}

bool LoadDistributionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& msg) {
    if (error) *error = msg;
    return false;
  };
  if (!(radial_load_n >= 0) || !std::isfinite(radial_load_n))
    return fail("radial load must be >= 0 N (got " + Num(radial_load_n) + ")");
  if (!std::isfinite(inner_ring_speed_rad_s)) return fail("inner ring speed must be finite");
  if (!(roller_length_m > 0) || !std::isfinite(roller_length_m))
    return fail("roller length must be > 0 (got " + Num(roller_length_m * 1e3) + " mm)");
  if (!(diametral_clearance_m >= 0) || !std::isfinite(diametral_clearance_m))
    return fail("diametral clearance must be >= 0 (got " + Num(diametral_clearance_m * 1e3) +
                " mm; preload is not modelled)");
  // Beyond one turn either way the roller angles lose their spacing in rounding.
  if (!(std::abs(phase_rad) <= 2.0 * kPi))
    return fail("roller phase must be within +-360 deg (got " + Num(phase_rad * 180.0 / kPi) +
                " deg)");
  if (!(roller_density_kg_m3 >= 0) || !std::isfinite(roller_density_kg_m3))
    return fail("roller density must be >= 0 kg/m^3");
  if (!(palmgren_coefficient > 0)) return fail("Palmgren coefficient must be > 0");
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (!(force_tolerance > 0)) return fail("force_tolerance must be > 0");
  return true;
}

double PalmgrenContactStiffness(double roller_length_m, double coefficient) {
  // K_c [N/mm^(10/9)] = coefficient * l_mm^(8/9); delta_mm = 1e3 delta_m.
  const double k_mm = coefficient * std::pow(roller_length_m * 1e3, 8.0 / 9.0);
  return k_mm * std::pow(1e3, 10.0 / 9.0);
}

double HertzLinePressure(
    double load_n, double length_m, double r1_m, double r2_m, double contact_modulus_pa) {
  if (!(load_n > 0)) return 0.0;
  const double r_eff = 1.0 / (1.0 / r1_m + 1.0 / r2_m);
  return std::sqrt(load_n / length_m * contact_modulus_pa / (kPi * r_eff));
}

double RadialIntegral(double epsilon) {
  if (!(epsilon > 0) || !(epsilon <= 1.0))
    throw InputError("load distribution factor epsilon must be in (0, 1] (got " + Num(epsilon) +
                     ")");
  const double psi_l = std::acos(std::clamp(1.0 - 2.0 * epsilon, -1.0, 1.0));
  auto f = [&](double psi) {
    const double b = 1.0 - (1.0 - std::cos(psi)) / (2.0 * epsilon);
    return b > 0 ? std::pow(b, 10.0 / 9.0) * std::cos(psi) : 0.0;
  };
  // Composite Simpson on [0, psi_l] (even integrand). The integrand is C^1 with a weak
  // (x^(1/9)) singularity of its derivative at psi_l; 2^16 panels give ~1e-9 relative.
  const int n = 1 << 16;
  const double h = psi_l / n;
  double sum = f(0.0) + f(psi_l);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(i * h);
  const double half = sum * h / 3.0;
  return 2.0 * half / (2.0 * kPi);
}

void SolveLoadDistribution(const LoadDistributionOptions& options,
                           const BearingGeometry& bearing,
                           LoadDistributionSummary* summary) {
  SPALLKIT_CHECK(summary != nullptr, "summary must not be null");
  std::string error;
  if (!options.IsValid(&error)) throw InputError(error);
  bearing.Validate();
  // Limits of the model against the bearing: a clearance of a roller diameter or a roller many
  // diameters long is outside what the line-contact law describes (and would stall the solver).
  if (!(options.diametral_clearance_m < bearing.element_diameter_m))
    throw InputError("diametral clearance must be below the roller diameter (" +
                     Num(bearing.element_diameter_m * 1e3) + " mm; got " +
                     Num(options.diametral_clearance_m * 1e3) + " mm)");
  if (!(options.roller_length_m <= kMaxLengthToDiameter * bearing.element_diameter_m))
    throw InputError("roller length must be at most " + Num(kMaxLengthToDiameter) +
                     " roller diameters (" +
                     Num(kMaxLengthToDiameter * bearing.element_diameter_m * 1e3) + " mm; got " +
                     Num(options.roller_length_m * 1e3) + " mm)");

  LoadDistributionSummary& s = *summary;
  s = LoadDistributionSummary();
  const int z = bearing.num_elements;
  const double d = bearing.element_diameter_m;
  const double dm = bearing.pitch_diameter_m;
  const double gamma = d * std::cos(bearing.contact_angle_rad) / dm;
  const double half_pd = 0.5 * options.diametral_clearance_m;
  const double k = PalmgrenContactStiffness(options.roller_length_m, options.palmgren_coefficient);
  const double kn = k / std::pow(2.0, 10.0 / 9.0);

  s.contact_stiffness = k;
  s.cage_speed_rad_s = 0.5 * options.inner_ring_speed_rad_s * (1.0 - gamma);
  s.roller_mass_kg = options.roller_density_kg_m3 * kPi * 0.25 * d * d * options.roller_length_m;
  s.centrifugal_force_n = 0.5 * s.roller_mass_kg * dm * s.cage_speed_rad_s * s.cage_speed_rad_s;
  const double fc = s.centrifugal_force_n;

  std::vector<double> psi(z), c(z);
  for (int j = 0; j < z; ++j) {
    psi[j] = std::remainder(options.phase_rad + 2.0 * kPi * j / z, 2.0 * kPi);
    c[j] = std::cos(psi[j]);
  }

  // Residual R(delta_r) = sum Q_i cos psi - F_r and its derivative; R is non-decreasing.
  auto residual = [&](double delta, double* dr) {
    double r = -options.radial_load_n, deriv = 0.0;
    for (int j = 0; j < z; ++j) {
      if (c[j] <= 0) continue;  // rollers on the unloaded half only see F_c
      const RollerSolution rs = SolveRoller(delta * c[j] - half_pd, k, fc);
      r += rs.q_inner * c[j];
      deriv += rs.dq_ds * c[j] * c[j];
    }
    if (dr) *dr = deriv;
    return r;
  };

  const double f_tol = options.force_tolerance * std::max(options.radial_load_n, 1.0);
  double delta = half_pd;
  if (options.radial_load_n > 0) {
    // Bracket: R(P_d/2) = -F_r < 0 (no roller is squeezed); grow hi until R(hi) >= 0.
    double lo = half_pd;
    // The step grows from at least one ulp of P_d/2 (a tiny load on a large clearance would
    // otherwise never move hi) and doubles a bounded number of times: R grows like
    // delta^(10/9) once a roller is squeezed, so 2^1100 covers every finite load.
    double step = std::max(std::pow(options.radial_load_n / (0.25 * z * kn), 0.9),
                           4.0 * std::numeric_limits<double>::epsilon() * half_pd);
    double hi = half_pd + step;
    int doublings = 0;
    for (; residual(hi, nullptr) < 0 && doublings < kMaxBracketDoublings; ++doublings) {
      step *= 2.0;
      hi = half_pd + step;
      if (!std::isfinite(hi)) break;
    }
    if (!(residual(hi, nullptr) >= 0)) {
      s.message = "No bracket for the ring displacement: sum Q cos psi stays below F_r = " +
                  Num(options.radial_load_n) + " N up to delta_r = " + Num(hi) + " m.";
      s.termination = LoadDistributionTermination::kNoConvergence;
      s.delta_r_m = half_pd;
      return;
    }
    delta = hi;  // the Stribeck-type start, from the side where R > 0 and the Jacobian is sound
    bool converged = false;
    for (int it = 1; it <= options.max_iterations; ++it) {
      s.iterations = it;
      double dr = 0.0;
      const double r = residual(delta, &dr);
      if (std::abs(r) <= f_tol) {
        converged = true;
        break;
      }
      if (r > 0)
        hi = delta;
      else
        lo = delta;
      double next = dr > 0 ? delta - r / dr : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (hi - lo <= 1e-15 * hi) {
        delta = next;
        converged = std::abs(residual(delta, nullptr)) <= 1e3 * f_tol;
        break;
      }
      delta = next;
    }
    s.termination = converged ? LoadDistributionTermination::kConverged
                              : LoadDistributionTermination::kNoConvergence;
  } else {
    s.termination = LoadDistributionTermination::kConverged;
  }

  s.delta_r_m = delta;
  double dr = 0.0;
  s.force_residual_n = residual(delta, &dr);
  s.radial_stiffness_n_m = dr;
  s.rollers.resize(z);
  for (int j = 0; j < z; ++j) {
    RollerLoad& rl = s.rollers[j];
    rl.angle_rad = psi[j];
    rl.approach_m = delta * c[j] - half_pd;
    const RollerSolution rs = SolveRoller(rl.approach_m, k, fc);
    rl.inner_load_n = rs.q_inner;
    rl.outer_load_n = rs.q_inner + fc;
    rl.inner_deflection_m = PalmgrenApproach(rl.inner_load_n, k);
    rl.outer_deflection_m = PalmgrenApproach(rl.outer_load_n, k);
    s.q_max_n = std::max(s.q_max_n, rl.outer_load_n);
    s.q_max_inner_n = std::max(s.q_max_inner_n, rl.inner_load_n);
    s.lateral_force_n += rl.inner_load_n * std::sin(psi[j]);
  }
  if (delta > 0) {
    const double ratio = std::clamp(half_pd / delta, 0.0, 1.0);
    s.load_zone_half_angle_rad = std::acos(ratio);
    s.load_distribution_factor = 0.5 * (1.0 - ratio);
  }
  if (s.IsSolutionUsable()) {
    s.message = "Converged: |sum Q cos psi - F_r| = " + Num(std::abs(s.force_residual_n)) + " N.";
  } else {
    s.message = "No convergence in " + std::to_string(s.iterations) + " iterations (residual " +
                Num(s.force_residual_n) + " N).";
  }
}

std::string LoadDistributionSummary::BriefReport() const {
  std::ostringstream os;
  os << "Harris-Jones: " << LoadDistributionTerminationToString(termination) << ", " << iterations
     << " iterations, delta_r " << delta_r_m * 1e6 << " um, Q_max " << q_max_n << " N, load zone +-"
     << load_zone_half_angle_rad * 180.0 / kPi << " deg, F_c " << centrifugal_force_n << " N";
  return os.str();
}

}  // namespace spallkit::sim
