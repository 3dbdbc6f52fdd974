// Thread-count independence and the fused code paths of the optimised FE step (fe-perf):
//  - a model big enough that every thread gets element blocks and node chunks (ring + rollers of
//    the engine benchmark, ~3000 elements = 12 blocks, 3 node chunks), with contact pairs,
//    relative mass damping, stiffness damping and a driven shaft: 1, 2 and 3 threads must give
//    bit-identical positions, velocities and energies;
//  - the same model without contributors (gather fused into the nodal update) likewise;
//  - ComputeForces (element pass + gather in one region) equals ComputeCornerForces followed by
//    GatherForces bit for bit;
//  - the stable step of a square element is L_e / c with L_e = A / diagonal (analytic), and
//    stiffness damping shortens it by sqrt(1 + xi^2) - xi.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "sim/contact/contact_pair.h"
#include "sim/contact/surface.h"
#include "sim/fe/mesh_primitives.h"
#include "sim/fe/quad_elements.h"
#include "sim/solver/engine_benchmark.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit {
namespace {

struct Run {
  std::unique_ptr<sim::solver::ExplicitSolver> solver;
  std::vector<std::unique_ptr<sim::contact::ContactPair>> pairs;
};

Run Build(const sim::fe::Mesh& mesh, int threads, bool with_contact) {
  Run r;
  sim::solver::SolverOptions opt;
  opt.num_threads = threads;
  opt.mass_damping_ratio = 0.02;
  opt.damping_frequency = 2e4;
  opt.stiffness_damping_ratio = 0.005;
  opt.stiffness_damping_frequency = 1e5;
  sim::fe::Section sec;
  sec.thickness = 0.01;
  r.solver = std::make_unique<sim::solver::ExplicitSolver>(
      mesh, std::vector<sim::fe::Section>(mesh.num_parts(), sec), opt);
  sim::solver::RigidBody shaft;
  shaft.name = "shaft";
  shaft.nodes = mesh.node_sets.at("inner_ring.inner");
  shaft.angle = sim::solver::RampedRotation(3000.0, 2e-6);
  shaft.y_motion = [](double) { return 0.0; };
  shaft.force_x = [](double) { return 2e4; };
  r.solver->AddRigidBody(shaft);
  if (with_contact) {
    const double bulk = sec.material.youngs_modulus / (3 * (1 - 2 * sec.material.poisson_ratio));
    const std::vector<double> k(mesh.num_parts(), bulk);
    for (int p = 1; p < mesh.num_parts(); ++p) {
      sim::contact::ContactPairOptions c;
      c.friction.static_coefficient = 0.1;
      c.friction.dynamic_coefficient = 0.05;
      c.normal_damping_ratio = 0.1;
      r.pairs.push_back(std::make_unique<sim::contact::ContactPair>(sim::contact::MakeContactPair(
          mesh, mesh.part_names[p] + ".outer", "inner_ring.outer", k, sec.thickness, c)));
      r.solver->AddContributor(r.pairs.back().get());
    }
  }
  return r;
}

void ExpectBitIdentical(bool with_contact) {
  sim::solver::EngineBenchmarkOptions o;
  o.elements = 3000;
  const sim::fe::Mesh mesh = sim::solver::MakeBenchmarkMesh(o);
  ASSERT_GT(mesh.num_elements(), 4 * sim::fe::QuadElements::kBlockSize);
  ASSERT_GT(mesh.num_nodes(), 2 * sim::fe::QuadElements::kGatherChunk);
  Run a = Build(mesh, 1, with_contact), b = Build(mesh, 2, with_contact),
      c = Build(mesh, 3, with_contact);
  // Few steps: extra threads spin at barriers on a busy 2-core machine.
  for (int k = 0; k < 120; ++k) a.solver->Step(), b.solver->Step(), c.solver->Step();
  const auto &sa = a.solver->state(), &sb = b.solver->state(), &sc = c.solver->state();
  for (size_t i = 0; i < sa.size(); ++i) {
    ASSERT_EQ(sa.x[i], sb.x[i]) << i;
    ASSERT_EQ(sa.y[i], sc.y[i]) << i;
    ASSERT_EQ(sa.vx[i], sc.vx[i]) << i;
    ASSERT_EQ(sa.vy[i], sb.vy[i]) << i;
  }
  const sim::solver::Energies ea = a.solver->energies(), eb = b.solver->energies(),
                              ec = c.solver->energies();
  EXPECT_EQ(ea.internal, eb.internal);
  EXPECT_EQ(ea.hourglass, ec.hourglass);
  EXPECT_EQ(ea.damping, eb.damping);
  EXPECT_EQ(ea.contact, ec.contact);
  EXPECT_EQ(ea.external, eb.external);
  EXPECT_EQ(a.solver->time(), c.solver->time());
  // The run did something: strain energy, and contact when the pairs are on.
  EXPECT_GT(ea.internal, 0.0);
  if (with_contact) {
    EXPECT_GT(ea.contact, 0.0);
  }
  // Energy balance of the fused paths stays small.
  EXPECT_LT(ea.BalanceError(), 0.05);
}

TEST(FePerf, BitIdenticalAcrossThreadsWithContactAndDamping) { ExpectBitIdentical(true); }

TEST(FePerf, BitIdenticalAcrossThreadsFusedGather) { ExpectBitIdentical(false); }

TEST(FePerf, FusedForcesEqualSeparatePasses) {
  sim::fe::RectangleSpec spec;
  spec.width = 0.03, spec.height = 0.01, spec.nx = 60, spec.ny = 20;
  const sim::fe::Mesh mesh = sim::fe::MakeRectangle("block", spec);
  sim::fe::QuadElements a(mesh, {sim::fe::Section{}}), b(mesh, {sim::fe::Section{}});
  a.set_stiffness_damping(1e-7), b.set_stiffness_damping(1e-7);
  sim::fe::NodalState s;
  s.Resize(mesh.num_nodes());
  s.x0 = s.x = mesh.x, s.y0 = s.y = mesh.y;
  for (int i = 0; i < mesh.num_nodes(); ++i) {  // a smooth deformation plus noise-like terms
    s.vx[i] = 0.3 * std::sin(300.0 * mesh.y[i]) + 0.01 * std::cos(7e3 * mesh.x[i] * mesh.y[i]);
    s.vy[i] = -0.2 * std::cos(200.0 * mesh.x[i]);
  }
  sim::fe::NodalState t = s;
  for (int step = 0; step < 5; ++step) {
    const double h = step == 0 ? 0.0 : 1e-8;
    const double dt_a = a.ComputeForces(&s, h, 2);
    const double dt_b = b.ComputeCornerForces(t, h, 1);
    b.GatherForces(&t, 1);
    ASSERT_EQ(dt_a, dt_b);
    for (int i = 0; i < mesh.num_nodes(); ++i) {
      ASSERT_EQ(s.fx[i], t.fx[i]) << i;
      ASSERT_EQ(s.fy[i], t.fy[i]) << i;
      s.x[i] += 1e-8 * s.vx[i], s.y[i] += 1e-8 * s.vy[i];
      t.x[i] += 1e-8 * t.vx[i], t.y[i] += 1e-8 * t.vy[i];
    }
  }
  EXPECT_EQ(a.InternalEnergy(), b.InternalEnergy());
  EXPECT_EQ(a.HourglassEnergy(), b.HourglassEnergy());
  EXPECT_EQ(a.DampingEnergy(), b.DampingEnergy());
  EXPECT_GT(a.InternalEnergy(), 0.0);
}

TEST(FePerf, StableStepOfASquareIsSideOverRootTwoOverWaveSpeed) {
  sim::fe::RectangleSpec spec;
  spec.width = 2e-3, spec.height = 1e-3, spec.nx = 2, spec.ny = 1;  // two 1 mm squares
  const sim::fe::Mesh mesh = sim::fe::MakeRectangle("sq", spec);
  sim::fe::Section sec;
  sim::fe::QuadElements el(mesh, {sec});
  sim::fe::NodalState s;
  s.Resize(mesh.num_nodes());
  s.x0 = s.x = mesh.x, s.y0 = s.y = mesh.y;
  // L_e = A / max(side, diagonal) = a^2 / (a sqrt 2) = a / sqrt 2.
  const double dt_e = 1e-3 / std::sqrt(2.0) / sec.WaveSpeed();
  EXPECT_NEAR(el.ComputeCornerForces(s, 0.0, 1), dt_e, 1e-14 * dt_e);
  const double beta = 0.3 * dt_e, xi = beta / dt_e;
  el.set_stiffness_damping(beta);
  EXPECT_NEAR(
      el.ComputeCornerForces(s, 0.0, 1), dt_e * (std::sqrt(1.0 + xi * xi) - xi), 1e-14 * dt_e);
}

TEST(FePerf, GatherCountsNodesSharedByMoreThanFourElements) {
  // Six quads around a centre node (valence 6: two slots go through the overflow list).
  sim::fe::Mesh mesh;
  mesh.x = {0.0}, mesh.y = {0.0};
  const double kPi = 3.14159265358979323846;
  for (int k = 0; k < 12; ++k)
    mesh.x.push_back(1e-3 * std::cos(kPi * k / 6)), mesh.y.push_back(1e-3 * std::sin(kPi * k / 6));
  for (int q = 0; q < 6; ++q) {
    mesh.quads.push_back({0, 1 + 2 * q, 2 + 2 * q, 1 + (2 * q + 2) % 12});
    mesh.element_part.push_back(0);
  }
  mesh.part_names = {"star"};
  sim::fe::QuadElements el(mesh, {sim::fe::Section{}});
  sim::fe::NodalState s;
  s.Resize(mesh.num_nodes());
  s.x0 = s.x = mesh.x, s.y0 = s.y = mesh.y;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    s.vx[i] = 0.5 * mesh.y[i] / 1e-3 + 0.2 * (i % 3), s.vy[i] = 0.3 * (i % 2) - 0.1 * (i % 5);
  el.ComputeForces(&s, 0.0, 1);
  for (int i = 0; i < mesh.num_nodes(); ++i) s.x[i] += 1e-8 * s.vx[i], s.y[i] += 1e-8 * s.vy[i];
  el.ComputeForces(&s, 1e-8, 1);
  // Internal forces are self-equilibrated: they sum to zero only if every corner is gathered.
  double sx = 0.0, sy = 0.0, scale = 0.0;
  for (int i = 0; i < mesh.num_nodes(); ++i)
    sx += s.fx[i], sy += s.fy[i], scale = std::max(scale, std::abs(s.fx[i]) + std::abs(s.fy[i]));
  ASSERT_GT(scale, 0.0);
  EXPECT_NEAR(sx, 0.0, 1e-12 * scale);
  EXPECT_NEAR(sy, 0.0, 1e-12 * scale);
  // The centre node's force is a real sum over six elements, not four.
  EXPECT_GT(std::abs(s.fx[0]) + std::abs(s.fy[0]), 1e-6 * scale);
}

}  // namespace
}  // namespace spallkit
