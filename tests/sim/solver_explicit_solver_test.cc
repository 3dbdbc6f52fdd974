#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/constants.h"
#include "core/error.h"
#include "sim/contact/contact_pair.h"
#include "sim/fe/mesh_primitives.h"
#include "sim/solver/explicit_solver.h"

namespace spallkit::sim::solver {
namespace {

// Inner ring (bore tied to a rigid shaft with prescribed rotation, free translation under a
// radial load) plus a loose disc: exercises elements, damping, constraints and outputs.
struct Model {
  fe::Mesh mesh;
  std::vector<fe::Section> sections;
  Model() {
    fe::AnnulusSpec ring;
    ring.inner_radius = 0.02, ring.outer_radius = 0.026, ring.n_theta = 64, ring.n_radial = 3;
    fe::DiscSpec disc;
    disc.cx = 0.05, disc.radius = 0.005, disc.n_core = 3, disc.n_radial = 3;
    mesh = fe::MergeMeshes({fe::MakeAnnulus("ring", ring), fe::MakeDisc("roller", disc)});
    fe::ReorderForLocality(&mesh);
    fe::Section s;
    s.thickness = 0.01;
    sections = {s, s};
  }
};

std::unique_ptr<ExplicitSolver> Build(const Model& m, int threads, SolverOptions opt = {}) {
  opt.num_threads = threads;
  opt.mass_damping_ratio = 0.05;
  opt.damping_frequency = 5e3;
  opt.stiffness_damping_ratio = 0.01;
  opt.stiffness_damping_frequency = 20e3;
  auto s = std::make_unique<ExplicitSolver>(m.mesh, m.sections, opt);
  RigidBody shaft;
  shaft.name = "shaft";
  shaft.nodes = m.mesh.node_sets.at("ring.inner");
  shaft.angle = RampedRotation(2000.0, 2e-5);
  shaft.force_y = [](double) { return -5e4; };
  shaft.extra_mass = 0.1;
  s->AddRigidBody(shaft);
  s->SetRigidVelocity(m.mesh.node_sets.at("roller.all"), 1.0, 0.5, 300.0, 0.05, 0.0);
  return s;
}

TEST(ExplicitSolver, BitIdenticalAcrossThreadCounts) {
  const Model m;
  auto a = Build(m, 1);
  auto b = Build(m, 2);
  for (int k = 0; k < 300; ++k) a->Step(), b->Step();
  for (size_t i = 0; i < a->state().size(); ++i) {
    ASSERT_EQ(a->state().x[i], b->state().x[i]) << i;
    ASSERT_EQ(a->state().vy[i], b->state().vy[i]) << i;
  }
  EXPECT_EQ(a->energies().internal, b->energies().internal);
  EXPECT_EQ(a->energies().damping, b->energies().damping);
}

// Without the energy terms (SolverOptions::energy_terms off) the element, damping and
// constraint passes skip their sums: the motion is bit for bit the same, the kinetic energy is
// still there, every other term reads NaN (so the balance does too), and what needs the terms
// (the energy guard, the work ledger) is refused up front.
TEST(ExplicitSolver, SkippingTheEnergyTermsLeavesTheMotionBitIdentical) {
  const Model m;
  auto a = Build(m, 1);
  SolverOptions off;
  off.energy_terms = false;
  auto b = Build(m, 1, off);
  for (int k = 0; k < 300; ++k) a->Step(), b->Step();
  for (size_t i = 0; i < a->state().size(); ++i) {
    ASSERT_EQ(a->state().x[i], b->state().x[i]) << i;
    ASSERT_EQ(a->state().vy[i], b->state().vy[i]) << i;
  }
  const Energies ea = a->energies(), eb = b->energies();
  EXPECT_EQ(ea.kinetic, eb.kinetic);
  EXPECT_GT(ea.internal, 0.0);
  EXPECT_GT(ea.damping, 0.0);
  EXPECT_LT(ea.BalanceError(), 1e-2);
  for (double v : {eb.internal, eb.hourglass, eb.damping, eb.external, eb.BalanceError()})
    EXPECT_TRUE(std::isnan(v));
  std::string err;
  off.max_energy_error = 0.01;
  EXPECT_FALSE(off.IsValid(&err));
  EXPECT_NE(err.find("energy_terms"), std::string::npos) << err;
  off.max_energy_error = 0.0;
  off.track_contributor_work = true;
  EXPECT_FALSE(off.IsValid(&err));
  EXPECT_NE(err.find("energy_terms"), std::string::npos) << err;
}

TEST(ExplicitSolver, RestartFromCheckpointIsBitIdentical) {
  const Model m;
  auto full = Build(m, 1);
  for (int k = 0; k < 400; ++k) full->Step();
  auto first = Build(m, 1);
  for (int k = 0; k < 170; ++k) first->Step();
  const std::string path = ::testing::TempDir() + "/solver_checkpoint.bin";
  first->SaveCheckpoint(path);
  auto resumed = Build(m, 1);
  resumed->LoadCheckpoint(path);
  EXPECT_EQ(resumed->step(), 170);
  for (int k = 170; k < 400; ++k) resumed->Step();
  EXPECT_EQ(resumed->time(), full->time());
  for (size_t i = 0; i < full->state().size(); ++i) {
    ASSERT_EQ(resumed->state().x[i], full->state().x[i]) << i;
    ASSERT_EQ(resumed->state().vx[i], full->state().vx[i]) << i;
  }
  EXPECT_EQ(resumed->energies().external, full->energies().external);
  EXPECT_EQ(resumed->rigid_body_state(0).y, full->rigid_body_state(0).y);
  std::remove(path.c_str());
  // A checkpoint of a different model is rejected.
  first->SaveCheckpoint(path);
  fe::RectangleSpec spec;
  ExplicitSolver other(fe::MakeRectangle("b", spec), {fe::Section{}});
  EXPECT_THROW(other.LoadCheckpoint(path), InputError);
  std::remove(path.c_str());
}

TEST(ExplicitSolver, FreeRigidTranslationFollowsNewton) {
  // A disc whose every node is tied to a rigid body: a = F / (m + extra_mass) exactly.
  fe::DiscSpec d;
  d.radius = 0.01;
  const fe::Mesh mesh = fe::MakeDisc("d", d);
  fe::Section sec;
  sec.thickness = 0.02;
  ExplicitSolver s(mesh, {sec});
  RigidBody b;
  b.name = "d";
  b.nodes = mesh.node_sets.at("d.all");
  b.force_x = [](double) { return 100.0; };
  b.extra_mass = 0.5;
  s.AddRigidBody(b);
  s.Run(1e-4);
  const double mass =
      7850 * 0.02 * 0.5 * 16 * std::sin(2 * kPi / 16) * 1e-4 + 0.5;  // polygon disc + extra
  const double t = s.time();
  // Central differences integrate constant acceleration exactly (with the half-step start).
  EXPECT_NEAR(
      s.rigid_body_state(0).x, 0.5 * 100.0 / mass * t * t, 1e-9 * 0.5 * 100.0 / mass * t * t);
  const auto e = s.energies();
  EXPECT_NEAR(
      e.external_loads, e.kinetic, 1e-3 * e.kinetic);  // all load work became kinetic energy
  EXPECT_LT(e.BalanceError(), 1e-3);
}

// A constant force on one node of a free elastic disc, applied by two contributors: one books
// its work as ExternalWork() (honest), one books nothing (the kind of bug the ledger is for).
// The ledger finds the second: its Created() is the work F . dx of the node, the honest one's
// and the elements' are ~0, and the ledgers add up to the global balance error.
class PointForce : public ForceContributor {
 public:
  PointForce(int node, double fx, bool book) : node_(node), fx_(fx), book_(book) {}
  void AddForces(fe::NodalState& s, double, double dt) override {
    s.fx[node_] += fx_;
    if (book_ && have_) work_ += fx_ * (s.x[node_] - x_prev_);  // increment of the last step
    x_prev_ = s.x[node_], have_ = true;
    (void)dt;
  }
  double ExternalWork() const override { return work_; }
  std::string Name() const override { return book_ ? "honest" : "unbooked"; }

 private:
  int node_;
  double fx_;
  bool book_;
  bool have_ = false;
  double x_prev_ = 0.0, work_ = 0.0;
};

// A spring (stiffness k) pulling one node back to where it started along x; books 1/2 k dx^2.
class Tether : public ForceContributor {
 public:
  Tether(int node, double x0, double k) : node_(node), x0_(x0), k_(k) {}
  void AddForces(fe::NodalState& s, double, double) override {
    const double d = s.x[node_] - x0_;
    s.fx[node_] -= k_ * d;
    stored_ = 0.5 * k_ * d * d;
  }
  double StoredEnergy() const override { return stored_; }
  std::string Name() const override { return "tether"; }

 private:
  int node_;
  double x0_, k_, stored_ = 0.0;
};

TEST(ExplicitSolver, WorkLedgerFindsTheContributorThatDoesNotBookItsWork) {
  fe::DiscSpec d;
  d.radius = 0.01, d.n_core = 3, d.n_radial = 2;
  const fe::Mesh mesh = fe::MakeDisc("d", d);
  fe::Section sec;
  sec.thickness = 0.01;
  SolverOptions opt;
  opt.track_contributor_work = true;
  ExplicitSolver s(mesh, {sec}, opt);
  const int node = mesh.node_sets.at("d.center")[0];
  PointForce honest(node, 400.0, true), unbooked(node, 200.0, false);
  Tether tether0(node, mesh.x[node], 2e5);
  s.AddContributor(&honest);
  s.AddContributor(&unbooked);
  s.AddContributor(&tether0);
  s.Run(2e-4);
  const double dx = s.state().x[node] - mesh.x[node];
  const auto ledgers = s.ContributorLedgers();
  ASSERT_EQ(ledgers.size(), 4u);
  EXPECT_EQ(ledgers[0].name, "elements");
  EXPECT_EQ(ledgers[2].name, "unbooked");
  const double w = 200.0 * dx;
  ASSERT_GT(w, 1e-4);
  EXPECT_NEAR(ledgers[2].Created(), w, 0.02 * w);
  EXPECT_NEAR(ledgers[1].Created(), 0.0, 0.02 * w);  // the honest one's book lags half a step
  EXPECT_NEAR(ledgers[0].Created(), 0.0, 1e-3 * w);
  const Energies e = s.energies();
  double created = 0.0;
  for (const auto& l : ledgers) created += l.Created();
  EXPECT_NEAR(created, e.BalanceError() * e.Scale(), 0.02 * w);
  const std::string report = LedgerReport(ledgers);
  EXPECT_EQ(report.find("unbooked"), report.find("\n  ") + 3) << report;  // listed first
  // A ledger started after a resume counts from the resume point (baselines taken there).
  const std::string ckpt = ::testing::TempDir() + "spallkit_ledger.ckpt";
  s.SaveCheckpoint(ckpt);
  ExplicitSolver resumed(mesh, {sec}, opt);
  PointForce honest2(node, 400.0, true), unbooked2(node, 200.0, false);
  // The spring is stretched at the resume point: its account starts from that stored energy.
  Tether tether(node, mesh.x[node], 2e5);
  resumed.AddContributor(&honest2);
  resumed.AddContributor(&unbooked2);
  resumed.AddContributor(&tether);
  resumed.LoadCheckpoint(ckpt);
  std::remove(ckpt.c_str());
  const double x_resume = resumed.state().x[node];
  resumed.Run(4e-4);
  const double w2 = 200.0 * (resumed.state().x[node] - x_resume);
  const auto after = resumed.ContributorLedgers();
  ASSERT_EQ(after.size(), 4u);
  EXPECT_GT(after[3].initial_stored, 0.1 * w2);  // stretched when the ledger started
  EXPECT_NEAR(after[3].Created(), 0.0, 0.02 * w2);
  EXPECT_NEAR(after[2].Created(), w2, 0.02 * w2);
  EXPECT_NEAR(after[1].Created(), 0.0, 0.02 * w2);
  EXPECT_NEAR(after[0].Created(), 0.0, 1e-3 * w2);
  // Off by default: no ledgers.
  ExplicitSolver plain(mesh, {sec});
  plain.Run(1e-5);
  EXPECT_TRUE(plain.ContributorLedgers().empty());
}

// A step load on a tethered node of an elastic disc: a (nearly) linear system under a constant
// force, for which central differences conserve the energy measured at t^n (stored energies at
// x^n, kinetic 1/2 m v^(n-1/2) . v^(n+1/2), work up to t^n) to rounding at every step. The
// kinetic energy at v^(n+1/2) would be off by half a step of the elastic forces' power: the
// error that measure gives at a load step's impact in the bearing models, first order in dt.
TEST(ExplicitSolver, EnergyBalanceAtTnHoldsEveryStepUnderAStepLoad) {
  fe::DiscSpec d;
  d.radius = 0.01, d.n_core = 3, d.n_radial = 2;
  const fe::Mesh mesh = fe::MakeDisc("d", d);
  fe::Section sec;
  sec.thickness = 0.01;
  ExplicitSolver s(mesh, {sec});
  const int node = mesh.node_sets.at("d.center")[0];
  PointForce load(node, 400.0, true);  // books F (x^n - x^0): the work up to t^n
  Tether tether(node, mesh.x[node], 2e6);
  s.AddContributor(&load);
  s.AddContributor(&tether);
  double worst = 0.0, worst_staggered = 0.0;
  for (int i = 0; i < 3000; ++i) {
    s.Step();
    const Energies e = s.energies();
    if (e.Scale() < 1e-9) continue;
    worst = std::max(worst, e.BalanceError());
    Energies staggered = e;  // the kinetic energy at v^(n+1/2)
    staggered.kinetic = 0.0;
    const fe::NodalState& st = s.state();
    for (size_t k = 0; k < st.size(); ++k)
      staggered.kinetic += 0.5 * st.mass[k] * (st.vx[k] * st.vx[k] + st.vy[k] * st.vy[k]);
    worst_staggered = std::max(worst_staggered, staggered.BalanceError());
  }
  // Measured: 2.6e-6 (the elements' geometric nonlinearity); at v^(n+1/2): up to 2.
  EXPECT_LT(worst, 2e-5);
  EXPECT_GT(worst_staggered, 0.1);
}

// Two discs that start 10 um inside each other (as a coarse roller vertex starts inside a race
// facet's sag): the penalty spring pushes them apart. Its energy at the first step is initial
// energy, not energy created: the balance counts it (Energies::initial_stored) and it reappears
// as the discs' kinetic energy.
TEST(ExplicitSolver, InitialOverlapIsInitialEnergyNotCreatedEnergy) {
  fe::DiscSpec a, b;
  a.radius = b.radius = 5e-3;
  a.n_core = b.n_core = 4, a.n_radial = b.n_radial = 2;
  b.cx = 10e-3 - 10e-6;  // rim vertices at angle 0 (a) and pi (b) overlap by 10 um
  const fe::Mesh mesh = fe::MergeMeshes({fe::MakeDisc("a", a), fe::MakeDisc("b", b)});
  fe::Section sec;
  sec.thickness = 0.01;
  ExplicitSolver s(mesh, {sec, sec});
  contact::ContactPairOptions o;
  o.penalty_law = contact::PenaltyLaw::kConstant;
  o.constant_stiffness = 1e8;
  o.symmetric = true;
  contact::ContactPair pair(
      contact::MakeContactPair(mesh, "a.outer", "b.outer", {1.0}, sec.thickness, o));
  s.AddContributor(&pair);
  s.Run(2e-4);
  const Energies e = s.energies();
  // Two vertex springs (one per pass), each about 1/2 k (10 um)^2 = 5 mJ.
  EXPECT_GT(e.initial_stored, 5e-3);
  EXPECT_LT(e.initial_stored, 1.5e-2);
  EXPECT_EQ(e.contact, 0.0);  // apart by now
  EXPECT_GT(e.kinetic, 0.5 * e.initial_stored);
  // Measured 0.029 % (the impact's discretisation); without the initial term ~100 %.
  EXPECT_LT(e.BalanceError(), 2e-3);
  Energies without = e;
  without.initial_stored = 0.0;
  EXPECT_GT(without.BalanceError(), 0.5);
}

TEST(ExplicitSolver, InvertedElementErrorSaysWhen) {
  // One corner of a single element driven through the opposite one: the step that finds the
  // inverted element names it and the simulated time (a user sees when the run went wrong).
  fe::RectangleSpec spec;
  spec.width = spec.height = 1e-3;
  ExplicitSolver s(fe::MakeRectangle("b", spec), {fe::Section{}});
  s.state().vx[0] = s.state().vy[0] = 1e4;  // node 0 at (0, 0) towards (1, 1) mm
  try {
    s.Run(1e-6);
    FAIL() << "expected a NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("element 0 (part 0) inverted"), std::string::npos) << what;
    EXPECT_NE(what.find(" at t = "), std::string::npos) << what;
  }
}

TEST(ExplicitSolver, RelativeDampingSparesSpinPlainDampingBrakesIt) {
  fe::DiscSpec d;
  d.radius = 0.005, d.n_core = 4, d.n_radial = 3;
  const fe::Mesh mesh = fe::MakeDisc("roller", d);
  auto spin_after = [&](bool relative, double* balance) {
    SolverOptions opt;
    opt.mass_damping_ratio = 0.02;
    opt.damping_frequency = 1e5;  // D_s = 2.5e4 1/s, decay time 40 us
    opt.damping_relative_to_rigid_motion = relative;
    ExplicitSolver s(mesh, {fe::Section{}}, opt);
    s.SetRigidVelocity(mesh.node_sets.at("roller.all"), 0.0, 0.0, 500.0, 0.0, 0.0);
    s.Run(1e-4);
    double vx, vy, w;
    s.PartRigidMotion(0, &vx, &vy, &w);
    *balance = s.energies().BalanceError();
    return w;
  };
  double b1, b2;
  const double w_rel = spin_after(true, &b1), w_abs = spin_after(false, &b2);
  EXPECT_NEAR(w_rel, 500.0, 0.5);
  // Plain damping: w(t) = w0 exp(-D_s t) = 500 exp(-2.513) = 40.5 rad/s.
  EXPECT_NEAR(w_abs, 500.0 * std::exp(-4 * kPi * 0.02 * 1e5 * 1e-4), 1.0);
  EXPECT_LT(b1, 1e-3);
  EXPECT_LT(b2, 1e-3);
}

TEST(ExplicitSolver, StiffnessDampingShortensStepAndDissipates) {
  fe::RectangleSpec spec;
  spec.width = 0.01, spec.height = 0.01, spec.nx = 4, spec.ny = 4;
  const fe::Mesh mesh = fe::MakeRectangle("b", spec);
  SolverOptions plain, damped;
  damped.stiffness_damping_ratio = 0.05;
  damped.stiffness_damping_frequency = 1e5;
  ExplicitSolver a(mesh, {fe::Section{}}, plain), b(mesh, {fe::Section{}}, damped);
  for (auto* s : {&a, &b})
    for (size_t i = 0; i < s->state().size(); ++i)
      s->state().vx[i] = 0.1 * std::sin(300.0 * s->state().y0[i]);
  a.Run(2e-5);
  b.Run(2e-5);
  const double dt_e = a.time_step() / 0.9;
  const double beta = 0.05 / (kPi * 1e5),
               xi = beta / dt_e;  // xi = beta w_max / 2, w_max = 2 / dt_e
  EXPECT_NEAR(b.time_step(),
              a.time_step() * (std::sqrt(1 + xi * xi) - xi),
              1e-4 * a.time_step());  // geometries differ slightly
  EXPECT_GT(b.energies().damping, 0.0);
  EXPECT_EQ(a.energies().damping, 0.0);
  // Viscous work is taken with v^(n-1/2) (half a step behind the force): O(dt) balance error.
  EXPECT_LT(b.energies().BalanceError(), 1e-2);
}

TEST(ExplicitSolver, OutputCallbackCadenceAndOptionsValidation) {
  fe::RectangleSpec spec;
  SolverOptions opt;
  opt.output_every_steps = 10;
  ExplicitSolver s(fe::MakeRectangle("b", spec), {fe::Section{}}, opt);
  std::vector<long> steps;
  s.SetOutputCallback([&](const ExplicitSolver& sv) { steps.push_back(sv.step()); });
  for (int k = 0; k < 35; ++k) s.Step();
  EXPECT_EQ(steps, (std::vector<long>{0, 10, 20, 30}));
  SolverOptions bad;
  bad.mass_damping_ratio = 0.02;
  std::string err;
  EXPECT_FALSE(bad.IsValid(&err));
  EXPECT_NE(err.find("damping_frequency"), std::string::npos);
  EXPECT_THROW(ExplicitSolver(fe::MakeRectangle("b", spec), {fe::Section{}}, bad), InputError);
}

TEST(ExplicitSolver, RampedRotationHistory) {
  const auto th = RampedRotation(125.66, 5e-3);
  const auto w = RampedSpeed(125.66, 5e-3);
  EXPECT_NEAR(th(2.5e-3), 125.66 * 2.5e-3 * 2.5e-3 / 1e-2, 1e-12);
  EXPECT_NEAR(th(10e-3), 125.66 * 7.5e-3, 1e-12);
  EXPECT_NEAR((th(4e-3 + 1e-9) - th(4e-3 - 1e-9)) / 2e-9, w(4e-3), 1e-4);
}

TEST(ExplicitSolver, LinearRampRisesFromZeroThenHolds) {
  const auto load = LinearRamp(-1e4, 1e-3);
  EXPECT_DOUBLE_EQ(load(0.0), 0.0);
  EXPECT_DOUBLE_EQ(load(0.25e-3), -2.5e3);
  EXPECT_DOUBLE_EQ(load(1e-3), -1e4);
  EXPECT_DOUBLE_EQ(load(5e-3), -1e4);
  const auto step = LinearRamp(-1e4, 0.0);  // no ramp: a step at t = 0
  EXPECT_DOUBLE_EQ(step(0.0), -1e4);
}

}  // namespace
}  // namespace spallkit::sim::solver
