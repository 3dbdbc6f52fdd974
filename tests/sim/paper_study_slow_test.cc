// The paper's findings on short hybrid runs (docs/PAPER.md): at the paper's friction (mu 0.01 /
// 0.005) the defective roller of every width scene slides and resumes rolling (its Fig. 9), while
// a through-length spall (the paper's 2-D section) traps the rigid roller for good; and the
// width / depth / count trends. Runs: 2 mm housing mesh, 2 ms speed ramp, 50 ms (80 ms at
// 4000 rpm), statistics from 10 ms (1.6 cage revolutions at 6000 rpm; the last test 70 ms from
// 30 ms). Slow: 18 runs. With the
// lubricant traction law, a through-length spall rolls (EhlTraction...); with 2 mm of the roller
// intact, a spall wider than that part's elastic approach no longer strikes (the last test).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sim/bearing/roller_sliding.h"
#include "sim/bearing/scene.h"
#include "sim/bearing/simulation.h"

namespace spallkit::sim {
namespace {

// What one short hybrid run of a paper scene gives, statistics from `from` seconds.
struct PaperRun {
  double accel_rms = 0;         // vertical, mean removed, m/s^2
  double slip_rms = 0;          // cage sliding ratio S, RMS with the mean, %
  double cage_force_rms = 0;    // defective rollers' pocket force, mean over them, N
  RollerSlidingSummary roller;  // roller 0
};

PaperRun RunScene(const std::string& name,
                  std::vector<std::string> sets,
                  double duration,
                  double from = 0.01) {
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

// Every width scene (spall 8 of 9 mm long, paper friction, 6000 rpm): the defective roller is
// never trapped for good: it rolls at least a tenth of the time, and where it slid it rolled again;
// from 0.92 mm on it alternates (a sliding episode after 10 ms) in at least three of the four
// wider scenes: when a slide starts moves with round-off (0.92 mm: one episode and 23 % rolling
// with std::pow's Palmgren law, none and 71 % with its expansion that differs by 1e-13), so one
// width's 40 ms window may hold none, and the widths are counted as a group. The control: the same
// 2.27 mm spall through the whole length stays trapped (rolls < 2 % of the time). Width trend on
// these short runs: the 1.38 and 2.27 mm spalls against 0.46 mm (vibration x2, cage sliding ratio
// x1.3) and the 0.92-2.27 mm spalls' mean defective roller-cage force against 0.46 mm's (x3); the
// monotonic trend through all five widths is the 0.1 s study's, docs/PAPER.md).
TEST(PaperStudyTest, DefectiveRollerSlidesAndResumesAndWiderSpallsShakeMore) {
  std::vector<PaperRun> runs;
  int wider_sliding = 0;
  for (const char* w : {"0.46", "0.92", "1.38", "1.82", "2.27"}) {
    SCOPED_TRACE(w);
    const PaperRun r = RunScene(std::string("width-") + w, {}, 0.05);
    EXPECT_GE(r.roller.rolling_fraction, 0.1);
    EXPECT_TRUE(r.roller.rolling_fraction == 1.0 || r.roller.resumed_rolling);
    if (std::string(w) != "0.46" && r.roller.sliding_episodes >= 1) ++wider_sliding;
    runs.push_back(r);
  }
  EXPECT_GE(wider_sliding, 3);
  for (int k : {2, 4}) {
    SCOPED_TRACE(k);
    EXPECT_GT(runs[k].accel_rms, 2.0 * runs[0].accel_rms);
    EXPECT_GT(runs[k].slip_rms, 1.3 * runs[0].slip_rms);
  }
  // The pocket force of one width in one 40 ms window moves with the slide timing, which moves
  // with round-off (2.27 mm: 2.4 N in one build, 22 N as the four-start-angle mean of the 0.1 s
  // study, docs/PAPER.md; 0.46 mm: 0.6 to 3.1 N), so the wider spalls are compared as a group:
  // their mean against the 0.46 mm spall's, x3 although most runs give x5 or more.
  const double wide_force = (runs[1].cage_force_rms + runs[2].cage_force_rms +
                             runs[3].cage_force_rms + runs[4].cage_force_rms) /
                            4.0;
  EXPECT_GT(wide_force, 3.0 * runs[0].cage_force_rms);
  const PaperRun through = RunScene("width-2.27", {"defects.0.length_mm=9"}, 0.05);
  EXPECT_LT(through.roller.rolling_fraction, 0.02);
}

// Depth (1.38 mm wide, 6000 rpm, 50 ms): 0.59 and 1.18 mm give the same vibration within +-30 %
// (the spall's starting angle alone moves it by +-11 % in 0.1 s runs, docs/PAPER.md); count
// (4000 rpm, 80 ms: two cage revolutions after 10 ms): three defective rollers shake the bearing
// more, slide the cage more and push harder on their pockets than one (x1.5, the cage's sliding
// x1.2; measured x2.5, x3.0, x2.8). How much more the cage slides depends on its radial play:
// x1.34 on these runs with 0.1 mm instead of the default 0.5 mm (docs/BEARING_MODEL.md, "Cage
// radial play"); the paper's finding is the rise.
TEST(PaperStudyTest, DepthChangesLittleAndMoreDefectiveRollersShakeMore) {
  const PaperRun shallow = RunScene("depth-0.59", {}, 0.05);
  const PaperRun deep = RunScene("depth-1.18", {}, 0.05);
  EXPECT_NEAR(deep.accel_rms / shallow.accel_rms, 1.0, 0.3);
  const PaperRun one = RunScene("rollers-1", {}, 0.08);
  const PaperRun three = RunScene("rollers-3", {}, 0.08);
  EXPECT_GT(three.accel_rms, 1.5 * one.accel_rms);
  EXPECT_GT(three.slip_rms, 1.2 * one.slip_rms);
  EXPECT_GT(three.cage_force_rms, 1.5 * one.cage_force_rms);
}

// The lubricant traction law (friction.model = "ehl") on the paper's through-length spall, the
// spall starting sideways (angles 60 / 90 / 120 deg; starting on a race, the 2.27 mm roller is
// loose from t = 0 and never spun up): the defective roller rolls through every passage, and the
// widest spall shakes the bearing most and slides the cage more, on the mean of the three starts
// (one 50 ms run's cage sliding ratio moves by +-25 % with its start; docs/PAPER.md, "Through-
// length spalls with lubricant traction"; measured: vibration x3.6, cage sliding ratio x1.86).
TEST(PaperStudyTest, EhlTractionRollsThroughLengthSpallsAndWiderSpallsShakeMore) {
  double accel[2] = {0, 0}, slip[2] = {0, 0};
  const char* scenes[2] = {"width-0.46", "width-2.27"};
  for (int w = 0; w < 2; ++w)
    for (const char* angle : {"60", "90", "120"}) {
      const PaperRun run = RunScene(scenes[w],
                                    {"friction.model=ehl",
                                     "defects.0.length_mm=9",
                                     std::string("defects.0.angle_deg=") + angle},
                                    0.05);
      EXPECT_GT(run.roller.rolling_fraction, 0.95) << scenes[w] << " from " << angle << " deg";
      accel[w] += run.accel_rms / 3, slip[w] += run.slip_rms / 3;
    }
  std::printf(
      "mean of 3 starts: accel RMS %.1f / %.1f m/s^2 (x%.2f), cage slip RMS %.2f / %.2f %% "
      "(x%.2f)\n",
      accel[0],
      accel[1],
      accel[1] / accel[0],
      slip[0],
      slip[1],
      slip[1] / slip[0]);
  EXPECT_GT(accel[1], 3.0 * accel[0]);
  EXPECT_GT(slip[1], 1.2 * slip[0]);
}

// Where the width trend turns (docs/PAPER.md, "Width"): with 2 mm of the roller's length intact
// (a 7 mm spall) that part alone is pressed in by about 35 um under the most loaded roller's
// load, so the spall's rims reach the races up to about 0.9 / 1.0 mm (inner / outer) and no
// longer at 1.38 mm. The roller rolls throughout, and the 1.38 mm spall shakes the bearing less
// than the 0.92 mm one (eight starts of 0.3 s: 777 +- 38 against 1109 +- 23 m/s^2), where the
// through-length spall's rims would strike harder. Measured from 30 ms, past the first cage turn
// (24 ms) after the ramp: the spall starts facing the outer race, and whether the roller's start
// there holds it before its first load-zone passage depends on the cage's radial play (with
// 0.1 mm it rolls 71 % of 10-50 ms, 100 % from 30 ms; docs/BEARING_MODEL.md, "Cage"). Measured:
// x0.62 (x0.71 with 0.1 mm).
TEST(PaperStudyTest, WiderThanTheIntactPartCarriesTheRimsNoLongerStrike) {
  const PaperRun narrow = RunScene("width-0.92", {"defects.0.length_mm=7"}, 0.07, 0.03);
  const PaperRun wide = RunScene("width-1.38", {"defects.0.length_mm=7"}, 0.07, 0.03);
  std::printf("7 mm spall: accel RMS %.1f (0.92 mm) / %.1f (1.38 mm) m/s^2 (x%.2f)\n",
              narrow.accel_rms,
              wide.accel_rms,
              wide.accel_rms / narrow.accel_rms);
  EXPECT_GT(narrow.roller.rolling_fraction, 0.95);
  EXPECT_GT(wide.roller.rolling_fraction, 0.95);
  EXPECT_LT(wide.accel_rms, 0.85 * narrow.accel_rms);
}

}  // namespace
}  // namespace spallkit::sim
