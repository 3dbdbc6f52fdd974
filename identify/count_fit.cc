#include "identify/count_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "core/constants.h"
#include "core/error.h"
#include "identify/chi_square.h"

namespace spallkit::identify {
namespace {

// Gauss-Hermite rule for E[f(X)], X ~ N(0, 1), 3 nodes (exact for polynomials to degree 5; the
// smear is a small correction to a hump ~100 deg wide).
constexpr double kGhNode[3] = {-1.7320508075688772, 0.0, 1.7320508075688772};
constexpr double kGhWeight[3] = {1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0};

// The hump at x smoothed by a Gaussian of std `smear` (which also stands for the bin width: its
// lower bound is 0.3 bin widths, the std of a uniform bin being 0.29).
// With `project`, `sensor` is the sensor's direction from the load line: an impact along the
// roller's radius at psi reaches it with cos(psi - sensor), its squared envelope with cos^2 (a
// horizontal sensor, sensor = 90 deg, sees no impact on the load line and most at the flanks).
template <typename T>
T Hump(const T& x,
       const T& p,
       const T& edge,
       const T& smear,
       const T& half,
       double /*bin_rad*/,
       double sensor,
       bool project) {
  using std::cos;
  using std::exp;
  using std::log;
  const T cl = cos(half);
  T sum(0.0);
  for (int q = 0; q < 3; ++q) {
    const T psi = x + smear * kGhNode[q];
    const T c = cos(psi);
    if (c > cl) {
      const T log_q = T(10.0 / 9.0) * log((c - cl) / (T(1.0) - cl));  // ln of relative load
      const T projection = project ? cos(psi - sensor) : T(1.0);
      sum += kGhWeight[q] * exp(p * log_q) * (T(1.0) + edge * (T(1.0) - exp(log_q))) * projection *
             projection;
    }
  }
  return sum;
}

struct HumpResidual {
  const CageAverage* avg;
  std::vector<int> slots;
  int z;
  double sensor;
  bool project;

  template <typename T>
  bool operator()(T const* const* params, T* residuals) const {
    const T* shape = params[0];
    const T theta0 = params[1][0];
    const T floor = params[2][0];
    const T* amp = params[3];
    const int n = avg->bins();
    const double bin = 2.0 * kPi / n;
    for (int i = 0; i < n; ++i) {
      T model = floor;
      for (size_t k = 0; k < slots.size(); ++k) {
        const T x = T(avg->BinCenterRad(i) + 2.0 * kPi * slots[k] / z) - theta0;
        model += amp[k] * Hump(x, shape[0], shape[3], shape[1], shape[2], bin, sensor, project);
      }
      residuals[i] = (T(avg->mean[i]) - model) / avg->sigma[i];
    }
    return true;
  }
};

constexpr double kMinSmear = 0.01;
constexpr double kMaxEdgeGain = 20.0;
constexpr double kMinHalfAngle = 20.0 * kPi / 180.0, kMaxHalfAngle = 100.0 * kPi / 180.0;

int ParameterCount(int k, bool half_fixed) { return k == 0 ? 1 : 1 + k + 1 + (half_fixed ? 3 : 4); }

double Chi2(const CageAverage& avg, const std::vector<double>& model) {
  return ChiSquare(avg.mean, avg.sigma, model);
}

std::vector<double> Model(const CageAverage& avg, const HumpFit& f, int z) {
  std::vector<double> m(avg.bins(), f.floor);
  for (int i = 0; i < avg.bins(); ++i)
    for (size_t k = 0; k < f.slots.size(); ++k) m[i] += RollerHump(avg, f, z, k, i);
  return m;
}

// Solves the symmetric positive (semi)definite system a x = b in place by Cholesky; false when
// it is singular.
bool SolveSymmetric(int m, std::vector<double>* a_io, std::vector<double>* b_io) {
  std::vector<double>& a = *a_io;
  std::vector<double>& b = *b_io;
  const double scale = *std::max_element(a.begin(), a.end());
  for (int j = 0; j < m; ++j) {
    double d = a[j * m + j];
    for (int p = 0; p < j; ++p) d -= a[j * m + p] * a[j * m + p];
    if (!(d > 1e-13 * scale)) return false;
    d = std::sqrt(d);
    a[j * m + j] = d;
    for (int i = j + 1; i < m; ++i) {
      double v = a[i * m + j];
      for (int p = 0; p < j; ++p) v -= a[i * m + p] * a[j * m + p];
      a[i * m + j] = v / d;
    }
  }
  for (int i = 0; i < m; ++i) {  // L y = b
    double v = b[i];
    for (int p = 0; p < i; ++p) v -= a[i * m + p] * b[p];
    b[i] = v / a[i * m + i];
  }
  for (int i = m - 1; i >= 0; --i) {  // L^T x = y
    double v = b[i];
    for (int p = i + 1; p < m; ++p) v -= a[p * m + i] * b[p];
    b[i] = v / a[i * m + i];
  }
  return std::all_of(b.begin(), b.end(), [](double v) { return std::isfinite(v); });
}

// Weighted linear least squares in (b, a) for fixed columns; false if an amplitude is negative.
bool LinearFit(const CageAverage& avg,
               const std::vector<const std::vector<double>*>& columns,
               double* floor,
               std::vector<double>* amp,
               double* chi2) {
  const int n = avg.bins(), k = static_cast<int>(columns.size());
  // Normal equations by hand: (k+1) is small, and Eigen's GEMM path is not needed.
  const int m = k + 1;
  std::vector<double> ata(m * m, 0.0), x(m, 0.0);
  std::vector<double> row(k + 1);
  for (int i = 0; i < n; ++i) {
    const double w = 1.0 / (avg.sigma[i] * avg.sigma[i]);
    row[0] = 1.0;
    for (int j = 0; j < k; ++j) row[j + 1] = (*columns[j])[i];
    for (int r = 0; r <= k; ++r) {
      x[r] += w * row[r] * avg.mean[i];
      for (int c = 0; c < m; ++c) ata[r * m + c] += w * row[r] * row[c];
    }
  }
  if (!SolveSymmetric(m, &ata, &x)) return false;
  for (int j = 0; j < k; ++j)
    if (x[j + 1] < 0) return false;
  *floor = x[0];
  amp->assign(x.begin() + 1, x.end());
  double c2 = 0.0;
  for (int i = 0; i < n; ++i) {
    double model = x[0];
    for (int j = 0; j < k; ++j) model += x[j + 1] * (*columns[j])[i];
    const double r = (avg.mean[i] - model) / avg.sigma[i];
    c2 += r * r;
  }
  *chi2 = c2;
  return true;
}

// Ceres refinement of all parameters of one configuration, from `start`.
HumpFit Refine(const CageAverage& avg, int z, const HumpFit& start, const CountFitOptions& o) {
  HumpFit f = start;
  if (f.slots.empty()) return f;
  const int k = static_cast<int>(f.slots.size());
  double shape[4] = {
      f.shape.exponent, f.shape.smear_rad, f.shape.half_angle_rad, f.shape.edge_gain};
  double theta0 = f.theta0_rad, floor = f.floor;
  std::vector<double> amp = f.amplitudes;
  for (double& a : amp) a = std::max(a, 1e-12);

  auto* cost = new ceres::DynamicAutoDiffCostFunction<HumpResidual, 4>(
      new HumpResidual{&avg, f.slots, z, f.shape.sensor_angle_rad, f.shape.sensor_projection});
  cost->AddParameterBlock(4);
  cost->AddParameterBlock(1);
  cost->AddParameterBlock(1);
  cost->AddParameterBlock(k);
  cost->SetNumResiduals(avg.bins());
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, {shape, &theta0, &floor, amp.data()});
  problem.SetParameterLowerBound(shape, 0, kHumpMinExponent);
  problem.SetParameterUpperBound(shape, 0, kHumpMaxExponent);
  problem.SetParameterLowerBound(shape, 1, std::max(kMinSmear, 0.3 * 2.0 * kPi / avg.bins()));
  problem.SetParameterUpperBound(shape, 1, std::max(kMinSmear * 1.01, o.max_smear_rad));
  if (f.shape.half_angle_fixed) {
    problem.SetManifold(shape, new ceres::SubsetManifold(4, {2}));
  } else {
    problem.SetParameterLowerBound(shape, 2, kMinHalfAngle);
    problem.SetParameterUpperBound(shape, 2, kMaxHalfAngle);
  }
  problem.SetParameterLowerBound(shape, 3, 0.0);
  problem.SetParameterUpperBound(shape, 3, kMaxEdgeGain);
  problem.SetParameterLowerBound(&floor, 0, 0.0);
  for (int j = 0; j < k; ++j) problem.SetParameterLowerBound(amp.data(), j, 0.0);
  ceres::Solver::Options so;
  so.max_num_iterations = o.max_iterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.logging_type = ceres::SILENT;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);

  f.shape.exponent = shape[0];
  f.shape.smear_rad = shape[1];
  f.shape.half_angle_rad = shape[2];
  f.shape.edge_gain = shape[3];
  f.theta0_rad = std::remainder(theta0, 2.0 * kPi);
  f.floor = floor;
  f.amplitudes = amp;
  f.model = Model(avg, f, z);
  f.chi2 = Chi2(avg, f.model);
  f.refined = true;
  return f.chi2 <= start.chi2 ? f : start;
}

// v[(j, m), q] = per_line[(m, q)] e^{-i j phi_q} for k rollers, harmonics j = 1..nj and `lines`
// sideband orders m, per_line[(m, q)] at m_index * k + q: feature B's basis, the rollers'
// cage-angle terms of each line times their spin phase at each harmonic.
std::vector<std::complex<double>> SpinPhaseBasis(const std::vector<std::complex<double>>& per_line,
                                                 const std::vector<double>& phase,
                                                 int k,
                                                 int nj,
                                                 int lines) {
  SPALLKIT_CHECK(
      static_cast<int>(phase.size()) >= k && per_line.size() >= static_cast<size_t>(lines) * k,
      "sideband basis: " << phase.size() << " spin phases and " << per_line.size()
                         << " line terms for " << k << " rollers");
  std::vector<std::complex<double>> v(static_cast<size_t>(nj) * lines * k);
  for (int q = 0; q < k; ++q) {  // e^{-i j phi} by powers: one sine pair per roller
    const std::complex<double> e1 = std::polar(1.0, -phase[q]);
    std::complex<double> e = e1;
    for (int j = 1; j <= nj; ++j, e *= e1)
      for (int m = 0; m < lines; ++m)
        v[(static_cast<size_t>(j - 1) * lines + m) * k + q] = per_line[m * k + q] * e;
  }
  return v;
}

// Feature B's chi2 of a configuration for given spin phases of rollers 2..K (roller 1's is in
// p_j) and hump offset delta: S_jm = p_j sum_k a_k e^{-i j phi_k} M_m e^{i m (2 pi s_k / Z -
// theta_0 - delta)}, with p_j (complex, per harmonic) and a_k (real, >= 0, shared by the
// harmonics) by alternating least squares from equal strengths (complex lines: each
// residual counts with variance noise_power / 2 per real component).
double SidebandChi2At(const SpinSidebands& sb,
                      const HumpFit& f,
                      const std::vector<std::complex<double>>& em,
                      const std::vector<double>& phase) {
  const int k = static_cast<int>(f.slots.size());
  const int lines = 2 * sb.orders + 1;
  const int nj = sb.harmonics;
  // Basis v[(j, m), q] = em[(m, q)] e^{-i j phi_q}, em = M_m e^{i m (2 pi s_q / Z - theta_0 -
  // delta)}.
  const std::vector<std::complex<double>> v = SpinPhaseBasis(em, phase, k, nj, lines);
  std::vector<double> a(k,
                        1.0);  // equal strengths to start: feature A's are poor when humps overlap
  std::vector<std::complex<double>> p(nj, 0.0);
  auto line = [&](int j, int m) { return static_cast<size_t>(j - 1) * lines + m + sb.orders; };
  auto solve_p = [&]() {
    for (int j = 1; j <= nj; ++j) {
      std::complex<double> num = 0.0;
      double den = 0.0;
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        std::complex<double> u = 0.0;
        for (int q = 0; q < k; ++q) u += a[q] * v[line(j, m) * k + q];
        const double wt = 1.0 / sb.noise_power[sb.Index(j, m)];
        num += wt * std::conj(u) * sb.value[sb.Index(j, m)];
        den += wt * std::norm(u);
      }
      p[j - 1] = den > 0 ? num / den : 0.0;
    }
  };
  constexpr int kAlternations = 5;
  solve_p();
  for (int it = 0; it < kAlternations && k > 1; ++it) {
    std::vector<double> ata(static_cast<size_t>(k) * k, 0.0), atb(k, 0.0);
    for (int j = 1; j <= nj; ++j)
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        const double wt = 1.0 / sb.noise_power[sb.Index(j, m)];
        for (int r = 0; r < k; ++r) {
          const std::complex<double> br = p[j - 1] * v[line(j, m) * k + r];
          atb[r] += wt * std::real(std::conj(br) * sb.value[sb.Index(j, m)]);
          for (int c = 0; c < k; ++c)
            ata[r * k + c] += wt * std::real(std::conj(br) * p[j - 1] * v[line(j, m) * k + c]);
        }
      }
    if (!SolveSymmetric(k, &ata, &atb)) break;
    const double amax = *std::max_element(atb.begin(), atb.end());
    if (!(amax > 0)) break;
    for (int q = 0; q < k; ++q) a[q] = std::max(atb[q], 0.0) / amax;
    solve_p();
  }
  double chi2 = 0.0;
  for (int j = 1; j <= nj; ++j)
    for (int m = -sb.orders; m <= sb.orders; ++m) {
      std::complex<double> u = 0.0;
      for (int q = 0; q < k; ++q) u += a[q] * v[line(j, m) * k + q];
      chi2 += std::norm(sb.value[sb.Index(j, m)] - p[j - 1] * u) /
              (0.5 * sb.noise_power[sb.Index(j, m)]);
    }
  return chi2;
}

// Feature B's chi2 with a second cage-angle pattern per roller: S_jm = sum_k a_k e^{-i j phi_k}
// e^{i m (2 pi s_k / Z - theta_0 - delta)} (p_j M_m + q_j N_m), M_m the hump's coefficients
// (real, symmetric in m) and N_m a second real pattern symmetric in m, fitted and shared by the
// rollers and the harmonics, with p_j, q_j complex per harmonic and a_k real, by alternating
// least squares (steer[(m + M) k + q] = e^{i m (...)} of roller q; mm[|m|] = M_m).
double SidebandChi2AtTwoPatterns(const SpinSidebands& sb,
                                 int k,
                                 const std::vector<std::complex<double>>& steer,
                                 const std::vector<double>& mm,
                                 const std::vector<double>& phase) {
  const int orders = sb.orders, lines = 2 * orders + 1, nj = sb.harmonics;
  auto idx = [&](int j, int m) { return static_cast<size_t>(j - 1) * lines + m + orders; };
  // v[(j, m), q] = e^{i m (...)} e^{-i j phi_q}.
  const std::vector<std::complex<double>> v = SpinPhaseBasis(steer, phase, k, nj, lines);
  // Second pattern: start from m^2 M_m with its M component removed (orthogonal to M).
  std::vector<double> n_pat(orders + 1);
  {
    double mm2 = 0.0, mn = 0.0;
    for (int m = 0; m <= orders; ++m) {
      n_pat[m] = (m * m + 1.0) * mm[m];
      mm2 += mm[m] * mm[m];
      mn += mm[m] * n_pat[m];
    }
    double norm = 0.0;
    for (int m = 0; m <= orders; ++m) {
      n_pat[m] -= (mm2 > 0 ? mn / mm2 : 0.0) * mm[m];
      norm += n_pat[m] * n_pat[m];
    }
    if (!(norm > 0)) return std::numeric_limits<double>::infinity();
    for (double& x : n_pat) x /= std::sqrt(norm);
  }
  std::vector<double> a(k, 1.0);
  std::vector<std::complex<double>> p(nj, 0.0), qc(nj, 0.0), u(static_cast<size_t>(nj) * lines);
  auto weight = [&](int j, int m) { return 1.0 / (0.5 * sb.noise_power[sb.Index(j, m)]); };
  auto update_u = [&]() {
    for (int j = 1; j <= nj; ++j)
      for (int m = -orders; m <= orders; ++m) {
        std::complex<double> x = 0.0;
        for (int q = 0; q < k; ++q) x += a[q] * v[idx(j, m) * k + q];
        u[idx(j, m)] = x;
      }
  };
  auto solve_pq = [&]() {  // per harmonic, 2 x 2 complex normal equations
    for (int j = 1; j <= nj; ++j) {
      std::complex<double> a11 = 0.0, a12 = 0.0, a22 = 0.0, b1 = 0.0, b2 = 0.0;
      for (int m = -orders; m <= orders; ++m) {
        const double w = weight(j, m);
        const std::complex<double> c1 = u[idx(j, m)] * mm[std::abs(m)];
        const std::complex<double> c2 = u[idx(j, m)] * n_pat[std::abs(m)];
        const std::complex<double> y = sb.value[sb.Index(j, m)];
        a11 += w * std::norm(c1);
        a22 += w * std::norm(c2);
        a12 += w * std::conj(c1) * c2;
        b1 += w * std::conj(c1) * y;
        b2 += w * std::conj(c2) * y;
      }
      const std::complex<double> det = a11 * a22 - a12 * std::conj(a12);
      if (std::abs(det) > 1e-12 * std::abs(a11 * a22)) {
        p[j - 1] = (a22 * b1 - a12 * b2) / det;
        qc[j - 1] = (a11 * b2 - std::conj(a12) * b1) / det;
      } else {
        p[j - 1] = std::abs(a11) > 0 ? b1 / a11 : 0.0;
        qc[j - 1] = 0.0;
      }
    }
  };
  auto solve_n = [&]() {  // per |m|, given p, q
    double norm = 0.0;
    for (int mu = 0; mu <= orders; ++mu) {
      double num = 0.0, den = 0.0;
      for (int sign : {-1, 1}) {
        if (mu == 0 && sign > 0) continue;
        const int m = sign * mu;
        for (int j = 1; j <= nj; ++j) {
          const double w = weight(j, m);
          const std::complex<double> c2 = qc[j - 1] * u[idx(j, m)];
          const std::complex<double> r =
              sb.value[sb.Index(j, m)] - p[j - 1] * u[idx(j, m)] * mm[mu];
          num += w * std::real(std::conj(c2) * r);
          den += w * std::norm(c2);
        }
      }
      n_pat[mu] = den > 0 ? num / den : 0.0;
      norm += n_pat[mu] * n_pat[mu];
    }
    if (norm > 0)
      for (double& x : n_pat) x /= std::sqrt(norm);
  };
  auto solve_a = [&]() {  // K real strengths, given the per-roller pattern
    std::vector<double> ata(static_cast<size_t>(k) * k, 0.0), atb(k, 0.0);
    for (int j = 1; j <= nj; ++j)
      for (int m = -orders; m <= orders; ++m) {
        const double w = weight(j, m);
        const std::complex<double> r = p[j - 1] * mm[std::abs(m)] + qc[j - 1] * n_pat[std::abs(m)];
        for (int rr = 0; rr < k; ++rr) {
          const std::complex<double> br = r * v[idx(j, m) * k + rr];
          atb[rr] += w * std::real(std::conj(br) * sb.value[sb.Index(j, m)]);
          for (int c = 0; c < k; ++c)
            ata[rr * k + c] += w * std::real(std::conj(br) * r * v[idx(j, m) * k + c]);
        }
      }
    if (!SolveSymmetric(k, &ata, &atb)) return;
    const double amax = *std::max_element(atb.begin(), atb.end());
    if (!(amax > 0)) return;
    for (int q = 0; q < k; ++q) a[q] = std::max(atb[q], 0.0) / amax;
  };
  constexpr int kAlternations = 6;
  update_u();
  for (int it = 0; it < kAlternations; ++it) {
    solve_pq();
    solve_n();
    solve_pq();
    if (k > 1) {
      solve_a();
      update_u();
    }
  }
  solve_pq();
  double chi2 = 0.0;
  for (int j = 1; j <= nj; ++j)
    for (int m = -orders; m <= orders; ++m) {
      const std::complex<double> model =
          u[idx(j, m)] * (p[j - 1] * mm[std::abs(m)] + qc[j - 1] * n_pat[std::abs(m)]);
      chi2 += std::norm(sb.value[sb.Index(j, m)] - model) * weight(j, m);
    }
  return chi2;
}

// Feature B's chi2 of a configuration for given spin phases of rollers 2..K (roller 1's is in
// p_j): S_jm = p_j G^(j mod 2)_m sum_k a_k e^{-i j phi_k} e^{i m 2 pi s_k / Z}, with p_j
// (complex, per harmonic), the cage-angle patterns G^0, G^1 (complex per order m, shared by the
// rollers, one for the even and one for the odd spin harmonics) and a_k (real, >= 0, shared by
// the harmonics) by alternating least squares from equal strengths and the start patterns
// (complex lines: each residual counts with variance noise_power / 2 per real component).
// Why two patterns: a roller strikes the outer race at spin phase phi and the inner race half a
// turn later, so its odd harmonics carry the difference of the two races' impacts and the even
// ones their sum; the two reach the sensor with different weights over the cage angle (on the
// lumped model's horizontal channel the odd and even patterns of one roller differ by a median
// 0.47 in 1 - |cos| against 0.01 within a parity, docs/IDENTIFY.md), which one shared pattern
// can only fit with a second, phantom roller.
double SidebandChi2AtPerParity(const SpinSidebands& sb,
                               const std::vector<int>& slots,
                               int z,
                               const std::vector<std::complex<double>>& start_pattern,
                               const std::vector<double>& phase) {
  const int k = static_cast<int>(slots.size());
  const int lines = 2 * sb.orders + 1;
  const int nj = sb.harmonics;
  auto line = [&](int j, int m) { return static_cast<size_t>(j - 1) * lines + m + sb.orders; };
  // Basis v[(j, m), q] = e^{-i j phi_q} e^{i m 2 pi s_q / Z}.
  std::vector<std::complex<double>> v(static_cast<size_t>(nj) * lines * k);
  for (int q = 0; q < k; ++q) {
    const std::complex<double> e1 = std::polar(1.0, -phase[q]);
    std::complex<double> e = e1;
    for (int j = 1; j <= nj; ++j, e *= e1)
      for (int m = -sb.orders; m <= sb.orders; ++m)
        v[line(j, m) * k + q] = e * std::polar(1.0, m * 2.0 * kPi * slots[q] / z);
  }
  std::vector<std::complex<double>> g[2] = {start_pattern, start_pattern};
  // Equal strengths to start: feature A's are poor when humps overlap.
  std::vector<double> a(k, 1.0);
  std::vector<std::complex<double>> p(nj, 0.0);
  // The rollers' sum u(j, m) = sum_q a_q v[(j, m), q], kept for the current strengths.
  std::vector<std::complex<double>> u_sum(static_cast<size_t>(nj) * lines);
  auto update_u = [&]() {
    for (int j = 1; j <= nj; ++j)
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        std::complex<double> u = 0.0;
        for (int q = 0; q < k; ++q) u += a[q] * v[line(j, m) * k + q];
        u_sum[line(j, m)] = u;
      }
  };
  auto u_of = [&](int j, int m) { return u_sum[line(j, m)]; };
  auto weight = [&](int j, int m) { return 1.0 / sb.noise_power[sb.Index(j, m)]; };
  auto solve_p = [&]() {
    for (int j = 1; j <= nj; ++j) {
      std::complex<double> num = 0.0;
      double den = 0.0;
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        const std::complex<double> u = g[j % 2][m + sb.orders] * u_of(j, m);
        num += weight(j, m) * std::conj(u) * sb.value[sb.Index(j, m)];
        den += weight(j, m) * std::norm(u);
      }
      p[j - 1] = den > 0 ? num / den : 0.0;
    }
  };
  auto solve_patterns = [&]() {  // each normalised: its scale is p_j's
    for (int par = 0; par < 2; ++par) {
      double norm = 0.0;
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        std::complex<double> num = 0.0;
        double den = 0.0;
        for (int j = 2 - par; j <= nj; j += 2) {
          const std::complex<double> u = p[j - 1] * u_of(j, m);
          num += weight(j, m) * std::conj(u) * sb.value[sb.Index(j, m)];
          den += weight(j, m) * std::norm(u);
        }
        if (den > 0) g[par][m + sb.orders] = num / den;
        norm += std::norm(g[par][m + sb.orders]);
      }
      if (norm > 0)
        for (auto& x : g[par]) x /= std::sqrt(norm);
    }
  };
  auto solve_strengths = [&]() {
    std::vector<double> ata(static_cast<size_t>(k) * k, 0.0), atb(k, 0.0);
    for (int j = 1; j <= nj; ++j)
      for (int m = -sb.orders; m <= sb.orders; ++m) {
        const std::complex<double> pg = p[j - 1] * g[j % 2][m + sb.orders];
        for (int r = 0; r < k; ++r) {
          const std::complex<double> br = pg * v[line(j, m) * k + r];
          atb[r] += weight(j, m) * std::real(std::conj(br) * sb.value[sb.Index(j, m)]);
          for (int c = 0; c < k; ++c)
            ata[r * k + c] += weight(j, m) * std::real(std::conj(br) * pg * v[line(j, m) * k + c]);
        }
      }
    if (!SolveSymmetric(k, &ata, &atb)) return;
    const double amax = *std::max_element(atb.begin(), atb.end());
    if (!(amax > 0)) return;
    for (int q = 0; q < k; ++q) a[q] = std::max(atb[q], 0.0) / amax;
    update_u();
  };
  constexpr int kAlternations = 5;
  update_u();
  solve_p();
  for (int it = 0; it < kAlternations; ++it) {
    solve_patterns();
    solve_p();
    if (k > 1) {
      solve_strengths();
      solve_p();
    }
  }
  double chi2 = 0.0;
  for (int j = 1; j <= nj; ++j)
    for (int m = -sb.orders; m <= sb.orders; ++m)
      chi2 +=
          std::norm(sb.value[sb.Index(j, m)] - p[j - 1] * g[j % 2][m + sb.orders] * u_of(j, m)) *
          (2.0 * weight(j, m));
  return chi2;
}

double LogSumExp(const std::vector<double>& v) {
  double m = -std::numeric_limits<double>::infinity();
  for (double x : v) m = std::max(m, x);
  if (!std::isfinite(m)) return m;
  double s = 0.0;
  for (double x : v) s += std::exp(x - m);
  return m + std::log(s);
}

}  // namespace

double HumpShape::EdgeToCentre() const {
  // d/dq [q^p (1 + beta - beta q)] = 0 at q* = p (1 + beta) / (beta (p + 1)); beyond q = 1 the
  // law rises all the way to the load line.
  if (!(edge_gain > 0.0)) return 1.0;
  const double q = exponent * (1.0 + edge_gain) / (edge_gain * (exponent + 1.0));
  if (q >= 1.0) return 1.0;
  return std::pow(q, exponent) * (1.0 + edge_gain * (1.0 - q));
}

bool CountFitOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  if (max_count < -1) return fail("count fit: max_count must be >= 0, or -1 for every roller");
  if (refine < 1) return fail("count fit: refine must be >= 1");
  if (sideband_pattern_per_parity && sideband_second_pattern)
    return fail(
        "count fit: sideband_pattern_per_parity and sideband_second_pattern exclude each other");
  if (theta_grid_per_slot < 1) return fail("count fit: theta_grid_per_slot must be >= 1");
  if (!(load_zone_half_angle_rad >= 0 && load_zone_half_angle_rad <= kPi))
    return fail("count fit: load_zone_half_angle_rad must be in [0, pi]");
  if (max_iterations < 1) return fail("count fit: max_iterations must be >= 1");
  if (!(sideband_screen_chi2 > 0)) return fail("count fit: sideband_screen_chi2 must be > 0");
  if (!(model_tolerance >= 0 && model_tolerance < 1))
    return fail("count fit: model_tolerance must be in [0, 1)");
  if (!(max_smear_rad > 0.01 && max_smear_rad <= 1.0))
    return fail("count fit: max_smear_rad must be in (0.01, 1]");
  if (exhaustive_max_count < 1) return fail("count fit: exhaustive_max_count must be >= 1");
  if (!(temperature_cage >= 1 && temperature_sidebands >= 1 && std::isfinite(temperature_cage) &&
        std::isfinite(temperature_sidebands)))
    return fail("count fit: temperatures must be finite and >= 1");
  if (sensor_angle_rad && !(std::abs(*sensor_angle_rad) <= kPi))
    return fail("count fit: sensor_angle_rad must be in [-pi, pi]");
  if (!(min_relative_amplitude >= 0 && min_relative_amplitude < 1))
    return fail("count fit: min_relative_amplitude must be in [0, 1)");
  return true;
}

int CountFit::MostProbable() const {
  return static_cast<int>(std::max_element(probability.begin(), probability.end()) -
                          probability.begin());
}

double RollerHump(const CageAverage& average, const HumpFit& fit, int z, size_t roller, int bin) {
  return fit.amplitudes[roller] *
         SmoothedHump(
             average.BinCenterRad(bin) + 2.0 * kPi * fit.slots[roller] / z - fit.theta0_rad,
             fit.shape,
             2.0 * kPi / average.bins());
}

double SmoothedHump(double x, const HumpShape& shape, double bin_rad) {
  return Hump(x,
              shape.exponent,
              shape.edge_gain,
              shape.smear_rad,
              shape.half_angle_rad,
              bin_rad,
              shape.sensor_angle_rad,
              shape.sensor_projection);
}

std::vector<int> CanonicalSlots(const std::vector<int>& slots, int z) {
  std::vector<int> best;
  for (int r : slots) {
    std::vector<int> s;
    for (int v : slots) s.push_back(((v - r) % z + z) % z);
    std::sort(s.begin(), s.end());
    if (best.empty() || s.back() < best.back() || (s.back() == best.back() && s < best)) best = s;
  }
  return best;
}

std::vector<std::vector<int>> SlotConfigurations(int slots, int count) {
  std::vector<std::vector<int>> out;
  if (count <= 0 || count > slots) return out;
  std::set<std::vector<int>> seen;
  // Subsets of {1..Z-1} of size count-1, each with 0 added.
  std::vector<int> pick(count - 1);
  std::function<void(int, int)> rec = [&](int pos, int start) {
    if (pos == count - 1) {
      std::vector<int> s = {0};
      s.insert(s.end(), pick.begin(), pick.end());
      auto c = CanonicalSlots(s, slots);
      if (seen.insert(c).second) out.push_back(c);
      return;
    }
    for (int v = start; v < slots; ++v) {
      pick[pos] = v;
      rec(pos + 1, v + 1);
    }
  };
  rec(0, 1);
  return out;
}

std::vector<double> HumpFourier(const HumpShape& shape, int orders) {
  constexpr int kPoints = 720;
  std::vector<double> out(orders + 1, 0.0);
  for (int i = 0; i < kPoints; ++i) {
    const double x = -kPi + (i + 0.5) * 2.0 * kPi / kPoints;
    const double h = SmoothedHump(x, shape, 0.0);
    for (int m = 0; m <= orders; ++m) out[m] += h * std::cos(m * x) / kPoints;
  }
  return out;
}

namespace {

// Feature B's chi2 of K = 0: every line is noise.
double NoRollerSidebandChi2(const SpinSidebands& sb) {
  double chi2 = 0.0;
  for (size_t i = 0; i < sb.value.size(); ++i)
    chi2 += std::norm(sb.value[i]) / (0.5 * sb.noise_power[i]);
  return chi2;
}

// Minimises chi2(phase) over the spin phases of rollers 2..K from 0: a grid of 24 (12 above
// K = 3) per roller in coordinate sweeps (two for K = 3), then a pattern search below the grid
// step (a phase error of half a step, 7.5 deg, is 30 deg at the fourth harmonic, enough to make a
// true configuration misfit). *phase holds the minimiser; returns the minimum.
template <typename Chi2>
double SearchSpinPhases(int k, const Chi2& chi2, std::vector<double>* phase_io) {
  std::vector<double>& phase = *phase_io;
  const int kPhaseSteps = k <= 3 ? 24 : 12;
  const int kSweeps = k == 3 ? 2 : 1;
  std::fill(phase.begin(), phase.end(), 0.0);
  double c = chi2(phase);
  for (int sweep = 0; sweep < kSweeps && k > 1; ++sweep)
    for (int q = 1; q < k; ++q) {
      double keep = phase[q];
      for (int g = 0; g < kPhaseSteps; ++g) {
        phase[q] = 2.0 * kPi * g / kPhaseSteps;
        const double cg = chi2(phase);
        if (cg < c) c = cg, keep = phase[q];
      }
      phase[q] = keep;
    }
  for (int q = 1; q < k; ++q)
    for (double step = kPi / kPhaseSteps; step > 0.002; step /= 3.0) {
      const double keep = phase[q];
      for (double d : {-step, step}) {
        phase[q] = keep + d;
        const double cg = chi2(phase);
        if (cg < c)
          c = cg;
        else
          phase[q] = keep;
        if (phase[q] != keep) break;
      }
    }
  return c;
}

}  // namespace

// Feature B's chi2 of a configuration, minimised over the spin phases of rollers 2..K (grid of
// kPhaseSteps, coordinate sweeps), a common offset of the humps within +/- one slot (feature A's
// hump centre is only as good as that average's lumps; grid and parabola) and two hump shapes.
// Parameters: one complex p_j per harmonic, K - 1 phases, K - 1 strength ratios and the offset.
double SidebandChi2(const SpinSidebands& sb,
                    const HumpFit& f,
                    int z,
                    int* parameters,
                    std::vector<double>* spin_phase,
                    bool pattern_per_parity,
                    bool second_pattern) {
  const int k = static_cast<int>(f.slots.size());
  std::vector<double> phase(k, 0.0);
  if (k == 0) {
    *parameters = 0;
    return NoRollerSidebandChi2(sb);
  }
  if (pattern_per_parity) {
    // One complex p_j per harmonic, two patterns of 2M + 1 complex orders (less one complex
    // scale each, p_j's), K - 1 phases and K - 1 strength ratios; the patterns start from
    // feature A's hump of this configuration, M_m e^{-i m theta_0}.
    *parameters = 2 * sb.harmonics + 2 * 2 * (2 * sb.orders + 1) - 2 * 2 + 2 * (k - 1);
    const std::vector<double> mm = HumpFourier(f.shape, sb.orders);
    std::vector<std::complex<double>> start(2 * sb.orders + 1);
    for (int m = -sb.orders; m <= sb.orders; ++m)
      start[m + sb.orders] = mm[std::abs(m)] * std::polar(1.0, -m * f.theta0_rad);
    const double c = SearchSpinPhases(
        k,
        [&](const std::vector<double>& ph) {
          return SidebandChi2AtPerParity(sb, f.slots, z, start, ph);
        },
        &phase);
    if (spin_phase) *spin_phase = phase;
    return c;
  }
  *parameters =
      2 * sb.harmonics + 2 * (k - 1) + 1 + 1 + (second_pattern ? 2 * sb.harmonics + sb.orders : 0);
  const int kDeltaSteps = k <= 3 ? 7 : 3;
  const double range = 2.0 * kPi / z;  // +/- one slot
  // The hump's spectrum: feature A's shape of this configuration, or a plain q of the same half
  // angle (A's shape is poorly fixed when humps overlap; the lines then choose).
  HumpShape plain = f.shape;
  plain.exponent = 1.0;
  plain.edge_gain = 0.0;
  plain.smear_rad = 0.02;
  double best = std::numeric_limits<double>::infinity();
  double best_phase_chi2 = std::numeric_limits<double>::infinity();
  std::vector<double> best_phase(k, 0.0);
  std::vector<HumpShape> shapes = {f.shape, plain};
  if (k >= 3) shapes = {plain};  // three and more humps fix their shape poorly anyway
  for (const HumpShape& shape : shapes) {
    const std::vector<double> mm = HumpFourier(shape, sb.orders);
    // Per line and roller: steer = e^{i m (2 pi s_q / Z - theta_0 - delta)}, the second-pattern
    // model's term, or em = M_m steer, the one-pattern model's (each model reads only its own).
    std::vector<std::complex<double>> per_line(static_cast<size_t>(2 * sb.orders + 1) * k);
    auto at = [&](double delta) {
      for (int m = -sb.orders; m <= sb.orders; ++m)
        for (int q = 0; q < k; ++q) {
          const std::complex<double> steer =
              std::polar(1.0, m * (2.0 * kPi * f.slots[q] / z - f.theta0_rad - delta));
          per_line[(m + sb.orders) * k + q] = second_pattern ? steer : mm[std::abs(m)] * steer;
        }
      const double c = second_pattern
                           ? SearchSpinPhases(
                                 k,
                                 [&](const std::vector<double>& ph) {
                                   return SidebandChi2AtTwoPatterns(sb, k, per_line, mm, ph);
                                 },
                                 &phase)
                           : SearchSpinPhases(
                                 k,
                                 [&](const std::vector<double>& ph) {
                                   return SidebandChi2At(sb, f, per_line, ph);
                                 },
                                 &phase);
      if (c < best_phase_chi2) best_phase_chi2 = c, best_phase = phase;
      return c;
    };
    std::vector<double> c(kDeltaSteps);
    int ib = 0;
    const double step = 2.0 * range / (kDeltaSteps - 1);
    for (int i = 0; i < kDeltaSteps; ++i) {
      c[i] = at(-range + step * i);
      if (c[i] < c[ib]) ib = i;
    }
    best = std::min(best, c[ib]);
    if (ib > 0 && ib < kDeltaSteps - 1) {
      const double den = c[ib - 1] - 2.0 * c[ib] + c[ib + 1];
      if (den > 0)
        best = std::min(best, at(-range + step * (ib + 0.5 * (c[ib - 1] - c[ib + 1]) / den)));
    }
  }
  if (spin_phase) *spin_phase = best_phase;
  return best;
}

CountFit FitRollerCount(const CageAverage& average,
                        const SpinSidebands* sidebands,
                        int z,
                        const CountFitOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw InputError(error);
  SPALLKIT_CHECK(z >= 1 && average.bins() >= 8, "count fit needs rollers and >= 8 bins");
  // The model tolerance: each bin's standard error and each line's noise widened by a fraction
  // of the feature's scale, so details the shape model cannot hold do not decide the count.
  CageAverage avg = average;
  {
    const auto [lo, hi] = std::minmax_element(avg.mean.begin(), avg.mean.end());
    const double tol = o.model_tolerance * (*hi - *lo);
    for (double& s : avg.sigma) s = std::sqrt(s * s + tol * tol);
  }
  SpinSidebands lines;
  if (sidebands) {
    lines = *sidebands;
    for (int j = 1; j <= lines.harmonics; ++j) {
      double peak = 0.0;
      for (int m = -lines.orders; m <= lines.orders; ++m)
        peak = std::max(peak, std::abs(lines.value[lines.Index(j, m)]));
      const double tol = o.model_tolerance * peak;
      for (int m = -lines.orders; m <= lines.orders; ++m)
        lines.noise_power[lines.Index(j, m)] += tol * tol;
    }
    sidebands = &lines;
  }
  const int n = avg.bins();
  const int kmax = o.max_count < 0 ? z : std::min(o.max_count, z);
  const bool half_fixed = o.load_zone_half_angle_rad > 0;
  const double bin = 2.0 * kPi / n;
  const SpinSidebands* sb =
      o.use_sidebands && sidebands && sidebands->harmonics > 0 ? sidebands : nullptr;
  const int n_b = sb ? 2 * sb->harmonics * (2 * sb->orders + 1) : 0;

  CountFit out;
  out.slots = z;
  out.bins = n;
  out.sideband_lines = n_b / 2;

  // Every configuration fitted, per K, with feature B's chi2 and parameter count.
  struct Scored {
    HumpFit fit;
    int params_b = 0;
  };
  std::vector<std::vector<Scored>> fits(kmax + 1);
  std::vector<int> n_configs(kmax + 1, 1);
  auto score_b = [&](HumpFit* f) {
    int p = 0;
    if (sb)
      f->chi2_sidebands = SidebandChi2(*sb,
                                       *f,
                                       z,
                                       &p,
                                       &f->spin_phase_rad,
                                       o.sideband_pattern_per_parity,
                                       o.sideband_second_pattern);
    return p;
  };
  auto valid = [&](const HumpFit& f) {
    if (f.amplitudes.empty()) return false;
    const double amax = *std::max_element(f.amplitudes.begin(), f.amplitudes.end());
    const double amin = *std::min_element(f.amplitudes.begin(), f.amplitudes.end());
    return amax > 0 && amin >= o.min_relative_amplitude * amax;
  };
  auto rank = [](const Scored& a, const Scored& b) {
    return a.fit.chi2 + a.fit.chi2_sidebands < b.fit.chi2 + b.fit.chi2_sidebands;
  };

  // K = 0: weighted mean; no lines.
  {
    double sw = 0, swy = 0;
    for (int i = 0; i < n; ++i) {
      const double w = 1.0 / (avg.sigma[i] * avg.sigma[i]);
      sw += w;
      swy += w * avg.mean[i];
    }
    Scored s;
    s.fit.floor = swy / sw;
    s.fit.model.assign(n, s.fit.floor);
    s.fit.chi2 = Chi2(avg, s.fit.model);
    s.fit.refined = true;
    s.params_b = score_b(&s.fit);
    fits[0].push_back(s);
  }

  // K = 1: grid over theta_0 and a few exponents, then Ceres.
  const int grid = o.theta_grid_per_slot * z;
  HumpShape shape;
  shape.half_angle_fixed = half_fixed;
  shape.half_angle_rad = half_fixed ? o.load_zone_half_angle_rad : 70.0 * kPi / 180.0;
  shape.sensor_angle_rad = o.sensor_angle_rad.value_or(0.0);
  shape.sensor_projection = o.sensor_angle_rad.has_value();
  shape.smear_rad = std::min(0.05, o.max_smear_rad);
  if (kmax >= 1) {
    HumpFit best1;
    best1.chi2 = std::numeric_limits<double>::infinity();
    for (auto [p, edge] : {std::pair{0.5, 0.0}, {1.0, 0.0}, {2.0, 0.0}, {0.5, 4.0}, {1.0, 8.0}}) {
      HumpShape s = shape;
      s.exponent = p;
      s.edge_gain = edge;
      for (int g = 0; g < grid; ++g) {
        const double theta = 2.0 * kPi * g / grid;
        std::vector<double> col(n);
        for (int i = 0; i < n; ++i) col[i] = SmoothedHump(avg.BinCenterRad(i) - theta, s, bin);
        HumpFit f;
        if (!LinearFit(avg, {&col}, &f.floor, &f.amplitudes, &f.chi2)) continue;
        if (f.chi2 < best1.chi2) {
          f.slots = {0};
          f.theta0_rad = theta;
          f.shape = s;
          best1 = f;
        }
      }
    }
    if (!std::isfinite(best1.chi2)) {  // no positive hump anywhere: a flat one
      best1.slots = {0};
      best1.amplitudes = {0.0};
      best1.floor = fits[0][0].fit.floor;
      best1.shape = shape;
      best1.model = Model(avg, best1, z);
      best1.chi2 = Chi2(avg, best1.model);
    }
    Scored s;
    s.fit = Refine(avg, z, best1, o);
    if (s.fit.model.empty()) s.fit.model = Model(avg, s.fit, z);
    s.params_b = score_b(&s.fit);
    fits[1].push_back(s);
    shape = s.fit.shape;
  }

  // K >= 2: screen with a fixed shape, refine the best few; two passes of the shape.
  auto search = [&](const HumpShape& screen_shape) {
    std::vector<std::vector<std::vector<double>>> columns(grid,
                                                          std::vector<std::vector<double>>(z));
    for (int g = 0; g < grid; ++g)
      for (int s = 0; s < z; ++s) {
        columns[g][s].resize(n);
        const double theta = 2.0 * kPi * g / grid;
        for (int i = 0; i < n; ++i)
          columns[g][s][i] =
              SmoothedHump(avg.BinCenterRad(i) + 2.0 * kPi * s / z - theta, screen_shape, bin);
      }
    auto screen = [&](const std::vector<int>& c) {
      Scored best;
      best.fit.chi2 = std::numeric_limits<double>::infinity();
      for (int g = 0; g < grid; ++g) {
        std::vector<const std::vector<double>*> cols;
        for (int s : c) cols.push_back(&columns[g][s]);
        HumpFit f;
        if (!LinearFit(avg, cols, &f.floor, &f.amplitudes, &f.chi2)) continue;
        if (f.chi2 < best.fit.chi2 && valid(f)) {
          f.slots = c;
          f.theta0_rad = 2.0 * kPi * g / grid;
          f.shape = screen_shape;
          best.fit = f;
        }
      }
      return best;
    };
    double best_so_far = -std::numeric_limits<double>::infinity();
    int best_k = 0;
    auto rough = [&](const Scored& s) {  // unscaled combined log evidence of one configuration
      return -0.5 * (s.fit.chi2 + s.fit.chi2_sidebands) -
             0.5 * ParameterCount(static_cast<int>(s.fit.slots.size()), half_fixed) *
                 std::log(static_cast<double>(n)) -
             0.5 * s.params_b * (n_b > 0 ? std::log(static_cast<double>(n_b)) : 0.0);
    };
    for (int k = 0; k < 2; ++k)
      for (const auto& s : fits[k])
        if (rough(s) > best_so_far) best_so_far = rough(s), best_k = k;
    for (int k = 2; k <= kmax; ++k) {
      // Greedy counts far beyond the best so far, with far less evidence, are not searched.
      if (k > o.exhaustive_max_count && k > best_k + 2 && !fits[k - 1].empty() &&
          rough(fits[k - 1].front()) < best_so_far - 50.0)
        break;
      std::vector<std::vector<int>> configs;
      if (k <= o.exhaustive_max_count) {
        configs = SlotConfigurations(z, k);
      } else if (!fits[k - 1].empty()) {
        std::set<std::vector<int>> seen;
        for (int s = 0; s < z; ++s) {
          std::vector<int> c = fits[k - 1].front().fit.slots;
          if (std::find(c.begin(), c.end(), s) != c.end()) continue;
          c.push_back(s);
          c = CanonicalSlots(c, z);
          if (seen.insert(c).second) configs.push_back(c);
        }
      }
      n_configs[k] = static_cast<int>(SlotConfigurations(z, k).size());
      // Keep the better of this pass and an earlier one for each configuration.
      std::map<std::vector<int>, Scored> by_slots;
      for (auto& s : fits[k]) by_slots[s.fit.slots] = s;
      std::vector<Scored> screened;
      for (const auto& c : configs) {
        Scored s = screen(c);
        if (std::isfinite(s.fit.chi2)) screened.push_back(s);
      }
      // Feature B (the costly one) only where feature A leaves the configuration a chance.
      double best_a = std::numeric_limits<double>::infinity();
      for (int q = 0; q < k; ++q)
        for (const auto& f : fits[q]) best_a = std::min(best_a, f.fit.chi2);
      for (const auto& f : screened) best_a = std::min(best_a, f.fit.chi2);
      for (auto& f : screened) {
        if (f.fit.chi2 <= best_a + o.sideband_screen_chi2) {
          f.params_b = score_b(&f.fit);
        } else if (sb) {
          f.fit.chi2_sidebands = std::numeric_limits<double>::infinity();
        }
      }
      std::sort(screened.begin(), screened.end(), rank);
      const int refine = std::min<int>(k <= o.exhaustive_max_count ? o.refine : 1, screened.size());
      for (int j = 0; j < refine; ++j) {
        // From the screened shape and from a plain one (the screen's shape may be a K = 1 fit's
        // compromise over several humps, a poor start for this configuration).
        HumpFit plain = screened[j].fit;
        plain.shape.exponent = 1.0;
        plain.shape.edge_gain = 0.0;
        plain.shape.smear_rad = std::min(0.03, o.max_smear_rad);
        plain.model = Model(avg, plain, z);
        plain.chi2 = Chi2(avg, plain.model);
        for (const HumpFit* start : {&screened[j].fit, &plain}) {
          HumpFit r = Refine(avg, z, *start, o);
          if (valid(r) && (!screened[j].fit.refined || r.chi2 < screened[j].fit.chi2)) {
            screened[j].fit = r;
            screened[j].params_b = score_b(&screened[j].fit);
          }
        }
      }
      for (auto& s : screened) {
        auto it = by_slots.find(s.fit.slots);
        if (it == by_slots.end() || rank(s, it->second)) by_slots[s.fit.slots] = s;
      }
      fits[k].clear();
      for (auto& [slots, s] : by_slots) fits[k].push_back(s);
      std::sort(fits[k].begin(), fits[k].end(), rank);
      for (const auto& s : fits[k])
        if (rough(s) > best_so_far) best_so_far = rough(s), best_k = k;
    }
  };

  // Evidence with each feature's chi2 scale (the best model's reduced chi2, >= 1).
  auto evidence = [&]() {
    const double ln_n = std::log(static_cast<double>(n));
    const double ln_nb = n_b > 0 ? std::log(static_cast<double>(n_b)) : 0.0;
    auto ln_za = [&](const Scored& s, double scale) {
      return -0.5 * s.fit.chi2 / scale -
             0.5 * ParameterCount(static_cast<int>(s.fit.slots.size()), half_fixed) * ln_n;
    };
    auto ln_zb = [&](const Scored& s, double scale) {
      return n_b > 0 ? -0.5 * s.fit.chi2_sidebands / scale - 0.5 * s.params_b * ln_nb : 0.0;
    };
    // Best models of each feature for the scales.
    const Scored* best_a = nullptr;
    const Scored* best_b = nullptr;
    for (int k = 0; k <= kmax; ++k)
      for (const auto& s : fits[k]) {
        if (!best_a || ln_za(s, 1.0) > ln_za(*best_a, 1.0)) best_a = &s;
        if (!best_b || ln_zb(s, 1.0) > ln_zb(*best_b, 1.0)) best_b = &s;
      }
    const int ka = static_cast<int>(best_a->fit.slots.size());
    out.chi2_scale =
        std::max(1.0, best_a->fit.chi2 / std::max(1, n - ParameterCount(ka, half_fixed)));
    out.chi2_scale_sidebands =
        n_b > 0 ? std::max(1.0, best_b->fit.chi2_sidebands / std::max(1, n_b - best_b->params_b))
                : 1.0;
    const double ninf = -std::numeric_limits<double>::infinity();
    out.log_evidence_cage.assign(kmax + 1, ninf);
    out.log_evidence_sidebands.assign(kmax + 1, ninf);
    out.log_evidence.assign(kmax + 1, ninf);
    out.configuration_probability.assign(kmax + 1, 0.0);
    out.best.assign(kmax + 1, HumpFit{});
    for (int k = 0; k <= kmax; ++k) {
      if (fits[k].empty()) continue;
      std::vector<double> ta, tb, tc;
      for (const auto& s : fits[k]) {
        ta.push_back(ln_za(s, out.chi2_scale));
        tb.push_back(ln_zb(s, out.chi2_scale_sidebands));
        tc.push_back(ta.back() / o.temperature_cage + tb.back() / o.temperature_sidebands);
      }
      const double ln_configs = std::log(static_cast<double>(n_configs[k]));
      out.log_evidence_cage[k] = LogSumExp(ta) - ln_configs;
      out.log_evidence_sidebands[k] = LogSumExp(tb) - ln_configs;
      const double lse = LogSumExp(tc);
      out.log_evidence[k] = o.combine_per_count
                                ? out.log_evidence_cage[k] / o.temperature_cage +
                                      out.log_evidence_sidebands[k] / o.temperature_sidebands
                                : lse - ln_configs;
      const int best = static_cast<int>(std::max_element(tc.begin(), tc.end()) - tc.begin());
      out.best[k] = fits[k][best].fit;
      out.configuration_probability[k] = std::exp(tc[best] - lse);
    }
    auto normalise = [&](const std::vector<double>& lz, std::vector<double>* p) {
      const double lse = LogSumExp(lz);
      p->resize(kmax + 1);
      for (int k = 0; k <= kmax; ++k) (*p)[k] = std::exp(lz[k] - lse);
    };
    auto tempered = [&](std::vector<double> lz, double t) {
      for (double& v : lz) v /= t;
      return lz;
    };
    normalise(tempered(out.log_evidence_cage, o.temperature_cage), &out.probability_cage);
    normalise(tempered(out.log_evidence_sidebands, o.temperature_sidebands),
              &out.probability_sidebands);
    normalise(out.log_evidence, &out.probability);
  };

  if (kmax >= 2) {
    search(shape);
    evidence();
    const HumpShape second = out.best[out.MostProbable()].shape;
    if (out.MostProbable() >= 2 &&
        (second.exponent != shape.exponent || second.edge_gain != shape.edge_gain))
      search(second);
  }
  evidence();
  for (auto& f : out.best)
    if (f.model.empty() && !f.slots.empty()) f.model = Model(avg, f, z);
  return out;
}

}  // namespace spallkit::identify
