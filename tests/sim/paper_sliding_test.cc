// The paper's findings on short hybrid runs (docs/PAPER.md): at the paper's friction (mu 0.01 /
// 0.005) the defective roller of every width scene slides and resumes rolling (its Fig. 9), while
// a through-length spall (the paper's 2-D section) traps the rigid roller for good; and the
// width / depth / count trends. Runs: 2 mm housing mesh, 2 ms speed ramp, statistics from 10 ms.
// Sliding measure: sim/bearing/roller_sliding.h, checked first on synthetic spin records.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "sim/bearing/roller_sliding.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace spallkit::sim {
namespace {

// N205EM at 1200 rpm: spin relative to the cage 361.5 rad/s against the inner ring
// (bearing-notes §2), i.e. 2 pi BSF with BSF = 57.542 Hz.
TEST(RollerSlidingTest, PureRollingSpinIsTheKinematicSpin) {
  const BearingGeometry b = CatalogBearing("N205EM");
  const double omega_i = 1200.0 * 2 * kPi / 60;
  EXPECT_NEAR(PureRollingRelativeSpin(b, omega_i), -361.5, 0.1);
  EXPECT_NEAR(PureRollingRelativeSpin(b, omega_i),
              -2 * kPi * ComputeFrequencies(b, 20.0).roller_spin_hz,
              1e-9);
}

// Synthetic record at 20 kHz, 0.1 s, cage at 50 rad/s: rolling, then trapped (spin = cage) over
// 20-35 ms, rolling, a 0.2 ms dip (not an episode), trapped again from 70 ms to the end.
TEST(RollerSlidingTest, CountsEpisodesAndLeavesShortDipsOut) {
  const double rolling = -360.0, cage = 50.0;
  std::vector<double> t, spin, w;
  for (int i = 0; i <= 2000; ++i) {
    const double ti = i / 20000.0;
    const bool trapped = (ti >= 0.020 && ti < 0.035) || ti >= 0.070;
    const bool dip = ti >= 0.050 && ti < 0.0502;
    t.push_back(ti);
    w.push_back(cage);
    spin.push_back(trapped || dip ? cage : cage + rolling);
  }
  RollerSlidingSummary s = MeasureRollerSliding(t, spin, w, rolling);
  EXPECT_EQ(s.sliding_episodes, 2);
  EXPECT_TRUE(s.resumed_rolling);
  EXPECT_NEAR(s.rolling_fraction, 0.55, 1e-3);  // 55 of 100 ms
  EXPECT_NEAR(s.cage_revolutions, 50.0 * 0.1 / (2 * kPi), 1e-9);
  EXPECT_NEAR(s.episodes_per_cage_rev, 2 / s.cage_revolutions, 1e-9);
  EXPECT_NEAR(s.mean_spin_ratio, 0.55 - 4.0 / 2001, 2e-3);  // the dip counts in the mean
  // From 75 ms on the roller never rolls: no episode starts, none resumes.
  RollerSlidingOptions o;
  o.from_s = 0.075;
  s = MeasureRollerSliding(t, spin, w, rolling, o);
  EXPECT_EQ(s.sliding_episodes, 0);
  EXPECT_FALSE(s.resumed_rolling);
  EXPECT_EQ(s.rolling_fraction, 0.0);
  // Without the dip filter the dip is a third episode.
  o = {};
  o.min_episode_s = 0;
  EXPECT_EQ(MeasureRollerSliding(t, spin, w, rolling, o).sliding_episodes, 3);
}

TEST(RollerSlidingTest, RejectsBadInput) {
  const std::vector<double> t = {0, 1e-3, 2e-3}, s = {1, 1, 1};
  EXPECT_THROW(MeasureRollerSliding(t, {1, 1}, s, -1.0), InputError);
  EXPECT_THROW(MeasureRollerSliding(t, s, s, 0.0), InputError);
  RollerSlidingOptions o;
  o.rolling_threshold = 1.5;
  EXPECT_THROW(MeasureRollerSliding(t, s, s, -1.0, o), InputError);
  o = {};
  o.from_s = 1.0;
  EXPECT_THROW(MeasureRollerSliding(t, s, s, -1.0, o), InputError);
}

// What one short hybrid run of a paper scene gives, statistics from 10 ms.
struct PaperRun {
  double accel_rms = 0;         // vertical, mean removed, m/s^2
  double slip_rms = 0;          // cage sliding ratio S, RMS with the mean, %
  double cage_force_rms = 0;    // defective rollers' pocket force, mean over them, N
  RollerSlidingSummary roller;  // roller 0
};

PaperRun RunScene(const std::string& name, std::vector<std::string> sets, double duration) {
  sets.insert(
      sets.end(),
      {"mesh.size_mm=2.0", "operation.ramp_s=0.002", "run.duration_s=" + std::to_string(duration)});
  const Scene scene =
      LoadScene(std::string(SPALLKIT_SOURCE_DIR) + "/datasets/scenes/" + name + ".toml", sets);
  Simulation sim(scene, SimulationOptions{});
  EXPECT_TRUE(sim.Run().completed);
  const Recorder& r = sim.recorder();
  const std::vector<double>& t = r.Find("/time")->data;
  const Recorder::Series* spin = r.Find("/rollers/spin");
  const Recorder::Series* force = r.Find("/contact/roller_cage");
  const std::vector<double>& slip = r.Find("/cage/slip_ratio")->data;
  const std::vector<double>& cage = r.Find("/cage/omega")->data;
  const std::vector<double>& accel = r.Acceleration(0);  // the top sensor's y channel
  const double from = 0.01;
  PaperRun out;
  double mean = 0;
  int n = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] >= from) mean += accel[i], ++n;
  mean /= n;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] < from) continue;
    out.accel_rms += (accel[i] - mean) * (accel[i] - mean) / n;
    out.slip_rms += 1e4 * slip[i] * slip[i] / n;
    for (const Defect& d : scene.defects) {
      const double f = force->data[i * force->cols + d.roller];
      out.cage_force_rms += f * f / n;
    }
  }
  out.accel_rms = std::sqrt(out.accel_rms);
  out.slip_rms = std::sqrt(out.slip_rms);
  out.cage_force_rms = std::sqrt(out.cage_force_rms / scene.defects.size());
  std::vector<double> spin0(t.size());
  for (size_t i = 0; i < t.size(); ++i) spin0[i] = spin->data[i * spin->cols];
  RollerSlidingOptions o;
  o.from_s = from;
  out.roller = MeasureRollerSliding(
      t,
      spin0,
      cage,
      PureRollingRelativeSpin(scene.geometry.bearing, scene.operation.inner_ring_speed_rad_s),
      o);
  std::printf(
      "%-12s accel RMS %7.1f m/s^2, cage slip RMS %.2f %%, defective roller-cage force "
      "RMS %6.2f N; roller 0: %s\n",
      name.c_str(),
      out.accel_rms,
      out.slip_rms,
      out.cage_force_rms,
      out.roller.BriefReport().c_str());
  return out;
}

// Every width scene (spall 8 of 9 mm long, paper friction, 6000 rpm, 50 ms): the defective roller
// is never trapped for good: it rolls at least a tenth of the time, and where it slid it rolled
// again; from 0.92 mm on it alternates (at least one sliding episode after 10 ms). The control:
// the same 2.27 mm spall through the whole length stays trapped (rolls < 2 % of the time).
TEST(PaperSlidingTest, DefectiveRollerSlidesAndResumesInEveryWidthScene) {
  for (const char* w : {"0.46", "0.92", "1.38", "1.82", "2.27"}) {
    SCOPED_TRACE(w);
    const PaperRun r = RunScene(std::string("width-") + w, {}, 0.05);
    EXPECT_GE(r.roller.rolling_fraction, 0.1);
    EXPECT_TRUE(r.roller.rolling_fraction == 1.0 || r.roller.resumed_rolling);
    if (std::string(w) != "0.46") {
      EXPECT_GE(r.roller.sliding_episodes, 1);
    }
  }
  const PaperRun through = RunScene("width-2.27", {"defects.0.length_mm=9"}, 0.05);
  EXPECT_LT(through.roller.rolling_fraction, 0.02);
}

}  // namespace
}  // namespace spallkit::sim
