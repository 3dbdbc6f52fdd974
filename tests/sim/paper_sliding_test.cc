// The roller sliding measure (sim/bearing/roller_sliding.h) on synthetic spin records and
// against the kinematic spin; the paper's findings on hybrid runs: paper_study_slow_test.cc.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "core/bearing.h"
#include "core/constants.h"
#include "core/error.h"
#include "core/hdf5.h"
#include "sim/bearing/roller_sliding.h"
#include "sim/bearing/scene.h"
#include "study/dataset.h"
#include "study/study_plot.h"
#include "study/sweep.h"

namespace spallkit::sim {
namespace {

// N205EM at 1200 rpm: spin relative to the cage 361.5 rad/s against the inner ring
// (the kinematic spin, core/bearing.h), i.e. 2 pi BSF with BSF = 57.542 Hz.
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

// `spall plot study --y defective_*`: the quantities come from the case's [[defects]] rollers
// (two defective rollers, 4 ms hybrid runs at 6000 rpm); a healthy case has no point.
TEST(PaperStudyPlotTest, DefectiveRollerQuantitiesUseTheDefectiveRollers) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("spall_paper_plot_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const study::Sweep sweep =
      study::ParseSweep("[base]\nscene = \"" SPALLKIT_SOURCE_DIR
                        "/datasets/scenes/paper-verification.toml\"\n"
                        "[base.set]\n\"model.fidelity\" = \"hybrid\"\n\"mesh.size_mm\" = 2.0\n"
                        "\"run.duration_s\" = 0.004\n\"operation.ramp_s\" = 0.001\n"
                        "\"operation.load_ramp_s\" = 0.001\n\"operation.speed_rpm\" = 6000.0\n"
                        "[grid]\n\"defects.count\" = [0, 2]\n",
                        "<paper test>",
                        dir.string());
  study::DatasetOptions options;
  options.out_dir = (dir / "ds").string();
  options.workers = 2;
  ASSERT_EQ(study::RunDataset(sweep, options).failed, 0);
  study::StudyPlotOptions o;
  o.x = "defects.count";
  o.group_set = true;
  // The force RMS over both defective rollers' columns, from the case file itself.
  const h5::File f = h5::File::OpenReadOnly((dir / "ds" / "case-00001.h5").string());
  std::vector<size_t> dims;
  const std::vector<double> force = f.ReadDataset("/contact/roller_cage", &dims);
  double m2 = 0;
  for (size_t i = 0; i < dims[0]; ++i)
    for (int j : {0, 1}) m2 += force[i * dims[1] + j] * force[i * dims[1] + j];
  o.y = "defective_cage_force_rms";
  study::PlottedSeries s = study::PlotStudy(options.out_dir, o, (dir / "f.png").string());
  ASSERT_EQ(s.x.size(), 1u);  // the healthy case has no defective roller
  EXPECT_EQ(s.x[0], 2.0);
  EXPECT_NEAR(s.columns[0].second[0], std::sqrt(m2 / (2.0 * dims[0])), 1e-9);
  o.y = "defective_rolling_percent";
  s = study::PlotStudy(options.out_dir, o, (dir / "r.png").string());
  ASSERT_EQ(s.x.size(), 1u);
  EXPECT_GE(s.columns[0].second[0], 0.0);
  EXPECT_LE(s.columns[0].second[0], 100.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spallkit::sim
