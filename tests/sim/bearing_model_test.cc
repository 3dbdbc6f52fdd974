// The bearing FE model (sim/bearing/model_builder.h): what is built, static equilibrium of the
// loaded section, and the load zone against Harris-Jones.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

#include "sim/bearing/model_builder.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"
#include "sim/quasistatic/harris_jones.h"

namespace spallkit::sim {
namespace {

std::string Scene0() {
  return std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml";
}

// The coarse healthy section most tests here run (1 mm, 0.9 mm along contacts), with mu 0.1 / 0.08
// where `rolling` (the traction the other dynamic tests use; the faceted contact locks at the
// paper's 0.01 on this mesh, the smooth and curved ones roll), plus `extra` overrides.
// What `spall simulate` would warn about for the paper scene with these overrides.
std::vector<std::string> WarningsFor(const std::vector<std::string>& sets) {
  return FeBearingModel(LoadScene(Scene0(), sets)).Warnings();
}

std::vector<std::string> CoarseHealthy(bool rolling, std::vector<std::string> extra) {
  std::vector<std::string> sets = {
      "mesh.size_mm=1.0", "mesh.contact_size_mm=0.9", "mesh.adapter_size_mm=2.0", "defects=[]"};
  if (rolling) sets.insert(sets.end(), {"friction.mu_static=0.1", "friction.mu_dynamic=0.08"});
  sets.insert(sets.end(), extra.begin(), extra.end());
  return sets;
}

// Faceted full-FE rollers lock on their rim facets when mu x facets is small (measured bracket in
// docs/BEARING_MODEL.md): the paper's friction on the 0.5 mm mesh (40 facets) is warned about,
// with the contact size that would do (2 pi r mu / 0.8 = 0.255 mm); mu 0.1 there, the paper's
// 0.25 mm mesh (80 facets), the smooth race contact (the default; it rolls, below) and the
// hybrid's exact circles are not.
TEST(BearingModelTest, WarnsWhenFacetedRollersWouldStandOnTheirFacets) {
  const std::vector<std::string> coarse =
      WarningsFor({"mesh.size_mm=0.5", "model.race_contact=faceted"});
  ASSERT_EQ(coarse.size(), 1u);
  EXPECT_NE(coarse[0].find("40 facets"), std::string::npos) << coarse[0];
  EXPECT_NE(coarse[0].find("<= 0.255"), std::string::npos) << coarse[0];
  EXPECT_TRUE(WarningsFor({"mesh.size_mm=0.5",
                           "model.race_contact=faceted",
                           "friction.mu_static=0.1",
                           "friction.mu_dynamic=0.08"})
                  .empty());
  EXPECT_TRUE(
      WarningsFor({"mesh.size_mm=0.5", "model.race_contact=faceted", "mesh.contact_size_mm=0.25"})
          .empty());
  EXPECT_TRUE(WarningsFor({"mesh.size_mm=0.5"}).empty());  // smooth
  EXPECT_TRUE(WarningsFor({"mesh.size_mm=0.5", "model.race_contact=curved"}).empty());
  EXPECT_TRUE(WarningsFor({"mesh.size_mm=0.5", "model.fidelity=hybrid"}).empty());
}

// The curved race contact on the paper's 0.25 mm rims (80 arcs) has created energy where a loaded
// rim node dents (docs/CONTACT.md, "Curved surfaces"): warned about, pointing at the smooth
// contact (the default, which balances there); the 0.5 mm rims (40 arcs) and the hybrid are not.
TEST(BearingModelTest, WarnsAboutCurvedRaceContactOnFineRims) {
  const std::vector<std::string> fine =
      WarningsFor({"mesh.size_mm=0.5", "mesh.contact_size_mm=0.25", "model.race_contact=curved"});
  ASSERT_EQ(fine.size(), 1u);
  EXPECT_NE(fine[0].find("80 facets"), std::string::npos) << fine[0];
  EXPECT_NE(fine[0].find("race_contact = \"smooth\""), std::string::npos) << fine[0];
  EXPECT_TRUE(WarningsFor({"mesh.size_mm=0.5", "mesh.contact_size_mm=0.25"}).empty());
  EXPECT_TRUE(
      WarningsFor({"mesh.size_mm=0.5", "mesh.contact_size_mm=0.25", "model.race_contact=faceted"})
          .empty());
  EXPECT_TRUE(
      WarningsFor({"mesh.size_mm=0.5", "mesh.contact_size_mm=0.25", "model.fidelity=hybrid"})
          .empty());
}

// The paper's friction (mu 0.01 / 0.005) on the coarse 1 mm section (24 rim facets, mu x facets
// 0.24): with the smooth race contact (the default) the healthy rollers roll (cage within a few per
// cent of pure rolling, the loaded roller spinning at its kinematic rate); faceted, the same
// section locks (cage -101 %, loaded roller +86 rad/s against -309; docs/BEARING_MODEL.md). 1200
// rpm, 8 ms (the speed ramp ends at 5 ms). ~16 s.
TEST(BearingModelTest, SmoothRaceContactRollsAtThePapersFriction) {
  const Scene scene = LoadScene(
      Scene0(),
      CoarseHealthy(false,
                    {"run.duration_s=0.008", "solver.threads=1", "model.race_contact=smooth"}));
  SimulationOptions o;
  Simulation sim(scene, o);
  const SimulationSummary summary = sim.Run();
  EXPECT_LT(summary.energy_balance_error, 1e-4);
  // Mean cage slip over the last half (SimulationSummary: the record after 2 ramp_s is empty).
  EXPECT_NEAR(summary.cage_slip_mean, 0.0, 0.03) << summary.BriefReport();
  // The roller on the load line at the end: pure rolling spin (omega_roller =
  // -(d_m / D)(1 - gamma^2) omega_i / 2 = -309.3 rad/s at 1200 rpm). An instant's spin on the
  // 1 mm section carries a few per cent of facet noise, and its phase moves with round-off (a
  // native and a portable build differ by 3.7 %), hence 6 %: the locked faceted case is +86.
  EXPECT_NEAR(sim.model().RollerMotion(0).omega, -309.3, 0.06 * 309.3);
}

TEST(BearingModelTest, BuildsPartsPairsConstraintsAndSensors) {
  const Scene scene = LoadScene(Scene0(), CoarseHealthy(false, {}));
  FeBearingModel model(scene);
  EXPECT_EQ(model.num_rollers(), 13);
  // Default sensors: top (0, 26 mm) along y and side (26 mm, 0) along x, on outer-ring nodes.
  ASSERT_EQ(model.sensor_channels().size(), 2u);
  EXPECT_EQ(model.sensor_channels()[0].direction, Axis::kY);
  EXPECT_EQ(model.sensor_channels()[1].direction, Axis::kX);
  for (const SensorChannel& c : model.sensor_channels()) EXPECT_LT(c.distance_m, scene.mesh.size_m);
  // Pure-rolling cage speed at 1200 rpm after the ramp: 52.224 rad/s (core/bearing.h).
  EXPECT_NEAR(model.TheoreticalCageSpeed(1.0), 52.224, 1e-3);
  EXPECT_NEAR(model.InnerRingSpeed(0.5 * scene.operation.ramp_s), 0.5 * 125.6637, 1e-3);
  EXPECT_NE(model.Describe().find("52 contact pairs"), std::string::npos) << model.Describe();
}

// The full-FE cage is roller-guided (CagePocketGuide): at 6000 rpm its centre stays within the
// radial play (bearing.cage_radial_play_mm) plus the rollers' own excursion and the energy books
// balance. With a free cage (the straight pocket walls only; measured with a 1 m play) the centre
// drifts 2.1 mm by 4 ms and 6.3 mm by 12 ms, and at 0.5 mm the webs' corners strike the rollers
// (energy error 28.7 %; docs/BEARING_MODEL.md, "Speed range of the full-FE section").
TEST(BearingModelTest, FullFeCageStaysCentredAtSpeed) {
  const std::string scene = std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/width-1.38.toml";
  FeBearingModel model(
      LoadScene(scene, CoarseHealthy(true, {"model.fidelity=fe", "solver.threads=1"})));
  double worst = 0.0, omega_sum = 0.0;
  int omega_samples = 0;
  for (int k = 1; k <= 80; ++k) {  // every 0.1 ms up to 8 ms
    model.solver().Run(1e-4 * k);
    const BodyMotion c = model.CageMotion();
    worst = std::max(worst, std::hypot(c.cx, c.cy));
    if (k > 60) omega_sum += c.omega, ++omega_samples;
  }
  const double play = model.options().cage_guide.radial_play_m;
  EXPECT_LT(worst, play + 0.25e-3);
  EXPECT_LT(model.solver().energies().BalanceError(), 1e-3);
  // And the cage turns at close to its rolling speed after the 5 ms ramp. Its mean over 6-8 ms:
  // the instantaneous speed of this faceted 1 mm model rattles by +-15 %, and which value 8 ms
  // lands on depends on the compiler's floating-point contraction alone (-march=native FMA).
  EXPECT_NEAR(omega_sum / omega_samples, model.TheoreticalCageSpeed(8e-3), 0.1 * 261.1);
}

// The roller-guided cage runs against its radial guide: the hybrid's cage centre settles at the
// play's edge within a few ms (the off-centre cage whirls with itself, held only by the guide) and
// stays there, so the play sets how unevenly the rollers are spaced, a deviation of up to
// atan(play / R_pitch) from 27.7 deg that turns with the cage and modulates every roller passage at
// f_c. The play is the scene's bearing.cage_radial_play_mm. Hybrid, 6000 rpm, lubricant traction
// law, 30 ms (~2 s per run); largest deviation of a roller pair's spacing from uniform 1.1 deg
// at 0.1 mm play, 3.5 deg at 0.5 mm (docs/BEARING_MODEL.md, "Cage").
TEST(BearingModelTest, HybridCageRunsAtTheEdgeOfItsRadialPlay) {
  const double pitch_radius = 0.5 * 38.5e-3;
  auto run = [&](double play_mm, double* spacing_deviation) {
    Scene scene = LoadScene(Scene0(),
                            {"model.fidelity=hybrid",
                             "mesh.size_mm=2.0",
                             "friction.model=ehl",
                             "operation.speed_rpm=6000",
                             "run.duration_s=0.03",
                             "run.outputs=[\"cage\", \"rollers\"]",
                             "bearing.cage_radial_play_mm=" + std::to_string(play_mm)});
    scene.defects.clear();
    Simulation simulation(scene, {});
    EXPECT_DOUBLE_EQ(simulation.model().options().cage_guide.radial_play_m, play_mm * 1e-3);
    const SimulationSummary summary = simulation.Run();
    const Recorder& rec = simulation.recorder();
    const std::vector<double>& t = rec.Find("/time")->data;
    const std::vector<double>& centre = rec.Find("/cage/centre")->data;
    const std::vector<double>& orbit = rec.Find("/rollers/orbit_angle")->data;
    const int z = scene.geometry.bearing.num_elements;
    double min_offset = 1.0, max_offset = 0.0, deviation = 0.0;
    for (size_t i = 0; i < t.size(); ++i) {
      if (t[i] < 0.01) continue;  // the ramp ends at 5 ms
      const double offset = std::hypot(centre[2 * i], centre[2 * i + 1]);
      min_offset = std::min(min_offset, offset), max_offset = std::max(max_offset, offset);
      for (int j = 1; j < z; ++j) {
        const double between = orbit[i * z + j] - orbit[i * z];
        const double uniform = 2.0 * std::numbers::pi * j / z;
        deviation = std::max(deviation,
                             std::abs(std::remainder(between - uniform, 2.0 * std::numbers::pi)));
      }
    }
    EXPECT_LT(max_offset, play_mm * 1e-3 + 0.03e-3) << play_mm;
    EXPECT_GT(min_offset, 0.5 * play_mm * 1e-3) << play_mm;  // against the guide throughout
    // The summary's mean offset (from 2 ramp_s = 10 ms) lies between the two.
    EXPECT_GE(summary.cage_offset_mean, min_offset) << summary.BriefReport();
    EXPECT_LE(summary.cage_offset_mean, max_offset) << summary.BriefReport();
    EXPECT_DOUBLE_EQ(summary.cage_radial_play, play_mm * 1e-3);
    EXPECT_NE(summary.BriefReport().find(" mm off the bearing's (radial play "), std::string::npos);
    *spacing_deviation = deviation;
  };
  double tight = 0.0, loose = 0.0;
  run(0.1, &tight);
  run(0.5, &loose);
  // Two rollers' spacing: each is off by up to the cage's offset plus its own tangential pocket
  // clearance (0.1 mm), over the pitch radius.
  EXPECT_LT(tight, 2.0 * (0.1e-3 + 0.13e-3) / pitch_radius);
  EXPECT_LT(loose, 2.0 * (0.1e-3 + 0.53e-3) / pitch_radius);
  EXPECT_GT(loose, 2.5 * tight);
}

// model.race_contact = "curved" against "faceted": the rims touch the raceways as
// circles, so a turning roller does not lift its centre over each rim vertex. The faceted
// section's sensor signal is those bumps (their acceleration ~ 2 pi^4 r f_spin^2 whatever the
// mesh); 1 mm mesh, mu 0.1, 1200 rpm, accel_y rms over 4-6 ms: curved 1450, faceted 12788 m/s^2
// (hybrid model at 0.5 mm: 33). Both keep their energy books. ~25 s for the two runs.
TEST(BearingModelTest, CurvedRaceContactRemovesTheFacetNoise) {
  auto rms = [](const std::string& race_contact) {
    const Scene scene = LoadScene(Scene0(),
                                  CoarseHealthy(true,
                                                {"model.race_contact=" + race_contact,
                                                 "operation.ramp_s=0.002",
                                                 "run.duration_s=0.006",
                                                 "solver.threads=1"}));
    SimulationOptions o;
    Simulation sim(scene, o);
    const SimulationSummary summary = sim.Run();
    EXPECT_LT(summary.energy_balance_error, 1e-4) << race_contact;
    const std::vector<double>& a = sim.recorder().Acceleration(0);        // top sensor, y
    const int first = static_cast<int>(4e-3 * scene.run.output_rate_hz);  // sample k at k / rate
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int k = first; k < sim.recorder().recorded_samples(); ++k)
      sum += a[k], sum2 += a[k] * a[k], ++n;
    return std::sqrt(sum2 / n - (sum / n) * (sum / n));
  };
  const double curved = rms("curved"), faceted = rms("faceted");
  EXPECT_LT(curved, 0.25 * faceted) << "curved " << curved << ", faceted " << faceted << " m/s^2";
}

// Harris-Jones for the scene's section (its load, roller length = thickness, clearance; static).
LoadDistributionSummary HarrisJonesFor(const Scene& scene) {
  LoadDistributionOptions o;
  o.radial_load_n = scene.operation.radial_load_n;
  o.roller_length_m = scene.geometry.thickness_m;
  o.diametral_clearance_m = scene.geometry.diametral_clearance_m;
  LoadDistributionSummary hj;
  SolveLoadDistribution(o, scene.geometry.bearing, &hj);
  return hj;
}

// Static load (speed 0): the outer-race contact forces carry the 10 kN, only rollers in the
// lower half are loaded; the roller on the load line is compared with Harris-Jones.
class StaticLoadTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Scene scene = LoadScene(
        Scene0(), CoarseHealthy(false, {"operation.speed_rpm=0", "operation.load_ramp_s=0.001"}));
    model_ = new FeBearingModel(scene);
    // Average the last millisecond of 3 ms (load ramped over the first).
    const int z = model_->num_rollers();
    q_.assign(z, 0.0);
    int n = 0;
    auto& s = model_->solver();
    while (s.time() < 3e-3) {
      s.Step();
      if (s.time() > 2e-3) {
        double fy = 0.0;
        for (int j = 0; j < z; ++j) {
          q_[j] += model_->RollerOuterForce(j);
          fy += model_->outer_pair(j).Resultant().normal_y;
        }
        sum_fy_ += fy;
        ++n;
      }
    }
    for (double& v : q_) v /= n;
    sum_fy_ /= n;
  }
  static void TearDownTestSuite() { delete model_; }
  static FeBearingModel* model_;
  static std::vector<double> q_;
  static double sum_fy_;
};
FeBearingModel* StaticLoadTest::model_ = nullptr;
std::vector<double> StaticLoadTest::q_;
double StaticLoadTest::sum_fy_ = 0.0;

TEST_F(StaticLoadTest, OuterRaceContactsCarryTheRadialLoad) {
  // Forces on the rollers from the outer race point up (+y) and add up to F_r = 10 kN.
  EXPECT_NEAR(sum_fy_, 10000.0, 300.0);
  const double total = std::accumulate(q_.begin(), q_.end(), 0.0);
  // Rollers in the upper half (|psi| > 90 deg, j = 4..9) carry nothing.
  for (int j = 4; j <= 9; ++j) EXPECT_LT(q_[j], 0.01 * total) << "roller " << j;
  // The roller on the load line carries the most.
  for (int j = 1; j < 13; ++j) EXPECT_GT(q_[0], q_[j]);
}

// The same static section on the scene's elastic steel adapter against Harris-Jones (rigid rings,
// rigid housing). Per roller the +-55.4 deg rollers carry about a quarter less (the ring bends away
// beyond the adapter's +-50.3 deg seat; docs/BEARING_MODEL.md), so the comparison here is the load
// distribution's: every roller within 10 % of the peak load Q_max, as the paper's figure compares
// them, and the two most loaded within 10 % each. The per-roller criterion on a rigid housing is
// HarrisJonesTest.FullFeLoadZoneWithinTenPercentOnARigidHousing below.
TEST_F(StaticLoadTest, LoadDistributionOnTheSteelAdapterWithinTenPercentOfQmax) {
  const LoadDistributionSummary hj = HarrisJonesFor(model_->scene());
  for (int j = 0; j < model_->num_rollers(); ++j) {
    const double ref = hj.rollers[j].outer_load_n;
    std::printf("roller %2d: FE %7.1f N, Harris-Jones %7.1f N (%+.1f %% of Q_max)\n",
                j,
                q_[j],
                ref,
                100.0 * (q_[j] - ref) / hj.q_max_n);
    EXPECT_NEAR(q_[j], ref, 0.1 * hj.q_max_n) << "roller " << j;
    if (ref > 0.75 * hj.q_max_n) {
      EXPECT_NEAR(q_[j], ref, 0.1 * ref) << "roller " << j;
    }
  }
}

// Load-zone forces within 10 % of Harris-Jones, on the housing Harris-Jones assumes (a rigid
// one: model.adapter = "rigid"), with the smooth race contact (the default). With faceted
// contact the roller on the load line carries +31 to +51 % and the +-55.4 deg rollers almost
// nothing (their approach is the size of the facets' sag). On the elastic steel adapter the
// +-55.4 deg rollers carry -28 % (the ring bends beyond the +-50 deg seat; docs/BEARING_MODEL.md).
// Static, load ramped over 1 ms, forces averaged over 2-3 ms. ~15 s.
TEST(HarrisJonesTest, FullFeLoadZoneWithinTenPercentOnARigidHousing) {
  const Scene scene = LoadScene(Scene0(),
                                {"mesh.size_mm=0.5",
                                 "defects=[]",
                                 "model.adapter=rigid",
                                 "operation.speed_rpm=0",
                                 "operation.load_ramp_s=0.001",
                                 "solver.threads=2"});
  FeBearingModel model(scene);
  const int z = model.num_rollers();
  std::vector<double> q(z, 0.0);
  int n = 0;
  for (auto& s = model.solver(); s.time() < 3e-3;) {
    s.Step();
    if (s.time() > 2e-3) {
      for (int j = 0; j < z; ++j) q[j] += model.RollerOuterForce(j);
      ++n;
    }
  }
  const LoadDistributionSummary hj = HarrisJonesFor(scene);
  int loaded = 0;
  for (int j = 0; j < z; ++j) {
    SCOPED_TRACE(j);
    const double ref = hj.rollers[j].outer_load_n;
    std::printf("roller %2d: FE %7.1f N, Harris-Jones %7.1f N\n", j, q[j] / n, ref);
    if (ref > 0.0) {
      ++loaded;
      EXPECT_NEAR(q[j] / n, ref, 0.1 * ref);
    } else {
      EXPECT_LT(q[j] / n, 0.01 * hj.q_max_n);
    }
  }
  EXPECT_EQ(loaded, 5);  // 0, +-27.7, +-55.4 deg (load zone +-71.1 deg)
  EXPECT_LT(model.solver().energies().BalanceError(), 1e-3);
}

}  // namespace
}  // namespace spallkit::sim
