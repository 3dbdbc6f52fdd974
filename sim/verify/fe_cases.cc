// Element and solver verification cases (patch, rigid rotation, centrifugal stress, wave speed,
// cantilever frequency, hourglass share, energy balance). Each runs in about a second or less.
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "core/constants.h"
#include "sim/fe/mesh_primitives.h"
#include "sim/fe/section.h"
#include "sim/solver/explicit_solver.h"
#include "sim/verify/verification.h"

namespace spallkit::sim::verify {
namespace {

fe::Section Steel(fe::PlaneMode mode) {
  fe::Section s;
  s.mode = mode;
  s.thickness = 0.01;
  return s;
}

// Times at which samples (t_k, u_k) cross zero (linear interpolation), after t_min.
std::vector<double> ZeroCrossings(const std::vector<double>& t,
                                  const std::vector<double>& u,
                                  double t_min) {
  std::vector<double> z;
  for (size_t k = 1; k < u.size(); ++k)
    if (t[k - 1] > t_min && ((u[k - 1] < 0.0) != (u[k] < 0.0)) && u[k] != u[k - 1])
      z.push_back(t[k - 1] + (t[k] - t[k - 1]) * u[k - 1] / (u[k - 1] - u[k]));
  return z;
}

// Constant strain on a distorted mesh: boundary nodes follow v = G x0, interior nodes start on
// it; every element must carry sigma = C : (G t) and interior nodes must not accelerate.
void PatchTest(std::vector<CaseResult>* out) {
  fe::RectangleSpec spec;
  spec.width = 0.02, spec.height = 0.015, spec.nx = 5, spec.ny = 4;
  fe::Mesh mesh = fe::MakeRectangle("patch", spec);
  // Distort interior nodes deterministically (up to 30 % of a cell).
  for (int j = 1; j < spec.ny; ++j)
    for (int i = 1; i < spec.nx; ++i) {
      const int id = j * (spec.nx + 1) + i;
      mesh.x[id] += 0.3 * (spec.width / spec.nx) * std::sin(1.7 * i + 2.3 * j);
      mesh.y[id] += 0.3 * (spec.height / spec.ny) * std::cos(2.9 * i - 1.1 * j);
    }
  const fe::Section sec = Steel(fe::PlaneMode::kPlaneStrain);
  solver::ExplicitSolver solver(mesh, {sec});
  const double g[2][2] = {{1e-3, 2.5e-4}, {2.5e-4, -6e-4}};  // symmetric velocity gradient, 1/s
  auto& s = solver.state();
  for (size_t i = 0; i < s.size(); ++i) {
    s.vx[i] = g[0][0] * s.x0[i] + g[0][1] * s.y0[i];
    s.vy[i] = g[1][0] * s.x0[i] + g[1][1] * s.y0[i];
  }
  solver::VelocityCondition bc;
  for (const auto& [name, set] : mesh.node_sets)
    if (name != "patch.all")
      for (int id : set)
        if (std::find(bc.nodes.begin(), bc.nodes.end(), id) == bc.nodes.end())
          bc.nodes.push_back(id);
  for (int id : bc.nodes) bc.vx.push_back(s.vx[id]), bc.vy.push_back(s.vy[id]);
  solver.AddVelocityCondition(bc);
  for (int k = 0; k < 200; ++k) solver.Step();
  const double t = solver.time() - solver.time_step();  // stresses lag positions by one step
  const double lam = sec.material.Lambda(), mu = sec.material.Mu();
  const double exx = g[0][0] * t, eyy = g[1][1] * t, exy = g[0][1] * t;
  const double rxx = lam * (exx + eyy) + 2 * mu * exx, ryy = lam * (exx + eyy) + 2 * mu * eyy,
               rxy = 2 * mu * exy;
  const double scale = std::max({std::abs(rxx), std::abs(ryy), std::abs(rxy)});
  double worst = 0.0, worst_sxx = rxx;
  const auto& el = solver.elements();
  for (int e = 0; e < el.num_elements(); ++e) {
    const double d =
        std::max(
            {std::abs(el.sxx(e) - rxx), std::abs(el.syy(e) - ryy), std::abs(el.sxy(e) - rxy)}) /
        scale;
    if (d > worst) worst = d, worst_sxx = el.sxx(e);
  }
  AddCase(out,
          "patch: constant strain, distorted mesh",
          "sigma_xx of the worst element (Pa)",
          rxx,
          worst_sxx,
          1e-6,
          "max over elements and components of |sigma - C:eps| / max|C:eps|; 20 distorted quads",
          false);
  out->back().error = worst;
  out->back().pass = worst <= 1e-6;
}

// A ring whose nodes all follow a prescribed rigid rotation for 100 revolutions.
void RigidRotation(std::vector<CaseResult>* out) {
  fe::AnnulusSpec as;
  as.inner_radius = 0.04, as.outer_radius = 0.05, as.n_theta = 48, as.n_radial = 2;
  const fe::Mesh mesh = fe::MakeAnnulus("ring", as);
  const fe::Section sec = Steel(fe::PlaneMode::kPlaneStrain);
  solver::ExplicitSolver solver(mesh, {sec});
  // About 0.02 rad per step.
  const double dt_est = 0.9 * (0.005 / std::sqrt(2.0)) / sec.WaveSpeed();
  const double omega = 0.02 / dt_est;
  solver::RigidBody body;
  body.name = "ring";
  body.nodes = mesh.node_sets.at("ring.all");
  body.angle = [omega](double t) { return omega * t; };
  body.x_motion = [](double) { return 0.0; };
  body.y_motion = [](double) { return 0.0; };
  solver.AddRigidBody(body);
  solver.SetRigidVelocity(body.nodes, 0, 0, omega, 0, 0);
  const double t_end = 100 * 2 * kPi / omega;
  double peak = 0.0;
  while (solver.time() < t_end) {
    solver.Step();
    if (solver.step() % 100 == 0)
      for (int e = 0; e < solver.elements().num_elements(); ++e)
        peak = std::max(peak, solver.elements().VonMises(e));
  }
  for (int e = 0; e < solver.elements().num_elements(); ++e)
    peak = std::max(peak, solver.elements().VonMises(e));
  const double revs = solver.time() * omega / (2 * kPi);
  std::ostringstream note;
  note << "peak von Mises / E over " << revs << " prescribed revolutions, " << solver.step()
       << " steps";
  AddCase(out,
          "rotation: prescribed rigid rotation, 100 revolutions",
          "peak von Mises stress / E",
          0.0,
          peak / sec.material.youngs_modulus,
          1e-12,
          note.str(),
          true);
}

// Free ring spinning at constant speed, relative mass damping removes the breathing transient:
// hoop stress vs the plane-stress rotating-disc solution.
void CentrifugalRing(std::vector<CaseResult>* out) {
  fe::AnnulusSpec as;
  as.inner_radius = 0.04, as.outer_radius = 0.05, as.n_theta = 96, as.n_radial = 4;
  const fe::Mesh mesh = fe::MakeAnnulus("ring", as);
  const fe::Section sec = Steel(fe::PlaneMode::kPlaneStress);
  solver::SolverOptions opt;
  const double f_breath = sec.WaveSpeed() / (2 * kPi * 0.045);
  opt.mass_damping_ratio = 0.3;
  opt.damping_frequency = f_breath;
  solver::ExplicitSolver solver(mesh, {sec}, opt);
  const double omega0 = 2500.0;  // rad/s, rho w^2 R^2 = 100 MPa
  solver.SetRigidVelocity(mesh.node_sets.at("ring.all"), 0, 0, omega0, 0, 0);
  const double t_end = 3 * 2 * kPi / omega0;  // three revolutions, ~30 damping time constants
  solver.Run(t_end);
  double vx, vy, omega;
  solver.PartRigidMotion(0, &vx, &vy, &omega);
  const double nu = sec.material.poisson_ratio, rho = sec.material.density;
  const double a = as.inner_radius, b = as.outer_radius;
  auto hoop = [&](double r) {
    return (3 + nu) / 8 * rho * omega * omega *
           (a * a + b * b + a * a * b * b / (r * r) - (1 + 3 * nu) / (3 + nu) * r * r);
  };
  // Element hoop stress per radial layer, averaged around the ring.
  const auto& el = solver.elements();
  double worst = 0.0, ref_worst = 0.0, comp_worst = 0.0;
  for (int layer = 0; layer < as.n_radial; ++layer) {
    double sum = 0.0, ref = 0.0;
    for (int i = 0; i < as.n_theta; ++i) {
      const int e = layer * as.n_theta + i;
      double cx, cy;
      el.Centroid(solver.state(), e, &cx, &cy);
      const double r = std::hypot(cx, cy), c = cx / r, s = cy / r;
      sum += el.sxx(e) * s * s + el.syy(e) * c * c - 2 * el.sxy(e) * s * c;
      // Reference radius: the undeformed centroid.
      double x0 = 0, y0 = 0;
      for (int k = 0; k < 4; ++k)
        x0 += 0.25 * mesh.x[mesh.quads[e][k]], y0 += 0.25 * mesh.y[mesh.quads[e][k]];
      ref += hoop(std::hypot(x0, y0));
    }
    sum /= as.n_theta, ref /= as.n_theta;
    const double err = std::abs(sum - ref) / std::abs(ref);
    if (err >= worst) worst = err, ref_worst = ref, comp_worst = sum;
  }
  std::ostringstream note;
  note << "plane stress ring 40/50 mm, 96x4 quads, " << solver.time() * omega / (2 * kPi)
       << " revolutions, worst radial layer; omega " << omega << " rad/s at the end";
  AddCase(out,
          "rotation: free spinning ring, centrifugal hoop stress",
          "layer-mean hoop stress (Pa)",
          ref_worst,
          comp_worst,
          0.02,
          note.str());
  AddCase(out,
          "rotation: relative mass damping keeps the spin",
          "spin after 3 revolutions (rad/s)",
          omega0,
          omega,
          0.005,
          "angular velocity from the part's rigid motion; plain mass damping would brake it");
}

// First longitudinal mode of a free-free bar: c = 2 L f.
void WaveSpeed(std::vector<CaseResult>* out, fe::PlaneMode mode) {
  const double length = 0.1, h = 0.002;
  fe::RectangleSpec spec;
  spec.width = length, spec.height = h, spec.nx = 50, spec.ny = 1;
  const fe::Mesh mesh = fe::MakeRectangle("bar", spec);
  fe::Section sec = Steel(mode);
  solver::ExplicitSolver solver(mesh, {sec});
  const bool strain = mode == fe::PlaneMode::kPlaneStrain;
  if (strain) solver.FixNodes(mesh.node_sets.at("bar.all"), false, true);  // uniaxial strain
  const double c_ref =
      strain ? sec.WaveSpeed() : std::sqrt(sec.material.youngs_modulus / sec.material.density);
  auto& s = solver.state();
  for (size_t i = 0; i < s.size(); ++i) s.vx[i] = 0.1 * std::cos(kPi * s.x0[i] / length);
  const int probe = 0;  // node at x = 0
  std::vector<double> t, u;
  const double period = 2 * length / c_ref;
  while (solver.time() < 3.2 * period) {
    solver.Step();
    t.push_back(solver.time());
    u.push_back(s.x[probe] - s.x0[probe]);
  }
  const auto z = ZeroCrossings(t, u, 0.1 * period);
  double c = 0.0;
  if (z.size() >= 2) c = 2 * length / (2 * (z.back() - z.front()) / (z.size() - 1));
  AddCase(out,
          strain ? "wave: P-wave speed, plane strain bar (uniaxial strain)"
                 : "wave: bar wave speed, plane stress",
          "longitudinal wave speed (m/s)",
          c_ref,
          c,
          0.01,
          strain ? "sqrt((lambda+2mu)/rho); first free-free mode, 50 quads"
                 : "sqrt(E/rho); first free-free mode, 50 quads");
}

// Cantilever first bending frequency vs Euler-Bernoulli; hourglass share; energy balance.
void Cantilever(std::vector<CaseResult>* out, const std::string& filter) {
  const double length = 0.4, h = 0.02;
  fe::RectangleSpec spec;
  spec.width = length, spec.height = h, spec.nx = 120, spec.ny = 6;
  const fe::Mesh mesh = fe::MakeRectangle("beam", spec);
  const fe::Section sec = Steel(fe::PlaneMode::kPlaneStress);
  solver::ExplicitSolver solver(mesh, {sec});
  solver.FixNodes(mesh.node_sets.at("beam.left"), true, true);
  const double bl = 1.8751040687119611;
  const double sig = (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
  auto& s = solver.state();
  for (size_t i = 0; i < s.size(); ++i) {
    const double z = bl * s.x0[i] / length;
    s.vy[i] = 0.05 * 0.5 * (std::cosh(z) - std::cos(z) - sig * (std::sinh(z) - std::sin(z)));
  }
  const auto& E = sec.material.youngs_modulus;
  const double f_eb =
      bl * bl / (2 * kPi * length * length) * std::sqrt(E * h * h / 12 / sec.material.density);
  const auto& tip = mesh.node_sets.at("beam.right");
  std::vector<double> t, u;
  double peak_int = 0.0, peak_hg = 0.0, worst_balance = 0.0;
  const double period = 1.0 / f_eb;
  while (solver.time() < 2.3 * period) {
    solver.Step();
    double w = 0;
    for (int id : tip) w += s.y[id] - s.y0[id];
    t.push_back(solver.time());
    u.push_back(w / tip.size());
    if (solver.step() % 200 == 0) {
      const auto e = solver.energies();
      peak_int = std::max(peak_int, e.internal);
      peak_hg = std::max(peak_hg, e.hourglass);
      worst_balance = std::max(worst_balance, e.BalanceError());
    }
  }
  const auto z = ZeroCrossings(t, u, 0.1 * period);
  double f = 0.0;
  if (z.size() >= 2) f = 1.0 / (2 * (z.back() - z.front()) / (z.size() - 1));
  if (CaseSelected("cantilever: first bending frequency", filter))
    AddCase(out,
            "cantilever: first bending frequency",
            "frequency (Hz)",
            f_eb,
            f,
            0.02,
            "plane stress, L/H = 20, 120x6 one-point quads, QM = 1; Euler-Bernoulli reference");
  if (CaseSelected("cantilever: hourglass energy share", filter))
    AddCase(out,
            "cantilever: hourglass energy share",
            "peak E_hg / peak E_int",
            0.0,
            peak_int > 0 ? peak_hg / peak_int : 1.0,
            0.05,
            "absolute; must stay below 5 %",
            true);
  if (CaseSelected("cantilever: energy balance", filter))
    AddCase(
        out,
        "cantilever: energy balance",
        "worst balance error",
        0.0,
        worst_balance,
        0.01,
        "absolute; |E_kin + E_int + E_hg - E_kin(0) - W_ext| / max term, sampled every 200 steps",
        true);
}

}  // namespace

void AppendFeCases(std::vector<CaseResult>* results, const std::string& filter) {
  if (CaseSelected("patch: constant strain, distorted mesh", filter)) PatchTest(results);
  if (CaseSelected("rotation: prescribed rigid rotation, 100 revolutions", filter))
    RigidRotation(results);
  if (CaseSelected("rotation: free spinning ring, centrifugal hoop stress", filter) ||
      CaseSelected("rotation: relative mass damping keeps the spin", filter))
    CentrifugalRing(results);
  if (CaseSelected("wave: P-wave speed, plane strain bar (uniaxial strain)", filter))
    WaveSpeed(results, fe::PlaneMode::kPlaneStrain);
  if (CaseSelected("wave: bar wave speed, plane stress", filter))
    WaveSpeed(results, fe::PlaneMode::kPlaneStress);
  if (CaseSelected("cantilever: first bending frequency", filter) ||
      CaseSelected("cantilever: hourglass energy share", filter) ||
      CaseSelected("cantilever: energy balance", filter))
    Cantilever(results, filter);
}

}  // namespace spallkit::sim::verify
