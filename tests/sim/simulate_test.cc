// spall simulate pieces: the rigid-cage and tie constraints (analytic checks), the HDF5 layout,
// checkpoint/resume identity and the CLI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/checkpoint_io.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "core/record_io.h"
#include "sim/bearing/constraints.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"
#include "sim/fe/mesh_primitives.h"
#include "sim/solver/explicit_solver.h"
#include "tests/apps/run_spall.h"
#include "tests/sim/same_datasets.h"

namespace spallkit::sim {
namespace {

// A couple of magnitude f |b - a| that turns with the segment a-b (follower forces).
class FollowerCouple : public solver::ForceContributor {
 public:
  FollowerCouple(int a, int b, double f) : a_(a), b_(b), f_(f) {}
  void AddForces(fe::NodalState& s, double, double) override {
    const double dx = s.x[b_] - s.x[a_], dy = s.y[b_] - s.y[a_], l = std::hypot(dx, dy);
    const double px = -dy / l, py = dx / l;
    s.fx[b_] += f_ * px, s.fy[b_] += f_ * py, s.fx[a_] -= f_ * px, s.fy[a_] -= f_ * py;
  }
  std::string Name() const override { return "couple"; }

 private:
  int a_, b_;
  double f_;
};

// Applies constant nodal forces (a couple or a load).
class NodalLoad : public solver::ForceContributor {
 public:
  NodalLoad(std::vector<int> nodes, std::vector<double> fx, std::vector<double> fy)
      : nodes_(std::move(nodes)), fx_(std::move(fx)), fy_(std::move(fy)) {}
  void AddForces(fe::NodalState& s, double, double) override {
    for (size_t k = 0; k < nodes_.size(); ++k) s.fx[nodes_[k]] += fx_[k], s.fy[nodes_[k]] += fy_[k];
  }
  std::string Name() const override { return "load"; }

 private:
  std::vector<int> nodes_;
  std::vector<double> fx_, fy_;
};

fe::Section Steel(double t) {
  fe::Section s;
  s.material = {206e9, 0.3, 7850};
  s.thickness = t;
  return s;
}

TEST(RigidPartTest, FreeDiscSpinsUpUnderACoupleExactlyAsARigidBody) {
  fe::DiscSpec d;
  d.radius = 3e-3, d.n_core = 4, d.n_radial = 3;
  const fe::Mesh mesh = fe::MakeDisc("disc", d);
  solver::ExplicitSolver solver(mesh, {Steel(9e-3)});
  // Couple: +y on the rightmost rim node, -y on the leftmost, plus a net force +x.
  int right = 0, left = 0;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (mesh.x[i] > mesh.x[right]) right = i;
    if (mesh.x[i] < mesh.x[left]) left = i;
  }
  const double f = 20.0, fx = 3.0;
  FollowerCouple couple(left, right, f);
  // The net force acts at the centre node (no torque as the disc turns).
  NodalLoad load({mesh.node_sets.at("disc.center")[0]}, {fx}, {0.0});
  RigidPart rigid("disc_rigid", mesh.node_sets.at("disc.all"));
  solver.AddContributor(&couple);
  solver.AddContributor(&load);
  solver.AddContributor(&rigid);
  const RigidPart::Motion m0 = rigid.ComputeMotion(solver.state());
  const double torque = f * (mesh.x[right] - mesh.x[left]);
  const double t_end = 2e-4;
  solver.Run(t_end);
  const double t = solver.time();
  const RigidPart::Motion m = rigid.ComputeMotion(solver.state());
  // omega at v^(n-1/2): T (t - dt/2) / J.
  const double expected = torque * (t - 0.5 * solver.time_step()) / m0.inertia;
  EXPECT_GT(std::abs(expected * t), 0.5);  // turned by more than half a radian
  EXPECT_NEAR(m.omega, expected, 1e-4 * std::abs(expected));
  EXPECT_NEAR(m.vx, fx * (t - 0.5 * solver.time_step()) / m0.mass, 1e-6 * std::abs(m.vx));
  EXPECT_NEAR(m.vy, 0.0, 1e-9);
  // Still rigid: every node at its original distance from the mass centre.
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const double r0 = std::hypot(mesh.x[i] - m0.cx, mesh.y[i] - m0.cy);
    const double r = std::hypot(solver.state().x[i] - m.cx, solver.state().y[i] - m.cy);
    EXPECT_NEAR(r, r0, 1e-8 * d.radius);  // one step's O((omega dt)^2)
  }
  // The constraint does no work: the kinetic energy is the work of the couple and the force.
  const solver::Energies e = solver.energies();
  EXPECT_LT(std::abs(rigid.ExternalWork()), 1e-6 * e.kinetic);
  EXPECT_LT(std::abs(e.internal) + std::abs(e.hourglass), 1e-3 * e.kinetic);
}

TEST(TiedNodesTest, TwoTiedBlocksMoveExactlyLikeOneBlock) {
  const double w = 4e-3, h = 3e-3;
  auto block = [&](const std::string& name, double y0, int ny) {
    fe::RectangleSpec r;
    r.y0 = y0, r.width = w, r.height = h * ny / 4, r.nx = 4, r.ny = ny;
    return fe::MakeRectangle(name, r);
  };
  // Reference: one block of 8 rows. Tied: two blocks of 4 rows with coincident interface nodes.
  const fe::Mesh one = block("a", 0.0, 8);
  const fe::Mesh two = fe::MergeMeshes({block("a", 0.0, 4), block("b", h, 4)});
  auto run = [&](const fe::Mesh& mesh, bool tied, std::vector<double>* top_y) {
    solver::ExplicitSolver solver(mesh, std::vector<fe::Section>(mesh.num_parts(), Steel(1e-2)));
    solver.FixNodes(mesh.node_sets.at("a.bottom"), true, true);
    const std::string top_set = tied ? "b.top" : "a.top";
    const auto& top = mesh.node_sets.at(top_set);
    NodalLoad load(
        top, std::vector<double>(top.size(), 50.0), std::vector<double>(top.size(), -400.0));
    solver.AddContributor(&load);
    std::unique_ptr<TiedNodes> tie;
    if (tied) {
      std::vector<std::pair<int, int>> pairs;
      for (int a : mesh.node_sets.at("a.top"))
        for (int b : mesh.node_sets.at("b.bottom"))
          if (std::hypot(mesh.x[a] - mesh.x[b], mesh.y[a] - mesh.y[b]) < 1e-12)
            pairs.emplace_back(a, b);
      EXPECT_EQ(pairs.size(), 5u);
      tie = std::make_unique<TiedNodes>("tie", pairs);
      solver.AddContributor(tie.get());
    }
    solver.Run(2e-5);
    for (int id : top) top_y->push_back(solver.state().y[id] - mesh.y[id]);
    if (tied)
      for (int a : mesh.node_sets.at("a.top"))
        for (int b : mesh.node_sets.at("b.bottom"))
          if (std::hypot(mesh.x[a] - mesh.x[b], mesh.y[a] - mesh.y[b]) < 1e-12) {
            EXPECT_EQ(solver.state().x[a], solver.state().x[b]);
            EXPECT_EQ(solver.state().y[a], solver.state().y[b]);
          }
    return solver.step();
  };
  std::vector<double> ref, tied;
  const long steps_ref = run(one, false, &ref);
  const long steps_tied = run(two, true, &tied);
  EXPECT_EQ(steps_ref, steps_tied);
  ASSERT_EQ(ref.size(), tied.size());
  double scale = 0.0;
  for (double v : ref) scale = std::max(scale, std::abs(v));
  EXPECT_GT(scale, 1e-8);
  for (size_t i = 0; i < ref.size(); ++i) EXPECT_NEAR(tied[i], ref[i], 1e-9 * scale);
}

// The roller-guided cage: a roller disc launched radially out of its pocket's play band comes
// back elastically, two-body spring physics: overtravel v sqrt(mu / k), peak force v sqrt(k mu)
// (mu the reduced mass), momentum kept, and the guide's work ledger balances. The cage (a rigid
// annulus) spins, so the pocket direction turns under the roller and the torque part is used.
TEST(CagePocketGuideTest, RollerBouncesElasticallyOffThePlayLimitOfASpinningCage) {
  fe::AnnulusSpec a;
  a.inner_radius = 8e-3, a.outer_radius = 10e-3, a.n_theta = 48, a.n_radial = 2;
  fe::DiscSpec d;
  d.cx = 5e-3, d.cy = 0.8e-3, d.radius = 1.5e-3, d.n_core = 2, d.n_radial = 2;
  const fe::Mesh mesh = fe::MergeMeshes({fe::MakeAnnulus("cage", a), fe::MakeDisc("roller", d)});
  solver::SolverOptions so;
  so.track_contributor_work = true;
  solver::ExplicitSolver solver(mesh, {Steel(9e-3), Steel(9e-3)}, so);
  const auto& cage_nodes = mesh.node_sets.at("cage.all");
  const auto& roller_nodes = mesh.node_sets.at("roller.all");
  // The "pocket": the cage nodes within 20 degrees of +x (centre line along +x at the start).
  std::vector<int> pocket;
  for (int id : cage_nodes)
    if (std::abs(std::atan2(mesh.y[id], mesh.x[id])) < 20.0 * M_PI / 180.0) pocket.push_back(id);
  CageGuideOptions opt;
  opt.radial_play_m = 0.2e-3, opt.stiffness_n_per_m = 1e7;
  const double pitch = 5e-3, v0 = 0.5, spin = 20.0;  // m/s outwards; rad/s
  CagePocketGuide guide("guide", {roller_nodes}, {pocket}, cage_nodes, pitch, opt);
  RigidPart rigid("cage_rigid", cage_nodes);
  solver.AddContributor(&guide);
  solver.AddContributor(&rigid);
  solver.SetRigidVelocity(cage_nodes, 0.0, 0.0, spin, 0.0, 0.0);
  // The roller sits 0.8 mm off the pocket's centre line (so the force has a moment about the
  // cage centre) and moves with the cage there, plus v0 outwards.
  solver.SetRigidVelocity(roller_nodes, v0 - spin * d.cy, spin * d.cx, 0.0, 0.0, 0.0);
  double m_cage = 0, m_roller = 0;
  for (int id : cage_nodes) m_cage += solver.state().mass[id];
  for (int id : roller_nodes) m_roller += solver.state().mass[id];
  const double mu = m_cage * m_roller / (m_cage + m_roller);
  // Rate of the guide's radial coordinate (c_r - c_cage) . e: (v_r - v_cage) . e plus the turn
  // of e (omega e_perp) seen from the roller's offset.
  auto radial_velocity = [&] {
    const RigidPart::Motion c = rigid.ComputeMotion(solver.state());
    double px = 0, py = 0, pm = 0, rx = 0, ry = 0, vx = 0, vy = 0;
    for (int id : pocket) {
      const double m = solver.state().mass[id];
      pm += m, px += m * solver.state().x[id], py += m * solver.state().y[id];
    }
    for (int id : roller_nodes) {
      const double m = solver.state().mass[id] / m_roller;
      rx += m * solver.state().x[id], ry += m * solver.state().y[id];
      vx += m * solver.state().vx[id], vy += m * solver.state().vy[id];
    }
    double ex = px / pm - c.cx, ey = py / pm - c.cy;
    const double l = std::hypot(ex, ey);
    ex /= l, ey /= l;
    const double dx = rx - c.cx, dy = ry - c.cy;
    return (vx - c.vx) * ex + (vy - c.vy) * ey + c.omega * (-dx * ey + dy * ex);
  };
  const double v_start = radial_velocity();
  double peak = 0.0;
  // Free flight to the play limit (0.4 ms), contact about pi sqrt(mu / k) = 0.16 ms, back.
  const double t_end = 2.0 * opt.radial_play_m / v0 + M_PI * std::sqrt(mu / opt.stiffness_n_per_m);
  while (solver.time() < t_end) {
    solver.Step();
    peak = std::max(peak, guide.Force(0));
  }
  EXPECT_NEAR(v_start, v0, 0.01 * v0);
  EXPECT_NEAR(radial_velocity(), -v0, 0.01 * v0);
  EXPECT_NEAR(peak, v0 * std::sqrt(opt.stiffness_n_per_m * mu), 0.02 * peak);
  EXPECT_EQ(guide.Force(0), 0.0);  // back inside the play band
  // Linear momentum: the guide's forces are internal.
  double px = 0, py = 0;
  for (size_t i = 0; i < solver.state().size(); ++i)
    px += solver.state().mass[i] * solver.state().vx[i],
        py += solver.state().mass[i] * solver.state().vy[i];
  EXPECT_NEAR(px, m_roller * (v0 - spin * d.cy), 1e-6 * m_roller * v0);
  EXPECT_NEAR(py, m_roller * spin * d.cx, 1e-6 * m_roller * v0);
  // The guide's books: work done = - (stored now) within 0.1 % of the energy it exchanged.
  const double exchanged = 0.5 * mu * v0 * v0;
  for (const solver::ContributorLedger& l : solver.ContributorLedgers()) {
    if (l.name == "guide") {
      EXPECT_NEAR(l.Created(), 0.0, 1e-3 * exchanged);
    }
  }
  EXPECT_LT(solver.energies().BalanceError(), 1e-3);
}

// A coarse healthy scene that runs in seconds: 1 mm elements, 0.9 mm along contact surfaces.
std::vector<std::string> CoarseSets(double duration_s) {
  return {"mesh.size_mm=1.0",
          "mesh.contact_size_mm=0.9",
          "mesh.adapter_size_mm=2.0",
          "defects=[]",
          "operation.ramp_s=0.0002",
          "run.output_rate_hz=50000",
          "run.duration_s=" + std::to_string(duration_s)};
}

std::string Scenes() { return std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/"; }

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "spallkit_simulate_" + name;
}

TEST(SimulateTest, WritesTheDocumentedHdf5Layout) {
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml", CoarseSets(2e-4));
  SimulationOptions o;
  o.output_path = TempPath("layout.h5");
  o.csv_path = TempPath("layout.csv");
  Simulation sim(scene, o);
  const SimulationSummary s = sim.Run();
  ASSERT_TRUE(s.completed);
  EXPECT_GT(s.steps, 1000);
  EXPECT_LT(s.energy_balance_error, 0.01);

  h5::File f = h5::File::OpenReadOnly(o.output_path);
  EXPECT_EQ(f.ReadStringAttribute("/", "scene").value(), scene.effective_toml);
  EXPECT_EQ(f.ReadStringAttribute("/", "spallkit_version").value(), SPALLKIT_VERSION);
  EXPECT_EQ(f.ReadStringAttribute("/", "mesh_quality").value(),
            sim.model().mesh_quality().Report());
  const int n = 11;  // 0.2 ms at 50 kHz, both ends
  const int z = 13;
  std::vector<size_t> dims;
  EXPECT_EQ(f.ReadDataset("/time", &dims).size(), static_cast<size_t>(n));
  for (const char* p : {"/signals/accel_y",
                        "/signals/accel_z",
                        "/cage/omega",
                        "/cage/slip_ratio",
                        "/energy/kinetic",
                        "/energy/internal",
                        "/energy/hourglass",
                        "/energy/contact",
                        "/energy/friction",
                        "/energy/damping",
                        "/energy/external",
                        "/energy/balance_error"}) {
    SCOPED_TRACE(p);
    EXPECT_EQ(f.DatasetDims(p), std::vector<size_t>{static_cast<size_t>(n)});
    EXPECT_TRUE(f.ReadStringAttribute(p, "units").has_value());
    EXPECT_EQ(f.ReadDoubleAttribute(p, "sample_rate_hz").value(), 50000.0);
  }
  for (const char* p : {"/contact/roller_outer",
                        "/contact/roller_inner",
                        "/contact/roller_cage",
                        "/rollers/spin",
                        "/rollers/orbit_angle"}) {
    SCOPED_TRACE(p);
    EXPECT_EQ(f.DatasetDims(p),
              (std::vector<size_t>{static_cast<size_t>(n), static_cast<size_t>(z)}));
  }
  // The cage's mass centre, (x, y) per sample, in metres; it starts on the bearing's centre.
  EXPECT_EQ(f.DatasetDims("/cage/centre"),
            (std::vector<size_t>{static_cast<size_t>(n), static_cast<size_t>(2)}));
  EXPECT_EQ(f.ReadStringAttribute("/cage/centre", "units").value(), "m");
  const auto centre = f.ReadDataset("/cage/centre");
  EXPECT_NEAR(centre[0], 0.0, 1e-9);
  EXPECT_NEAR(centre[1], 0.0, 1e-9);
  EXPECT_EQ(f.ReadStringAttribute("/contact/roller_outer", "units").value(), "N");
  EXPECT_EQ(f.ReadStringAttribute("/signals/accel_y", "units").value(), "m/s^2");
  // Orbit angles start at the mesher's roller angles: roller 0 on the load line (-pi/2).
  const auto orbit = f.ReadDataset("/rollers/orbit_angle");
  EXPECT_NEAR(orbit[0], -M_PI / 2, 1e-9);
  EXPECT_NEAR(orbit[1], -M_PI / 2 + 2 * M_PI / z, 1e-9);
  // The CSV carries the same acceleration for spall diagnose.
  const spallkit::Record csv = spallkit::ReadCsvRecord(o.csv_path);
  EXPECT_EQ(csv.samples, f.ReadDataset("/signals/accel_y"));
  EXPECT_NEAR(csv.sample_rate_hz, 50000.0, 1e-6);
  std::remove(o.output_path.c_str());
  std::remove(o.csv_path.c_str());
}

TEST(SimulateTest, OutputsNotAskedForAreNotWritten) {
  std::vector<std::string> sets = CoarseSets(5e-5);
  sets.push_back("run.outputs=[\"cage\"]");
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml", sets);
  SimulationOptions o;
  o.output_path = TempPath("partial.h5");
  Simulation(scene, o).Run();
  h5::File f = h5::File::OpenReadOnly(o.output_path);
  EXPECT_EQ(f.ListDatasets(),
            (std::vector<std::string>{"/cage/centre", "/cage/omega", "/cage/slip_ratio", "/time"}));
  std::remove(o.output_path.c_str());
}

// Skip what is not needed: with neither the "energy" output nor the energy guard, no model
// keeps energy books (the rigid rollers', the FE solver's element and nodal terms; the
// summary's balance is NaN and says so), and every recorded signal is bit for bit what the run
// with the books gives. Either reader keeps them.
TEST(SimulateTest, EnergyBooksAreKeptOnlyWhenSomethingReadsThem) {
  for (const char* fidelity : {"lumped", "hybrid", "fe"}) {
    SCOPED_TRACE(fidelity);
    const bool fe = std::string(fidelity) == "fe";
    auto run = [&](const char* name, std::vector<std::string> extra) {
      std::vector<std::string> sets = {std::string("model.fidelity=") + fidelity,
                                       "mesh.size_mm=2.0",
                                       "operation.ramp_s=0.002",
                                       fe ? "run.duration_s=0.0005" : "run.duration_s=0.004",
                                       fe ? "defects=[]" : "friction.model=ehl"};
      sets.insert(sets.end(), extra.begin(), extra.end());
      SimulationOptions o;
      o.output_path = TempPath(std::string(fidelity) + "_" + name + ".h5");
      const SimulationSummary sum =
          Simulation(LoadScene(Scenes() + "paper-verification.toml", sets), o).Run();
      return std::make_pair(o.output_path, sum.energy_balance_error);
    };
    const std::string no_energy =
        "run.outputs=[\"contact_forces\",\"acceleration\",\"cage\",\"rollers\"]";
    const auto [books_path, books_error] =
        run("books", {no_energy, "solver.max_energy_error_percent=5"});
    const auto [output_path, output_error] = run("output", {"solver.max_energy_error_percent=0"});
    const auto [none_path, none_error] =
        run("none", {no_energy, "solver.max_energy_error_percent=0"});
    EXPECT_TRUE(std::isfinite(books_error));   // the guard reads them
    EXPECT_TRUE(std::isfinite(output_error));  // the output reads them
    EXPECT_LT(books_error, 1e-3);
    EXPECT_TRUE(std::isnan(none_error));
    spallkit::testing::ExpectSameDatasets(books_path, none_path, 9);
    for (const std::string& p : {books_path, output_path, none_path}) std::remove(p.c_str());
  }
}

TEST(SimulateTest, ResumedRunIsBitIdenticalToAnUninterruptedOne) {
  std::vector<std::string> sets = CoarseSets(3e-4);
  sets.push_back("solver.checkpoint_interval_s=0.0001");
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml", sets);
  SimulationOptions a;
  a.output_path = TempPath("straight.h5");
  const SimulationSummary sa = Simulation(scene, a).Run();
  ASSERT_TRUE(sa.completed);

  SimulationOptions b;
  b.output_path = TempPath("resumed.h5");
  b.stop_after_s = 1.5e-4;  // between checkpoints: the stop writes its own
  {
    const SimulationSummary s1 = Simulation(scene, b).Run();
    EXPECT_FALSE(s1.completed);
    std::ifstream ckpt(b.output_path + ".ckpt");
    EXPECT_TRUE(ckpt.good());
  }
  b.stop_after_s = std::numeric_limits<double>::infinity();
  b.resume = true;
  const SimulationSummary s2 = Simulation(scene, b).Run();
  ASSERT_TRUE(s2.completed);
  EXPECT_TRUE(s2.resumed);
  EXPECT_EQ(s2.steps, sa.steps);

  testing::ExpectSameDatasets(a.output_path, b.output_path);
  // A checkpoint of another scene is refused.
  std::vector<std::string> other = sets;
  other.push_back("operation.radial_load_n=5000");
  SimulationOptions c = b;
  {
    SimulationOptions stop = b;
    stop.resume = false, stop.stop_after_s = 1e-4;
    Simulation(scene, stop).Run();
  }
  const Scene other_scene = LoadScene(Scenes() + "paper-verification.toml", other);
  EXPECT_THROW(Simulation(other_scene, c).Run(), spallkit::InputError);
  std::remove((b.output_path + ".ckpt").c_str());
  std::remove(a.output_path.c_str());
  std::remove(b.output_path.c_str());
}

// A checkpoint another build wrote, whose state no longer fits the model (the state layouts
// change between builds), or one of the format before the version was recorded, is refused with
// one line naming the file, whose build wrote it, and what to do.
TEST(SimulateTest, CheckpointOfAnotherBuildIsRefusedWithWhatToDo) {
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml",
                                {"model.fidelity=lumped", "run.duration_s=0.002"});
  SimulationOptions o;
  o.output_path = TempPath("other_build.h5");
  o.stop_after_s = 1e-3;
  EXPECT_FALSE(Simulation(scene, o).Run().completed);
  const std::string ckpt = o.output_path + ".ckpt";
  std::string bytes;
  {
    std::ifstream in(ckpt, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 8u);
  auto resume_error = [&](const std::string& file_bytes) {
    std::ofstream(ckpt, std::ios::binary | std::ios::trunc) << file_bytes;
    SimulationOptions r = o;
    r.resume = true, r.stop_after_s = std::numeric_limits<double>::infinity();
    try {
      Simulation(scene, r).Run();
    } catch (const spallkit::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  // The model's state one value short, as an older build's layout would be.
  CheckpointReader in(std::string_view(bytes).substr(8), "test");
  const std::string version = in.GetBytes(), toml = in.GetBytes(), model = in.GetBytes(),
                    recorder = in.GetBytes();
  EXPECT_EQ(version, SPALLKIT_VERSION);
  CheckpointWriter out;
  for (char c : bytes.substr(0, 8)) out.Put(c);
  out.PutBytes("0.0.1");
  out.PutBytes(toml);
  out.PutBytes(model.substr(0, model.size() - 8));
  out.PutBytes(recorder);
  const std::string short_state = resume_error(out.bytes());
  EXPECT_EQ(short_state.find(ckpt), 0u) << short_state;
  EXPECT_NE(short_state.find("written by spallkit 0.0.1"), std::string::npos) << short_state;
  EXPECT_NE(short_state.find("run again without --resume"), std::string::npos) << short_state;
  std::string format01 = bytes;
  format01[7] = '1';
  const std::string old = resume_error(format01);
  EXPECT_NE(old.find("older spallkit"), std::string::npos) << old;
  EXPECT_NE(old.find("run again without --resume"), std::string::npos) << old;
  std::remove(ckpt.c_str());
  std::remove(o.output_path.c_str());
}

TEST(SimulateTest, HybridResumedRunIsBitIdenticalToAnUninterruptedOne) {
  // The hybrid model's rigid bodies, friction springs and energies travel in the checkpoint
  // (RollerContacts::SaveState): a run stopped after the spall's first contacts and resumed
  // must write exactly the datasets of the uninterrupted run. 6000 rpm with the spall so that
  // every state variable (friction springs, cage contacts) is live; a second, half-length spall
  // on roller 1 brings the intact part's friction springs in.
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml",
                                {"model.fidelity=hybrid",
                                 "defects.1.roller=1",
                                 "defects.1.length_mm=4.5",
                                 "mesh.size_mm=2.0",
                                 "operation.speed_rpm=6000",
                                 "operation.ramp_s=0.001",
                                 "run.duration_s=0.003",
                                 "run.outputs=[\"contact_forces\", \"acceleration\", \"cage\", "
                                 "\"rollers\", \"energy\", \"field\"]",
                                 "run.field_rate_hz=2000",
                                 "solver.checkpoint_interval_s=0.001"});
  SimulationOptions a;
  a.output_path = TempPath("hybrid_straight.h5");
  const SimulationSummary sa = Simulation(scene, a).Run();
  ASSERT_TRUE(sa.completed);
  SimulationOptions b;
  b.output_path = TempPath("hybrid_resumed.h5");
  b.stop_after_s = 1.7e-3;
  EXPECT_FALSE(Simulation(scene, b).Run().completed);
  b.stop_after_s = std::numeric_limits<double>::infinity();
  b.resume = true;
  const SimulationSummary s2 = Simulation(scene, b).Run();
  ASSERT_TRUE(s2.completed);
  EXPECT_TRUE(s2.resumed);
  EXPECT_EQ(s2.steps, sa.steps);
  testing::ExpectSameDatasets(a.output_path, b.output_path);
  h5::File fa = h5::File::OpenReadOnly(a.output_path);
  // The run did reach the contacts (not a trivially idle model).
  const auto outer = fa.ReadDataset("/contact/roller_outer");
  double peak = 0;
  for (double v : outer) peak = std::max(peak, v);
  EXPECT_GT(peak, 2000.0);
  std::remove((b.output_path + ".ckpt").c_str());
  std::remove(a.output_path.c_str());
  std::remove(b.output_path.c_str());
}

// The "field" output: the von Mises stress of every element of the stepped mesh (the hybrid's
// outer ring and adapter) at run.field_rate_hz, with the mesh it lives on. The bearing at rest
// under the ramped 10 kN load: no stress at t = 0; at the end the outer ring is stressed most in
// the load zone (within 45 deg of the load line, where the rollers press it) and little at the
// top. The lumped model, which steps no mesh, refuses the output.
TEST(SimulateTest, FieldOutputHoldsTheHousingStressWhereTheRollersPress) {
  const Scene scene = LoadScene(Scenes() + "paper-verification.toml",
                                {"model.fidelity=hybrid",
                                 "mesh.size_mm=2.0",
                                 "operation.speed_rpm=0",
                                 "run.duration_s=0.008",
                                 "run.outputs=[\"field\"]"});
  SimulationOptions o;
  o.output_path = TempPath("field.h5");
  ASSERT_TRUE(Simulation(scene, o).Run().completed);
  h5::File f = h5::File::OpenReadOnly(o.output_path);
  const auto vm = f.ReadDataset("/field/von_mises");
  const auto nodes = f.ReadDataset("/field/nodes");
  const auto elements = f.ReadDataset("/field/elements");
  const auto part = f.ReadDataset("/field/part");
  const auto t = f.ReadDataset("/field/time");
  const size_t ne = part.size();
  ASSERT_EQ(t.size(), 9u);  // 1 kHz over 8 ms, both ends
  ASSERT_EQ(vm.size(), t.size() * ne);
  ASSERT_EQ(elements.size(), 4 * ne);
  for (size_t e = 0; e < ne; ++e) EXPECT_EQ(vm[e], 0.0);
  double peak = 0, peak_angle = 0, top = 0, top_distance = 1e9;
  for (size_t e = 0; e < ne; ++e) {
    if (part[e] != 0) continue;  // outer_ring
    double cx = 0, cy = 0;
    for (int c = 0; c < 4; ++c) {
      const int n = static_cast<int>(elements[4 * e + c]);
      cx += 0.25 * nodes[2 * n], cy += 0.25 * nodes[2 * n + 1];
    }
    const double angle = std::atan2(cy, cx) * 180.0 / kPi;
    const double s = vm[(t.size() - 1) * ne + e];
    if (s > peak) peak = s, peak_angle = angle;
    if (std::abs(angle - 90.0) < top_distance) top_distance = std::abs(angle - 90.0), top = s;
  }
  std::printf("outer ring von Mises: peak %.1f MPa at %.1f deg, top %.1f MPa\n",
              peak / 1e6,
              peak_angle,
              top / 1e6);
  EXPECT_LT(std::abs(peak_angle + 90.0), 45.0);
  EXPECT_GT(peak, 10e6);
  EXPECT_LT(top, 0.2 * peak);
  std::remove(o.output_path.c_str());

  const Scene lumped = LoadScene(Scenes() + "paper-verification.toml",
                                 {"model.fidelity=lumped", "run.outputs=[\"field\"]"});
  EXPECT_THROW(Simulation(lumped, {}), spallkit::InputError);
}

// A run whose energy balance error passes solver.max_energy_error_percent stops with a
// NumericalError naming the key and writes nothing (the full-FE section above its speed range
// reaches 7.8 % by 6.75 ms: docs/BEARING_MODEL.md). Here the same hybrid run is judged against
// the default limit (passes: its error is ~0.01 %) and against a limit below its error.
TEST(SimulateTest, RunPastTheEnergyErrorLimitStopsAndWritesNothing) {
  const std::vector<std::string> sets = {"model.fidelity=hybrid",
                                         "mesh.size_mm=2.0",
                                         "operation.ramp_s=0.001",
                                         "run.duration_s=0.002"};
  SimulationOptions o;
  o.output_path = TempPath("energy_limit.h5");
  const SimulationSummary ok =
      Simulation(LoadScene(Scenes() + "paper-verification.toml", sets), o).Run();
  ASSERT_TRUE(ok.completed);
  ASSERT_GT(ok.energy_balance_error, 1e-8);
  ASSERT_LT(ok.energy_balance_error, 0.05);
  std::remove(o.output_path.c_str());

  std::vector<std::string> strict = sets;
  strict.push_back("solver.max_energy_error_percent=" +
                   std::to_string(0.1 * 100.0 * ok.energy_balance_error));
  o.model.track_contributor_work = true;  // the message then names the worst account
  try {
    Simulation(LoadScene(Scenes() + "paper-verification.toml", strict), o).Run();
    FAIL() << "expected a NumericalError";
  } catch (const spallkit::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("solver.max_energy_error_percent"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("most energy created by '"), std::string::npos)
        << e.what();
  }
  std::ifstream written(o.output_path);
  EXPECT_FALSE(written.good()) << o.output_path << " was written";
}

using spallkit::testing::RunSpall;

TEST(SimulateCliTest, PrintsTheSummaryAndWritesFiles) {
  std::string sets;
  for (const std::string& s : CoarseSets(1e-4)) sets += " --set '" + s + "'";
  int code = -1;
  const std::string h5 = TempPath("cli.h5"), csv = TempPath("cli.csv");
  const std::string out = RunSpall(
      "simulate " + Scenes() + "paper-verification.toml -o " + h5 + " --csv " + csv + sets, &code);
  EXPECT_EQ(code, 0) << out;
  for (const char* key : {"steps",
                          "time step",
                          "wall time",
                          "ns per element-cycle",
                          "energy balance error",
                          "hourglass/internal",
                          "mesh quality:",
                          "  roller0..12: ",
                          "max skew"})
    EXPECT_NE(out.find(key), std::string::npos) << key << "\n" << out;
  EXPECT_NO_THROW(spallkit::ReadHdf5Record(h5));
  EXPECT_NO_THROW(spallkit::ReadCsvRecord(csv));
  EXPECT_EQ(out.find("energy ledger"), std::string::npos) << out;  // only when asked
  std::remove(h5.c_str());
  std::remove(csv.c_str());

  const std::string ledger = RunSpall(
      "simulate " + Scenes() + "paper-verification.toml --quiet --energy-ledger -o " + h5 + sets,
      &code);
  EXPECT_EQ(code, 0) << ledger;
  EXPECT_NE(ledger.find("energy ledger"), std::string::npos) << ledger;
  EXPECT_NE(ledger.find("roller0.surface/outer_ring.raceway"), std::string::npos) << ledger;
  std::remove(h5.c_str());

  const std::string bad = RunSpall(
      "simulate " + Scenes() + "paper-verification.toml -o " + h5 + " --set mesh.sise_mm=1", &code);
  EXPECT_EQ(code, 2);
  EXPECT_NE(bad.find("spall: error:"), std::string::npos) << bad;
  EXPECT_NE(bad.find("sise_mm"), std::string::npos) << bad;
}

}  // namespace
}  // namespace spallkit::sim
