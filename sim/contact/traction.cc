#include "sim/contact/traction.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace spallkit::sim::contact {

const char* TractionModelName(TractionModel model) {
  switch (model) {
    case TractionModel::kCoulomb:
      return "coulomb";
    case TractionModel::kEhl:
      return "ehl";
  }
  return "coulomb";
}

bool ParseTractionModel(const std::string& name, TractionModel* model) {
  for (TractionModel m : {TractionModel::kCoulomb, TractionModel::kEhl})
    if (name == TractionModelName(m)) {
      *model = m;
      return true;
    }
  return false;
}

double EhlTraction::Coefficient(double slide_to_roll) const {
  // -expm1 keeps the viscous slope exact at small s.
  return -limiting_coefficient * std::expm1(-std::abs(slide_to_roll) / slide_roll_scale);
}

namespace {
// Entrainment below this counts as pure sliding for any slip above about 1e-8 m/s (s_0 = 0.01):
// the curve stays continuous for the implicit solve.
constexpr double kMinEntrainment = 1e-6;

// (1 - exp(-x)) / x by its series, for x below kSeriesBound (error < x^4 / 120): spares the
// exponential on a rolling contact's creep.
constexpr double kSeriesBound = 1e-2;
inline double SeriesTail(double x) { return 1.0 - x * (0.5 - x * (1.0 / 6.0 - x / 24.0)); }

// The curve at slip v for a contact of peak force Lambda |F_n| and 1 / (u_e s_0): the force
// along v and its slope dF/dv.
inline void CurveAt(double peak, double inverse_scale, double v, double* force, double* slope) {
  const double x = std::abs(v) * inverse_scale;
  double mu, decay;  // 1 - exp(-x), exp(-x)
  if (x < kSeriesBound) {
    const double tail = SeriesTail(x);
    mu = x * tail;
    decay = 1.0 - x * tail;
  } else {
    mu = -std::expm1(-x);
    decay = 1.0 - mu;
  }
  *force = std::copysign(peak * mu, v);
  *slope = peak * decay * inverse_scale;
}

// The curve's secant F(v) / v at slip v, the same contact's.
inline double SecantAt(double peak, double inverse_scale, double v) {
  const double x = std::abs(v) * inverse_scale;
  const double slope = peak * inverse_scale;
  // mu(x) / x.
  if (x < kSeriesBound) return slope * SeriesTail(x);
  return -slope * std::expm1(-x) / x;
}

double InverseScale(const EhlTraction& law, double entrainment_speed) {
  return 1.0 / (std::max(std::abs(entrainment_speed), kMinEntrainment) * law.slide_roll_scale);
}
}  // namespace

double EhlTraction::Secant(double normal_force, double slip_speed, double entrainment_speed) const {
  return SecantAt(limiting_coefficient * std::abs(normal_force),
                  InverseScale(*this, entrainment_speed),
                  slip_speed);
}

void EhlTraction::CurveForce(double normal_force,
                             double slip_speed,
                             double entrainment_speed,
                             double* force,
                             double* slope) const {
  CurveAt(limiting_coefficient * std::abs(normal_force),
          InverseScale(*this, entrainment_speed),
          slip_speed,
          force,
          slope);
}

namespace {
// Solves a x = b for n <= kMaxImplicitContacts: one or two unknowns in closed form (a roller's
// usual one or two lubricated contacts), more (a partial-length spall's two profiles on both
// races) by Eigen's partial-pivoting LU.
void SolveSmall(int n, const double a[][kMaxImplicitContacts], const double* b, double* x) {
  if (n == 1) {
    x[0] = b[0] / a[0][0];
    return;
  }
  if (n == 2) {
    const double inverse_det = 1.0 / (a[0][0] * a[1][1] - a[0][1] * a[1][0]);
    x[0] = (b[0] * a[1][1] - a[0][1] * b[1]) * inverse_det;
    x[1] = (a[0][0] * b[1] - a[1][0] * b[0]) * inverse_det;
    return;
  }
  using Matrix = Eigen::
      Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxImplicitContacts, kMaxImplicitContacts>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxImplicitContacts, 1>;
  Matrix m(n, n);
  Vector v(n);
  for (int k = 0; k < n; ++k) {
    v(k) = b[k];
    for (int l = 0; l < n; ++l) m(k, l) = a[k][l];
  }
  const Vector solution = m.partialPivLu().solve(v);
  for (int k = 0; k < n; ++k) x[k] = solution(k);
}
}  // namespace

void SolveImplicitTraction(const EhlTraction& law,
                           int n,
                           const double* normal_force,
                           const double* free_slip,
                           const double* entrainment_speed,
                           const double* compliance,
                           double* secant_guess,
                           double* force) {
  constexpr int kN = kMaxImplicitContacts;
  double cap[kN], inverse_scale[kN];
  for (int k = 0; k < n; ++k) {
    cap[k] = normal_force[k] > 0.0 ? law.limiting_coefficient * normal_force[k] : 0.0;
    inverse_scale[k] = InverseScale(law, entrainment_speed[k]);
  }
  // First guess, exact where the secants are the curve's at the slips the step leaves:
  // (D + A) f = -v_free, D = diag(1 / c_k), A the compliance. c_k: the last step's secant (a
  // rolling contact's slip changes little from step to step), else the secant at the free slip.
  {
    // a: the first n x n written below (no zero-fill of the whole matrix: a hot path).
    double a[kN][kN], b[kN] = {};
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < n; ++l) a[k][l] = cap[k] > 0 && cap[l] > 0 ? compliance[k * n + l] : 0.0;
      if (!(cap[k] > 0)) {  // no film load, no force
        a[k][k] = 1.0;
        continue;
      }
      // 1 / c, c the guessed secant (kept per newton of normal force).
      a[k][k] += secant_guess[k] > 0.0 ? 1.0 / (secant_guess[k] * normal_force[k])
                                       : 1.0 / SecantAt(cap[k], inverse_scale[k], free_slip[k]);
      b[k] = -free_slip[k];
    }
    SolveSmall(n, a, b, force);
    for (int k = 0; k < n; ++k) force[k] = std::clamp(force[k], -cap[k], cap[k]);
  }
  // Newton on R_k(f) = f_k + F_k(v_free,k + sum_l A_kl f_l) (F the curve's force along the
  // slip), Jacobian I + diag(F'_k) A, with backtracking on max |R_k| / cap_k, until every
  // |R_k| <= 1e-3 |f_k| + 1e-9 cap_k. The curve saturates, so the linear guess is off where a
  // slip crosses its knee within the step.
  double slope[kN], residual[kN], slip[kN];
  bool converged = false;
  // Sets converged; returns max |R_k| / cap_k when not converged (backtracking's measure).
  auto evaluate = [&](const double* f, double* r, double* dfdv, double* v) {
    converged = true;
    for (int k = 0; k < n; ++k) {
      v[k] = free_slip[k];
      if (!(cap[k] > 0)) {
        r[k] = f[k], dfdv[k] = 0.0;
        continue;
      }
      for (int l = 0; l < n; ++l) v[k] += compliance[k * n + l] * f[l];
      double curve;
      CurveAt(cap[k], inverse_scale[k], v[k], &curve, &dfdv[k]);
      r[k] = f[k] + curve;
      converged = converged && std::abs(r[k]) <= 1e-3 * std::abs(f[k]) + 1e-9 * cap[k];
    }
    double worst = 0.0;
    if (!converged)
      for (int k = 0; k < n; ++k)
        if (cap[k] > 0) worst = std::max(worst, std::abs(r[k]) / cap[k]);
    return worst;
  };
  double worst = evaluate(force, residual, slope, slip);
  for (int it = 0; it < 30 && !converged; ++it) {
    double j[kN][kN], rhs[kN], step[kN];
    for (int k = 0; k < n; ++k) {
      for (int l = 0; l < n; ++l) j[k][l] = (k == l ? 1.0 : 0.0) + slope[k] * compliance[k * n + l];
      rhs[k] = -residual[k];
    }
    SolveSmall(n, j, rhs, step);
    double trial[kN], trial_residual[kN], trial_slope[kN], trial_slip[kN];
    double scale = 1.0, trial_worst = worst;
    for (int tries = 0; tries < 20; ++tries, scale *= 0.5) {
      for (int k = 0; k < n; ++k)
        trial[k] = std::clamp(force[k] + scale * step[k], -cap[k], cap[k]);
      trial_worst = evaluate(trial, trial_residual, trial_slope, trial_slip);
      if (trial_worst < worst || converged) break;
    }
    if (!(trial_worst < worst || converged)) break;  // no progress left in double precision
    for (int k = 0; k < n; ++k) {
      force[k] = trial[k], residual[k] = trial_residual[k];
      slope[k] = trial_slope[k], slip[k] = trial_slip[k];
    }
    worst = trial_worst;
  }
  // The secants per newton at the slips this step leaves (the curve's force F_k = -f_k + R_k is
  // at hand): the next step's guess. At zero slip, the slope.
  for (int k = 0; k < n; ++k) {
    if (!(cap[k] > 0)) {
      secant_guess[k] = 0.0;
      continue;
    }
    const double curve = std::abs(residual[k] - force[k]);
    secant_guess[k] =
        slip[k] != 0.0 ? curve / (std::abs(slip[k]) * normal_force[k]) : slope[k] / normal_force[k];
  }
}

bool EhlTraction::IsValid(std::string* error) const {
  std::ostringstream os;
  if (!(limiting_coefficient > 0.0 && limiting_coefficient < 1.0)) {
    os << "EHL limiting traction coefficient must be in (0, 1), got " << limiting_coefficient;
  } else if (!(slide_roll_scale > 0.0) || !std::isfinite(slide_roll_scale)) {
    os << "EHL slide-to-roll scale s_0 must be finite and > 0, got " << slide_roll_scale;
  } else if (!(inlet_viscosity_pa_s >= 0.0) || !std::isfinite(inlet_viscosity_pa_s)) {
    os << "EHL inlet viscosity must be finite and >= 0, got " << inlet_viscosity_pa_s;
  } else {
    return true;
  }
  if (error) *error = os.str();
  return false;
}

}  // namespace spallkit::sim::contact
