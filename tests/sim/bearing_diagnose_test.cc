// The diagnosis criterion of docs/BEARING_MODEL.md end to end, at the paper's speed: `spall
// simulate` the verification scene (hybrid model, 2 mm housing, 1200 rpm, 0.8 s: 6.6 cage turns)
// and `spall diagnose` its acceleration. Diagnose must call the roller spall and find f_b within 2
// % and f_c within 5 % of theory (the paper's LS-DYNA model: f_b 114.49 Hz against 115.08, f_c 8.69
// against 8.31), and the deviations must be the simulated slip: f_c against the mean /cage/omega,
// f_b against twice the defective roller's mean spin relative to the cage. Friction: the main job's
// lubricant traction law (friction.model = "ehl"): with Coulomb friction at the scene's 0.01 /
// 0.005 the rigid roller gets trapped with its spall on a race, and at 0.1 / 0.08 the spall that
// starts facing the outer race (angle 0) stays there unless the cage's start-up swing pushes it
// onto the inner race, which depends on the cage's radial play (docs/BEARING_MODEL.md, "Spall
// trapping" and "Cage"); the traction law rolls it out with either play. About 40 s (the
// simulation); the 6000 rpm checks in bearing_verification_test are shorter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "core/constants.h"
#include "core/hdf5.h"
#include "dsp/diagnose.h"
#include "dsp/explain.h"
#include "sim/bearing/record_adapter.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"
#include "tests/apps/run_spall.h"

namespace {

using spallkit::kPi;
using spallkit::testing::RunSpall;

TEST(HybridDiagnoseTest, DiagnoseFindsTheRollerSpallAtThePapersSpeed) {
  const std::string dir = ::testing::TempDir();
  const std::string h5_path = dir + "/hybrid_diag_1200.h5", csv = dir + "/hybrid_diag_1200.csv";
  const std::string scene =
      std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml";
  int code = 0;
  std::string out = RunSpall("simulate " + scene + " -o " + h5_path + " --csv " + csv +
                                 " --quiet --set model.fidelity=hybrid --set mesh.size_mm=2.0"
                                 " --set run.duration_s=0.8 --set friction.model=ehl",
                             &code);
  ASSERT_EQ(code, 0) << out;
  std::printf("%s", out.c_str());
  out = RunSpall("diagnose " + csv + " --bearing N205EM --rpm 1200 --json", &code);
  ASSERT_EQ(code, 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);
  const double fb_theory = j["kinematics"]["f_b_hz"], fc_theory = j["kinematics"]["cage_hz"];
  EXPECT_NEAR(fb_theory, 115.085, 0.001);
  EXPECT_NEAR(fc_theory, 8.312, 0.001);
  EXPECT_EQ(j["verdict"], "rolling_element") << j["verdict"];
  ASSERT_TRUE(j["measured"]["f_b_hz"].is_number()) << j["measured"].dump();
  ASSERT_TRUE(j["measured"]["f_c_hz"].is_number()) << j["measured"].dump();
  const double fb = j["measured"]["f_b_hz"], fc = j["measured"]["f_c_hz"];

  // Simulated kinematics after the 5 ms ramp and a settling time.
  spallkit::h5::File f = spallkit::h5::File::OpenReadOnly(h5_path);
  const std::vector<double> t = f.ReadDataset("/time"), cage = f.ReadDataset("/cage/omega"),
                            spin = f.ReadDataset("/rollers/spin");
  const size_t z = spin.size() / t.size();
  double fc_sim = 0, fb_sim = 0;
  int n = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] >= 0.05) {
      fc_sim += cage[i] / (2 * kPi);
      fb_sim += 2.0 * std::abs(spin[i * z + 0] - cage[i]) / (2 * kPi);  // roller 0: the spall
      ++n;
    }
  fc_sim /= n, fb_sim /= n;
  const double df = 1.0 / (t.back() - t.front());
  std::printf(
      "diagnose: f_b %.3f Hz (theory %.3f, %+.2f %%), f_c %.3f Hz (theory %.3f, %+.2f %%)\n"
      "simulated: f_b %.3f Hz (%+.2f %%) from the defective roller's spin, f_c %.3f Hz (%+.2f %%) "
      "from the cage speed; record resolution %.2f Hz\n",
      fb,
      fb_theory,
      100 * (fb / fb_theory - 1),
      fc,
      fc_theory,
      100 * (fc / fc_theory - 1),
      fb_sim,
      100 * (fb_sim / fb_theory - 1),
      fc_sim,
      100 * (fc_sim / fc_theory - 1),
      df);
  EXPECT_NEAR(fb, fb_theory, 0.02 * fb_theory);
  EXPECT_NEAR(fc, fc_theory, 0.05 * fc_theory);
  // The deviations are the simulated slip, to a fraction of the record's resolution (1.25 Hz).
  EXPECT_NEAR(fb, fb_sim, 0.25 * df);
  EXPECT_NEAR(fc, fc_sim, 0.25 * df);
  std::remove(h5_path.c_str());
  std::remove(csv.c_str());
}

// The lumped model's 1 s record of the paper scene with the traction law (the issue's "1 s in
// about 1 s" rung; 8 cage turns at 1200 rpm) is the roller spall wherever the record starts. Its
// f_b lies 1.3 SES bins from 14 f_c, so the integer-ratio test cannot tell its roller comb from
// a cage comb (dsp/explain.h, RollerCageSeparation): the report says so, and the roller comb is
// given to the cage only when the ratio and the harmonic evidence both say so. (On the ratio
// alone the vertical record trimmed by 5 ms was called healthy: the cage comb's rate came out
// 0.7-0.9 % low, the ratio landed on 14, and the cage comb, too short to be claimed, explained
// the roller lines away; on the evidence alone the horizontal one was, its load-zone lines
// outweighing its f_b harmonics.) Where the record's strongest cage comb (the spall's load-zone
// modulation) does outweigh its roller comb, the comb is given to the cage, which a 1 s record
// cannot claim: "healthy" with the warning, never another fault. Measured: rolling_element in
// 11 of the 12 cuts (the horizontal one trimmed by 2 ms is that case; which cuts move with any
// change at round-off). Both channels, about 3 s.
TEST(LumpedDiagnoseTest, OneSecondRecordIsTheRollerSpallWhereverItStarts) {
  namespace sim = spallkit::sim;
  namespace dsp = spallkit::dsp;
  const sim::Scene scene =
      sim::LoadScene(std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml",
                     {"model.fidelity=lumped", "run.duration_s=1", "friction.model=ehl"});
  sim::Simulation simulation(scene, {});
  simulation.Run();
  const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * kPi);
  int unresolved = 0, rolling = 0;
  for (auto axis : {sim::AccelerationAxis::kVertical, sim::AccelerationAxis::kHorizontal})
    for (double trim_s : {0.0, 0.002, 0.005, 0.01, 0.02, 0.05}) {
      spallkit::Record r = sim::ToRecord(simulation, axis);
      r.samples.erase(r.samples.begin(),
                      r.samples.begin() + static_cast<long>(trim_s * r.sample_rate_hz));
      const dsp::Diagnosis d = dsp::Diagnose(r, scene.geometry.bearing, shaft_hz);
      SCOPED_TRACE(r.channel + " trimmed by " + std::to_string(trim_s) + " s\n" + d.BriefReport());
      if (d.roller_cage.tested) {  // the cage comb detected too
        EXPECT_FALSE(d.roller_cage.separable);
        EXPECT_NEAR(d.roller_cage.offset_bins, 1.28, 0.1);
        ++unresolved;
      }
      if (d.verdict != dsp::Verdict::kRollingElement) {
        EXPECT_EQ(d.verdict, dsp::Verdict::kHealthy);
        EXPECT_TRUE(d.roller_cage.tested && !d.roller_cage.separable);
        continue;
      }
      ++rolling;
      ASSERT_TRUE(d.measured_f_b_hz.has_value());
      EXPECT_NEAR(*d.measured_f_b_hz / d.kinematics.f_b_hz, 1.0, 0.01);
    }
  std::printf(
      "rolling_element on %d of 12 cuts, %d with the two combs unresolved\n", rolling, unresolved);
  EXPECT_GE(rolling, 10);
  EXPECT_GE(unresolved, 6);  // the case this test is about: both combs, not separable
}

// A simulated healthy bearing's steady state (from 0.05 s on) and the lubricant film's normal
// load (sim/contact/film_lift.h; docs/DIAGNOSIS.md, "Empirical false-alarm rate"). With the dry
// penalty law a race contact's force starts and ends with a slope step where the rollers enter
// and leave the load zone, which strikes the rings at Z f_c; the contact damping (zeta 0.1)
// makes it a force step. The horizontal channel of this healthy lumped bearing (one of the
// identification's tuning cases: 1498 rpm, 11.9 kN, traction law) is then called outer_race
// (printed, not asserted: which healthy cases it hits moves with the realization, 5 of 8 of
// those cases). With the film the load fades over micrometres of gap and the bearing is healthy
// on both channels. About 7 s.
TEST(LumpedDiagnoseTest, HealthyLubricatedBearingIsHealthy) {
  namespace sim = spallkit::sim;
  namespace dsp = spallkit::dsp;
  const sim::Scene scene =
      sim::LoadScene(std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml",
                     {"model.fidelity=lumped",
                      "defects=[]",
                      "friction.model=ehl",
                      "operation.speed_rpm=1497.6492058994559",
                      "operation.radial_load_n=11922.633053147838",
                      "run.duration_s=1.05",
                      "run.outputs=[\"acceleration\"]"});
  ASSERT_GT(scene.friction.ehl.inlet_viscosity_pa_s, 0.0);  // the film is the default
  const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * kPi);
  // The verdicts of both channels from 0.05 s on, at the given inlet viscosity (0: no film).
  auto verdicts = [&](double viscosity) {
    sim::Scene s = scene;
    s.friction.ehl.inlet_viscosity_pa_s = viscosity;  // [friction] ehl_viscosity_pa_s
    sim::Simulation simulation(s, {});
    simulation.Run();
    std::vector<dsp::Verdict> v;
    for (auto axis : {sim::AccelerationAxis::kVertical, sim::AccelerationAxis::kHorizontal}) {
      spallkit::Record r = sim::ToRecord(simulation, axis);
      spallkit::DropStart(&r, 0.05);
      v.push_back(dsp::Diagnose(r, scene.geometry.bearing, shaft_hz).verdict);
      std::printf("inlet viscosity %.2f Pa s, %s from 0.05 s: %s\n",
                  viscosity,
                  r.channel.c_str(),
                  dsp::VerdictName(v.back()));
    }
    return v;
  };
  verdicts(0.0);
  for (dsp::Verdict v : verdicts(scene.friction.ehl.inlet_viscosity_pa_s))
    EXPECT_EQ(v, dsp::Verdict::kHealthy);
}

// A case of the identification's simulated sets (datasets/sweeps/identify-*.toml): three
// spalled rollers of one width and depth on the lumped model, dry friction 0.15 / 0.12, the
// horizontal channel from 0.05 s, diagnosed. The cage's radial play is the one the sets were
// drawn with (0.5 mm): the case is a replay, and another play makes another record
// (docs/BEARING_MODEL.md, "Cage radial play").
struct ThreeRollerCase {
  int rollers[3];
  double width_mm, depth_mm;
  double angle_deg[3];
  double load_n, rpm, duration_s;
};

spallkit::dsp::Diagnosis DiagnoseLumpedCase(const ThreeRollerCase& c) {
  namespace sim = spallkit::sim;
  auto num = [](double v) {  // every digit: the cases are chaotic enough for 1e-7 to matter
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  std::vector<std::string> set = {"model.fidelity=lumped",
                                  "bearing.cage_radial_play_mm=0.5",
                                  "run.outputs=[\"acceleration\"]",
                                  "friction.mu_static=0.15",
                                  "friction.mu_dynamic=0.12",
                                  "operation.radial_load_n=" + num(c.load_n),
                                  "operation.speed_rpm=" + num(c.rpm),
                                  "run.duration_s=" + num(c.duration_s)};
  for (int k = 0; k < 3; ++k) {
    const std::string d = "defects." + std::to_string(k) + ".";
    set.push_back(d + "roller=" + std::to_string(c.rollers[k]));
    set.push_back(d + "width_mm=" + num(c.width_mm));
    set.push_back(d + "depth_mm=" + num(c.depth_mm));
    set.push_back(d + "angle_deg=" + num(c.angle_deg[k]));
  }
  const sim::Scene scene = sim::LoadScene(
      std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/paper-verification.toml", set);
  sim::Simulation simulation(scene, {});
  simulation.Run();
  spallkit::Record r = sim::ToRecord(simulation, sim::AccelerationAxis::kHorizontal);
  spallkit::DropStart(&r, 0.05);
  const double shaft_hz = scene.operation.inner_ring_speed_rad_s / (2.0 * kPi);
  return spallkit::dsp::Diagnose(r, scene.geometry.bearing, shaft_hz);
}

// Three spalled rollers (slots 1, 2, 6; 1.68 mm; 1352 rpm, 7.2 kN, dry friction 0.15 / 0.12; a
// case of the identification's 1-2 s report set, datasets/sweeps/identify-report-long.toml) on
// the lumped model: the cage slips 1.8 % and the rollers' f_b 1.1 %, so the measured f_b / f_c
// sits 0.4 % from 14, on the integer of a dense cage comb, in a record (1.4 s) that resolves f_b
// from 14 f_c. The load-zone modulation of three rollers is a strong cage comb too, which the
// record is too short to claim (13 cage turns). Given the roller comb on the ratio alone, that
// comb explained the record's strongest line (f_b, SNR 370) away and the spall was "healthy";
// the comb goes to the cage only when the cage's harmonics also outweigh the roller's
// (dsp/explain.h). About 4 s.
TEST(LumpedDiagnoseTest, ThreeSpalledRollersWithASlippingCageAreTheRollerSpall) {
  namespace dsp = spallkit::dsp;
  const dsp::Diagnosis d =
      DiagnoseLumpedCase({{1, 2, 6},
                          1.6831320818163533,
                          0.9060868776702237,
                          {328.9969995648117, 92.18152357611976, 239.4153247490316},
                          7236.445637546889,
                          1351.5052563410022,
                          1.4482967526378718});
  SCOPED_TRACE(d.BriefReport());
  EXPECT_EQ(d.verdict, dsp::Verdict::kRollingElement);
  // The case this test is about: the ratio on 14, resolved, and a cage comb detected beside it.
  ASSERT_TRUE(std::isfinite(d.roller_integer_ratio_mismatch));
  EXPECT_LE(std::abs(d.roller_integer_ratio_mismatch),
            dsp::ExplanationOptions{}.integer_ratio_tolerance);
  EXPECT_TRUE(d.roller_cage.tested && d.roller_cage.separable);
}

// Three spalled rollers in adjacent slots (5, 6, 7; 1.66 mm; 1705 rpm, 6.4 kN, dry friction
// 0.15 / 0.12; case 12 of the identification's 1 s report set, datasets/sweeps/
// identify-report.toml) on the lumped model, horizontal channel: f_b stands at about 100 times
// the floor and its upper f_c sidebands at the first two harmonics are significant, but neither
// harmonic has both (the three rollers' sidebands add with other phases on the two sides), 2 f_b
// lies on the shaft half order 11.5 f_r and the spin series is weak. A roller family is one f_b
// harmonic and two sidebands of any harmonics (dsp/detection.h); on the both-sides rule alone
// the record was "healthy". About 3 s.
TEST(LumpedDiagnoseTest, ThreeAdjacentSpalledRollersWithOneSidedSidebandsAreTheRollerSpall) {
  namespace dsp = spallkit::dsp;
  const dsp::Diagnosis d =
      DiagnoseLumpedCase({{5, 6, 7},
                          1.6603116753154061,
                          0.9588876640705507,
                          {168.23018883265422, 4.3968739947765334, 46.941437785674957},
                          6447.5735471528815,
                          1704.5410540402509,
                          1.05});
  SCOPED_TRACE(d.BriefReport());
  EXPECT_EQ(d.verdict, dsp::Verdict::kRollingElement);
  // The case this test is about: no f_b harmonic with both of its sidebands significant.
  for (const auto& det : d.faults) {
    if (det.component != dsp::FaultComponent::kRollingElement) continue;
    for (const auto& h : det.lines) {
      if (h.line.is_sideband() || h.line.half_order || !h.significant) continue;
      int both = 0;
      for (const auto& sb : det.lines)
        both += sb.line.is_sideband() && sb.line.harmonic == h.line.harmonic && sb.significant;
      EXPECT_LT(both, 2) << "harmonic " << h.line.harmonic;
    }
  }
}

}  // namespace
