// spall plot on a CSV record, on a simulation's HDF5 and on a dataset folder: PNGs of the asked
// size that are not blank, CSV exports of what was plotted (the sample's SES peaks at f_b), and
// one-line errors for a bad path or kind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/record_io.h"
#include "tests/apps/run_spall.h"
#include "tests/study/dataset_test_sweep.h"

namespace spallkit {
namespace {
namespace fs = std::filesystem;
using testing::RunSpall;

const std::string kSample =
    std::string(SPALLKIT_SOURCE_DIR) + "/datasets/samples/n205em_roller_defect_1200rpm.csv";

std::string Scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("spall_plot_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// The PNG has the size asked for and shows something besides the white background and frame.
void ExpectPlot(const std::string& png, int width = 1600, int height = 800) {
  const cv::Mat img = cv::imread(png, cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty()) << png;
  EXPECT_EQ(img.cols, width);
  EXPECT_EQ(img.rows, height);
  // Coloured (not grey) pixels: data lines, markers or a heatmap.
  int coloured = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      const int spread = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
      coloured += spread > 40;
    }
  EXPECT_GT(coloured, 200) << png;
}

TEST(PlotCliTest, EnvelopeOfTheCsvSampleShowsFbWithMarkers) {
  const std::string dir = Scratch("csv");
  const auto r = RunSpall("plot " + kSample +
                          " --kind envelope --band 2500:3500 --bearing N205EM --rpm 1200 -o " +
                          dir + "/ses.png --csv " + dir + "/ses.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  ExpectPlot(dir + "/ses.png");
  // The exported SES: its largest line between 50 and 300 Hz is f_b = 115.08 Hz.
  RecordOptions o;
  o.sample_rate_hz = 1.0;  // the x column is frequency, not time
  o.channel = "SES";
  const Record ses = ReadCsvRecord(dir + "/ses.csv", o);
  RecordOptions ox = o;
  ox.channel = "cyclic frequency alpha (Hz)";
  const Record alpha = ReadCsvRecord(dir + "/ses.csv", ox);
  double best = 0, best_hz = 0;
  for (size_t i = 0; i < ses.samples.size(); ++i)
    if (alpha.samples[i] > 50 && alpha.samples[i] < 300 && ses.samples[i] > best)
      best = ses.samples[i], best_hz = alpha.samples[i];
  EXPECT_NEAR(best_hz, 115.08, 2.0);

  for (const char* kind : {"time", "spectrum", "spectrogram"}) {
    const std::string png = dir + "/" + kind + ".png";
    const auto k = RunSpall("plot " + kSample + " --kind " + kind +
                            " --from-s 0.5 --to-s 1.5 --width 800 --height 500 -o " + png);
    ASSERT_EQ(k.code, 0) << kind << ": " << k.err;
    ExpectPlot(png, 800, 500);
  }
  fs::remove_all(dir);
}

TEST(PlotCliTest, EveryKindOfASimulationFile) {
  const std::string dir = Scratch("h5");
  const std::string h5 = dir + "/run.h5";
  const auto sim = RunSpall("simulate " + std::string(SPALLKIT_SOURCE_DIR) +
                            "/datasets/scenes/paper-verification.toml --quiet"
                            " --set model.fidelity=hybrid --set mesh.size_mm=2.0"
                            " --set run.duration_s=0.01 --set operation.ramp_s=0.001"
                            " --set operation.load_ramp_s=0.001 -o " +
                            h5);
  ASSERT_EQ(sim.code, 0) << sim.err;
  for (const char* kind :
       {"time", "spectrum", "envelope", "spectrogram", "orbit", "contact", "cage"}) {
    const std::string png = dir + "/" + kind + ".png";
    const auto r = RunSpall("plot " + h5 + " --kind " + kind + " -o " + png + " --csv " + dir +
                            "/" + kind + ".csv");
    ASSERT_EQ(r.code, 0) << kind << ": " << r.err;
    ExpectPlot(png);
    EXPECT_GT(fs::file_size(dir + "/" + kind + ".csv"), 100u) << kind;
  }
  // The contact CSV holds one column per roller (N205EM: 13) after the time column.
  std::ifstream in(dir + "/contact.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), 13) << header;
  fs::remove_all(dir);
}

TEST(PlotCliTest, StudyOfADatasetFolderHasOneLinePerGroup) {
  const std::string dir = Scratch("study");
  const std::string sweep = study::WriteTinySweep(dir, 1);  // widths x speeds = 6 cases
  const auto run = RunSpall("dataset run " + sweep + " --out " + dir + "/ds --quiet");
  ASSERT_EQ(run.code, 0) << run.err;
  const auto r = RunSpall("plot study " + dir + "/ds --x defects.0.width_mm --y accel_rms -o " +
                          dir + "/trend.png --csv " + dir + "/trend.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  ExpectPlot(dir + "/trend.png");
  std::ifstream in(dir + "/trend.csv");
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 7u);  // header + 2 speeds x 3 widths
  EXPECT_EQ(lines[0], "group,defects.0.width_mm,accel_rms,cases,std");
  EXPECT_EQ(lines[1].rfind("\"operation.speed_rpm = 1000.0\",0.8,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[6].rfind("\"operation.speed_rpm = 2000.0\",2.2,", 0), 0u) << lines[6];
  // One line: each width's point averages the two speeds, its std their sample deviation.
  const auto one = RunSpall("plot study " + dir + "/ds --x defects.0.width_mm --y accel_rms " +
                            "--one-line -o " + dir + "/one.png --csv " + dir + "/one.csv");
  ASSERT_EQ(one.code, 0) << one.err;
  auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line.substr(line.rfind('"') + 2));  // after the quoted group
    for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
    return out;  // x, y, cases, std
  };
  std::ifstream one_in(dir + "/one.csv");
  std::vector<std::string> one_lines;
  for (std::string l; std::getline(one_in, l);) one_lines.push_back(l);
  ASSERT_EQ(one_lines.size(), 4u);  // header + 3 widths
  for (int w = 0; w < 3; ++w) {
    const auto a = cells(lines[1 + w]), b = cells(lines[4 + w]), m = cells(one_lines[1 + w]);
    ASSERT_EQ(m.size(), 4u) << one_lines[1 + w];
    const double ya = std::stod(a[1]), yb = std::stod(b[1]);
    EXPECT_EQ(m[2], "2");
    EXPECT_NEAR(std::stod(m[1]), 0.5 * (ya + yb), 1e-9 * std::abs(ya + yb));
    EXPECT_NEAR(std::stod(m[3]), std::abs(ya - yb) / std::sqrt(2.0), 1e-9 * std::abs(ya + yb));
    EXPECT_EQ(cells(lines[1 + w])[3], "0.0");  // one case: no spread
  }
  // A label on y, cage quantity, and an unknown quantity.
  EXPECT_EQ(RunSpall("plot study " + dir + "/ds --x speed_rpm --y f_b_hz --one-line -o " + dir +
                     "/fb.png")
                .code,
            0);
  EXPECT_EQ(
      RunSpall("plot study " + dir + "/ds --x width_mm --y cage_slip_rms -o " + dir + "/slip.png")
          .code,
      0);
  const auto bad =
      RunSpall("plot study " + dir + "/ds --x width_mm --y nonsense -o " + dir + "/x.png");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--y nonsense"), std::string::npos) << bad.err;
  fs::remove_all(dir);
}

TEST(PlotCliTest, BadPathKindOrFileTypeGiveOneLineErrors) {
  const std::string dir = Scratch("bad");
  struct Case {
    std::string args, expect;
  } cases[] = {
      {"plot " + dir + "/missing.csv --kind spectrum -o " + dir + "/a.png", "missing.csv"},
      {"plot " + kSample + " --kind bode -o " + dir + "/a.png", "--kind 'bode'"},
      {"plot " + kSample + " --kind orbit -o " + dir + "/a.png", "needs a simulation's HDF5"},
      {"plot " + kSample + " --kind time --from-s 5 -o " + dir + "/a.png", "time window"},
      {"plot study " + dir + " --x a --y accel_rms -o " + dir + "/a.png", "no index"},
  };
  for (const Case& c : cases) {
    const auto r = RunSpall(c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/a.png"));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spallkit
