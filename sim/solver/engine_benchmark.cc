#include "sim/solver/engine_benchmark.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <utility>

#include "core/constants.h"
#include "core/error.h"
#include "sim/contact/contact_pair.h"
#include "sim/contact/surface.h"
#include "sim/fe/mesh_primitives.h"

namespace spallkit::sim::solver {
namespace {

constexpr double kRingIn = 0.02, kRingOut = 0.03, kRollerR = 0.005, kInterference = 1e-6,
                 kThickness = 0.01;

double CpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Wall and process CPU seconds of `steps` steps after a warm-up.
std::pair<double, double> TimeSteps(ExplicitSolver& s, int steps) {
  for (int k = 0; k < 5; ++k) s.Step();  // warm-up: caches, contact grids
  const double c0 = CpuSeconds();
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) s.Step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {wall, CpuSeconds() - c0};
}

}  // namespace

bool EngineBenchmarkOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* m) {
    if (error) *error = m;
    return false;
  };
  if (elements < 500) return fail("bench: --elements must be >= 500");
  if (threads < 1) return fail("bench: --threads must be >= 1");
  if (steps < 1) return fail("bench: --steps must be >= 1");
  if (rollers < 1 || rollers > 16) return fail("bench: rollers must be in [1, 16]");
  return true;
}

namespace {
fe::Mesh MeshWithSize(const EngineBenchmarkOptions& o, double h) {
  std::vector<fe::Mesh> parts;
  fe::AnnulusSpec ring;
  ring.inner_radius = kRingIn, ring.outer_radius = kRingOut;
  ring.n_radial = std::max(1, static_cast<int>(std::lround((kRingOut - kRingIn) / h)));
  ring.n_theta =
      std::max(8, static_cast<int>(std::lround(2 * kPi * 0.5 * (kRingIn + kRingOut) / h)));
  parts.push_back(fe::MakeAnnulus("inner_ring", ring));
  for (int k = 0; k < o.rollers; ++k) {
    fe::DiscSpec d;
    const double phi = 2 * kPi * k / o.rollers, rc = kRingOut + kRollerR - kInterference;
    d.cx = rc * std::cos(phi), d.cy = rc * std::sin(phi), d.radius = kRollerR;
    d.n_core = std::max(1, static_cast<int>(std::lround(2 * kPi * kRollerR / (4 * h))));
    d.n_radial = std::max(1, static_cast<int>(std::lround(kRollerR * (1 - d.core_fraction) / h)));
    parts.push_back(fe::MakeDisc("roller" + std::to_string(k), d));
  }
  return fe::MergeMeshes(parts);
}
}  // namespace

fe::Mesh MakeBenchmarkMesh(const EngineBenchmarkOptions& o) {
  std::string err;
  if (!o.IsValid(&err)) throw InputError(err);
  const double area =
      kPi * (kRingOut * kRingOut - kRingIn * kRingIn) + o.rollers * kPi * kRollerR * kRollerR;
  double h = std::sqrt(area / o.elements);
  // One correction: the O-grid discs hold more elements than their area suggests.
  h *= std::sqrt(static_cast<double>(MeshWithSize(o, h).num_elements()) / o.elements);
  fe::Mesh mesh = MeshWithSize(o, h);
  fe::ReorderForLocality(&mesh);
  return mesh;
}

std::unique_ptr<BenchmarkModel> MakeBenchmarkModel(const EngineBenchmarkOptions& o,
                                                   bool with_contact) {
  auto m = std::make_unique<BenchmarkModel>();
  m->mesh = MakeBenchmarkMesh(o);
  fe::Section sec;
  sec.thickness = kThickness;
  SolverOptions opt;
  opt.num_threads = o.threads;
  opt.energy_terms = o.energy_terms;
  m->solver = std::make_unique<ExplicitSolver>(
      m->mesh, std::vector<fe::Section>(m->mesh.num_parts(), sec), opt);
  // The ring turns slowly so the nodes move (prescribed bore rotation).
  RigidBody shaft;
  shaft.name = "shaft";
  shaft.nodes = m->mesh.node_sets.at("inner_ring.inner");
  shaft.angle = [](double t) { return 100.0 * t; };
  shaft.x_motion = shaft.y_motion = [](double) { return 0.0; };
  m->solver->AddRigidBody(shaft);
  if (with_contact) {
    const double bulk = sec.material.youngs_modulus / (3 * (1 - 2 * sec.material.poisson_ratio));
    const std::vector<double> k(m->mesh.num_parts(), bulk);
    for (int r = 0; r < o.rollers; ++r) {
      const std::string name = "roller" + std::to_string(r);
      contact::ContactPairOptions copt;
      copt.friction.static_coefficient = 0.01;
      copt.friction.dynamic_coefficient = 0.005;
      auto pair = std::make_unique<contact::ContactPair>(
          name + "/inner_ring",
          contact::MakeSurface(m->mesh, name + ".outer", k, kThickness),
          contact::MakeSurface(m->mesh, "inner_ring.outer", k, kThickness),
          copt);
      m->solver->AddContributor(pair.get());
      m->contributors.push_back(std::move(pair));
    }
  }
  return m;
}

EngineBenchmarkResult RunEngineBenchmark(const EngineBenchmarkOptions& o) {
  EngineBenchmarkResult r;
  r.threads = o.threads, r.steps = o.steps;
  {
    auto m = MakeBenchmarkModel(o, false);
    r.elements = m->mesh.num_elements(), r.nodes = m->mesh.num_nodes();
    const auto [wall, cpu] = TimeSteps(*m->solver, o.steps);
    r.ns_per_element_cycle = 1e9 * wall / (static_cast<double>(o.steps) * r.elements);
    r.cpu_ns_per_element_cycle = 1e9 * cpu / (static_cast<double>(o.steps) * r.elements);
    r.time_step = m->solver->time_step();
  }
  {
    auto m = MakeBenchmarkModel(o, true);
    const auto [wall, cpu] = TimeSteps(*m->solver, o.steps);
    r.ns_per_element_cycle_with_contact = 1e9 * wall / (static_cast<double>(o.steps) * r.elements);
    r.cpu_ns_per_element_cycle_with_contact =
        1e9 * cpu / (static_cast<double>(o.steps) * r.elements);
  }
  return r;
}

}  // namespace spallkit::sim::solver
