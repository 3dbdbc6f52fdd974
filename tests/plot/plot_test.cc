// Tests for PNG rendering: tick arithmetic, and rendered images checked pixel by pixel (size,
// frame, data colour where the data is, viridis ends of the colorbar). Set SPALLKIT_PLOT_DIR to
// keep the images for a look.
#include "plot/plot.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace spallkit::plot {
namespace {

namespace fs = std::filesystem;

class PlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* keep = std::getenv("SPALLKIT_PLOT_DIR");
    keep_ = keep != nullptr;
    dir_ = keep ? fs::path(keep)
                : fs::temp_directory_path() / ("spallkit_plot_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!keep_) fs::remove_all(dir_);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  bool keep_ = false;
};

// Pixels within `tol` of colour c (per channel).
int CountColor(const cv::Mat& img, Rgb c, int tol = 40) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r) {
    for (int col = 0; col < img.cols; ++col) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, col);
      if (std::abs(p[2] - c.r) <= tol && std::abs(p[1] - c.g) <= tol &&
          std::abs(p[0] - c.b) <= tol) {
        ++n;
      }
    }
  }
  return n;
}

// Longest run of dark pixels along any column / row: the plot frame is one.
int LongestDarkVerticalRun(const cv::Mat& img) {
  int best = 0;
  for (int c = 0; c < img.cols; ++c) {
    int run = 0;
    for (int r = 0; r < img.rows; ++r) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      run = (p[0] < 60 && p[1] < 60 && p[2] < 60) ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best;
}
int LongestDarkHorizontalRun(const cv::Mat& img) {
  int best = 0;
  for (int r = 0; r < img.rows; ++r) {
    int run = 0;
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      run = (p[0] < 60 && p[1] < 60 && p[2] < 60) ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best;
}

TEST(NiceTicks, StepsAreOneTwoFiveTimesAPowerOfTenAndStayInRange) {
  EXPECT_EQ(NiceTicks(0, 100, 5), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(NiceTicks(0, 1000, 10).size(), 11u);
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0.013, 0.087}, {-3.7, 12.2}, {1e-7, 9e-6}, {115.08, 2000}, {-1e9, 3e9}}) {
    const std::vector<double> t = NiceTicks(lo, hi, 8);
    ASSERT_GE(t.size(), 3u) << lo << " " << hi;
    ASSERT_LE(t.size(), 16u) << lo << " " << hi;
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                std::abs(mantissa - 5) < 1e-9)
        << step;
    for (double v : t) {
      EXPECT_GE(v, lo - 1e-9 * step);
      EXPECT_LE(v, hi + 1e-9 * step);
      EXPECT_NEAR(std::remainder(v, step), 0, 1e-9 * step);  // on the step grid
    }
  }
  EXPECT_EQ(NiceTicks(3, 3), std::vector<double>{3});
}

TEST(FormatTick, UsesTheDigitsTheStepNeeds) {
  EXPECT_EQ(FormatTick(0.5, 0.1), "0.5");
  EXPECT_EQ(FormatTick(1e-17, 0.1), "0");
  EXPECT_EQ(FormatTick(200, 50), "200");
  EXPECT_EQ(FormatTick(2.5, 0.25), "2.50");
  EXPECT_EQ(FormatTick(1.5e6, 5e5), "1.5e6");
  EXPECT_EQ(FormatTick(2e-5, 1e-5), "2e-5");
  EXPECT_EQ(FormatTick(-0.02, 0.01), "-0.02");
}

TEST(PaletteColor, IsTableauAndWraps) {
  EXPECT_EQ(PaletteColor(0).r, 31);
  EXPECT_EQ(PaletteColor(3).r, 214);
  EXPECT_EQ(PaletteColor(13).g, PaletteColor(3).g);
}

// An envelope-spectrum-like plot: lines at k*f_b with +/- f_c sidebands.
LinePlot EnvelopeSpectrumPlot() {
  const double fb = 115.08, fc = 8.31;
  LinePlot plot;
  plot.title = "Squared envelope spectrum, band 2500-3500 Hz";
  plot.x_label = "frequency (Hz)";
  plot.y_label = "SES amplitude ((m/s^2)^2)";
  LineSeries ses;
  ses.color = PaletteColor(0);
  ses.label = "SES";
  for (int i = 0; i <= 4000; ++i) {
    const double f = i * 0.125;
    double y = 0.02 + 0.01 * std::sin(f * 0.37) * std::sin(f * 0.11);
    for (int k = 1; k <= 4; ++k) {
      y += 1.0 / k * std::exp(-std::pow((f - k * fb) / 0.4, 2));
      y += 0.3 / k * std::exp(-std::pow((f - k * fb - fc) / 0.4, 2));
      y += 0.3 / k * std::exp(-std::pow((f - k * fb + fc) / 0.4, 2));
    }
    ses.x.push_back(f);
    ses.y.push_back(y);
  }
  plot.series.push_back(ses);
  for (int k = 1; k <= 4; ++k) {
    plot.markers.push_back({k * fb, std::to_string(k) + "f_b", PaletteColor(3), true, false});
    plot.markers.push_back({k * fb - fc, "-f_c", PaletteColor(1), true, true});
    plot.markers.push_back({k * fb + fc, "+f_c", PaletteColor(1), true, true});
  }
  plot.markers.push_back({fc, "f_c", PaletteColor(2), true, false});
  plot.x_min = 0;
  plot.x_max = 500;
  return plot;
}

TEST_F(PlotTest, LinePlotIsAPngOfTheRequestedSizeWithFrameDataAndMarkers) {
  const LinePlot plot = EnvelopeSpectrumPlot();
  const std::string path = Path("envelope_spectrum.png");
  WriteLinePlot(path, plot);
  const cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty()) << "not a readable PNG";
  EXPECT_EQ(img.cols, 1600);
  EXPECT_EQ(img.rows, 800);
  // Frame: dark runs over most of the height and width.
  EXPECT_GT(LongestDarkVerticalRun(img), 800 / 2);
  EXPECT_GT(LongestDarkHorizontalRun(img), 1600 / 2);
  // The series, the fault-line markers and the sideband markers are all visible.
  EXPECT_GT(CountColor(img, PaletteColor(0)), 2000);
  EXPECT_GT(CountColor(img, PaletteColor(3), 30), 500);
  EXPECT_GT(CountColor(img, PaletteColor(2), 30), 100);
  cv::Scalar mean, stddev;
  cv::meanStdDev(img, mean, stddev);
  EXPECT_GT(stddev[0], 10) << "blank image";
}

TEST_F(PlotTest, PeaksSurviveDecimationOfLongSeries) {
  // One sample out of a million reaches the top; min/max decimation per pixel column must keep it.
  LinePlot plot;
  plot.title = "spike";
  plot.width = 800;
  plot.height = 400;
  plot.legend = false;
  LineSeries s;
  s.color = PaletteColor(3);
  s.y.assign(1000000, 0.0);
  s.y[654321] = 1.0;
  plot.series.push_back(s);
  std::vector<unsigned char> png = RenderLinePlotPng(plot);
  const cv::Mat img = cv::imdecode(png, cv::IMREAD_COLOR);
  ASSERT_EQ(img.cols, 800);
  // Find the top-most red pixel: it must be in the upper fifth of the image.
  int top_red = img.rows;
  for (int r = 0; r < img.rows && top_red == img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      if (p[2] > 180 && p[1] < 90 && p[0] < 90) {
        top_red = r;
        break;
      }
    }
  }
  EXPECT_LT(top_red, img.rows / 5);
}

TEST_F(PlotTest, LogAxisAndAutoRanges) {
  LinePlot plot;
  plot.title = "Spectrum (log)";
  plot.x_label = "frequency (Hz)";
  plot.y_label = "PSD (g^2/Hz)";
  plot.log_y = true;
  plot.width = 1000;
  plot.height = 500;
  LineSeries s;
  s.color = PaletteColor(0);
  s.label = "PSD";
  for (int i = 0; i < 2000; ++i) {
    s.x.push_back(i * 5.0);
    s.y.push_back(1e-6 + 1e-2 / (1 + std::pow((i * 5.0 - 3000) / 200, 2)) + (i == 0 ? -1 : 0));
  }
  plot.series.push_back(s);
  const std::string path = Path("log_spectrum.png");
  WriteLinePlot(path, plot);
  const cv::Mat img = cv::imread(path);
  ASSERT_EQ(img.cols, 1000);
  ASSERT_EQ(img.rows, 500);
  EXPECT_GT(CountColor(img, PaletteColor(0)), 1000);
}

// A scatter on log axes (the fidelity ladder's Pareto plot): points a decade apart in x and y
// land equally far apart in pixels, each a filled dot; a log x axis without a positive x throws.
TEST_F(PlotTest, ScatterOnLogAxesSpacesDecadesEqually) {
  LinePlot plot;
  plot.title = "Pareto";
  plot.log_x = plot.log_y = true;
  plot.legend = false;
  plot.width = 1000;
  plot.height = 600;
  LineSeries s;
  s.points = true;
  s.color = PaletteColor(0);
  s.x = {1.0, 10.0, 100.0};
  s.y = {100.0, 10.0, 1.0};
  s.point_labels = {"a", "b", "c"};
  plot.series.push_back(s);
  const cv::Mat img = cv::imdecode(RenderLinePlotPng(plot), cv::IMREAD_COLOR);
  ASSERT_EQ(img.cols, 1000);
  // Centroids of the blue dots, split into three clusters by column.
  std::vector<double> sx(3, 0), sy(3, 0), n(3, 0);
  double x_lo = img.cols, x_hi = 0;
  std::vector<cv::Point> blue;
  for (int r = 0; r < img.rows; ++r)
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      const Rgb k = PaletteColor(0);
      if (std::abs(p[2] - k.r) < 30 && std::abs(p[1] - k.g) < 30 && std::abs(p[0] - k.b) < 30) {
        blue.push_back({c, r});
        x_lo = std::min<double>(x_lo, c), x_hi = std::max<double>(x_hi, c);
      }
    }
  ASSERT_GT(blue.size(), 30u);
  for (const cv::Point& q : blue) {
    const int k = std::min(2, static_cast<int>(3 * (q.x - x_lo) / (x_hi - x_lo + 1)));
    sx[k] += q.x, sy[k] += q.y, n[k] += 1;
  }
  for (int k = 0; k < 3; ++k) {
    ASSERT_GT(n[k], 10) << k;
    sx[k] /= n[k], sy[k] /= n[k];
  }
  EXPECT_NEAR(sx[1] - sx[0], sx[2] - sx[1], 3.0);
  EXPECT_NEAR(sy[1] - sy[0], sy[2] - sy[1], 3.0);
  EXPECT_GT(sy[1], sy[0]);  // y falls as x rises: lower on the image
  plot.series[0].x = {-1.0, 0.0, 0.0};
  EXPECT_THROW(RenderLinePlotPng(plot), InputError);
}

TEST_F(PlotTest, ErrorBarsSpanTheirPointsSpreadAndAreInTheRange) {
  LinePlot plot;
  plot.title = "trend";
  plot.legend = false;
  plot.width = 800;
  plot.height = 600;
  LineSeries s;
  s.color = PaletteColor(1);
  s.x = {0.0, 1.0, 2.0};
  s.y = {1.0, 1.0, 1.0};
  s.y_error = {0.5, 0.0, NAN};  // a bar on the first point only
  plot.series.push_back(s);
  LineSeries floor;  // a second line at 0: the data span [0, 1]
  floor.color = PaletteColor(2);
  floor.x = s.x;
  floor.y = {0.0, 0.0, 0.0};
  plot.series.push_back(floor);
  const cv::Mat img = cv::imdecode(RenderLinePlotPng(plot), cv::IMREAD_COLOR);
  // First and last rows holding the first series' colour in a band of columns.
  auto rows_with_colour = [&](int c0, int c1) {
    int lo = img.rows, hi = -1;
    const Rgb k = PaletteColor(1);
    for (int r = 0; r < img.rows; ++r)
      for (int c = c0; c < c1; ++c) {
        const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
        if (std::abs(p[2] - k.r) < 30 && std::abs(p[1] - k.g) < 30 && std::abs(p[0] - k.b) < 30)
          lo = std::min(lo, r), hi = std::max(hi, r);
      }
    return std::make_pair(lo, hi);
  };
  // The bar (1 +/- 0.5) spans a good part of the plot's height; the line elsewhere is a few
  // pixels thick, and the range reaches the bar's top (1.5), so the line at 1 sits a third of
  // the way down instead of at the top (5 % headroom above the data's 1).
  const auto bar = rows_with_colour(0, img.cols / 3);
  const auto line = rows_with_colour(img.cols * 2 / 3, img.cols);
  EXPECT_GT(bar.second - bar.first, img.rows / 4);
  EXPECT_LT(line.second - line.first, 12);
  EXPECT_GT(line.first, img.rows / 4);
  plot.series[0].y_error = {0.5, 0.5};  // one bar fewer than points
  EXPECT_THROW(RenderLinePlotPng(plot), InputError);
}

TEST_F(PlotTest, LinePlotBadInputsThrowInputError) {
  LinePlot plot = EnvelopeSpectrumPlot();
  EXPECT_THROW(WriteLinePlot(Path("no/such/dir/x.png"), plot), InputError);
  try {
    WriteLinePlot(Path("no/such/dir/x.png"), plot);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/dir/x.png"), std::string::npos) << e.what();
  }
  LinePlot bad = plot;
  bad.series[0].x.pop_back();
  EXPECT_THROW(WriteLinePlot(Path("bad.png"), bad), InputError);
  bad = plot;
  for (double& y : bad.series[0].y) y = NAN;
  EXPECT_THROW(WriteLinePlot(Path("bad.png"), bad), InputError);
  bad = plot;
  bad.width = 10;
  EXPECT_THROW(WriteLinePlot(Path("bad.png"), bad), InputError);
  bad = plot;
  bad.x_min = 600;  // above x_max = 500
  EXPECT_THROW(WriteLinePlot(Path("bad.png"), bad), InputError);
  bad = plot;
  bad.log_y = true;
  bad.y_min = -1;
  EXPECT_THROW(WriteLinePlot(Path("bad.png"), bad), InputError);
  EXPECT_FALSE(fs::exists(Path("bad.png")));
}

// A kurtogram-like map: 2*L rows (levels), value peak near one cell.
Heatmap KurtogramMap() {
  Heatmap map;
  map.title = "Fast kurtogram, max K = 12.3 at level 3.6, fc = 3000 Hz, bw = 833 Hz";
  map.x_label = "frequency (Hz)";
  map.y_label = "level";
  map.colorbar_label = "spectral kurtosis";
  map.rows = 12;
  map.cols = 3 * 64;
  map.x_min = 0;
  map.x_max = 10000;
  map.y_min = 0;
  map.y_max = 12;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const double f = (c + 0.5) / map.cols * 10000;
      const double width = 300 + 4000.0 / (r + 1);
      map.values.push_back(12.3 * std::exp(-std::pow((f - 3000) / width, 2)) *
                           std::exp(-std::pow((r - 7) / 4.0, 2)));
    }
  }
  const char* levels[] = {"0", "1", "1.6", "2", "2.6", "3", "3.6", "4", "4.6", "5", "5.6", "6"};
  for (const char* l : levels) map.y_tick_labels.push_back(l);
  map.highlight_row = 7;
  map.highlight_col = 57;
  return map;
}

TEST_F(PlotTest, HeatmapUsesViridisWithColorbarAndRowZeroOnTop) {
  Heatmap map = KurtogramMap();
  const std::string path = Path("kurtogram.png");
  WriteHeatmap(path, map);
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 1400);
  EXPECT_EQ(img.rows, 800);
  // Viridis ends: yellow (253, 231, 37) and dark purple (68, 1, 84).
  EXPECT_GT(CountColor(img, {253, 231, 37}, 25), 50);
  EXPECT_GT(CountColor(img, {68, 1, 84}, 25), 5000);
  EXPECT_GT(LongestDarkVerticalRun(img), 800 / 2);

  // Orientation: a map whose row 0 is the maximum has yellow at the top of the cell area.
  Heatmap ramp;
  ramp.rows = 4;
  ramp.cols = 3;
  ramp.values = {3, 3, 3, 2, 2, 2, 1, 1, 1, 0, 0, 0};
  ramp.width = 600;
  ramp.height = 400;
  auto yellow_row_fraction = [&](const Heatmap& m) {
    const cv::Mat im = cv::imdecode(RenderHeatmapPng(m), cv::IMREAD_COLOR);
    double sum = 0;
    int n = 0;
    for (int r = 0; r < im.rows; ++r) {
      for (int c = 0; c < im.cols * 2 / 3; ++c) {  // left of the colorbar
        const cv::Vec3b p = im.at<cv::Vec3b>(r, c);
        if (std::abs(p[2] - 253) < 25 && std::abs(p[1] - 231) < 25 && std::abs(p[0] - 37) < 25) {
          sum += r;
          ++n;
        }
      }
    }
    return n ? sum / n / im.rows : -1.0;
  };
  EXPECT_LT(yellow_row_fraction(ramp), 0.4);
  ramp.row0_at_top = false;
  EXPECT_GT(yellow_row_fraction(ramp), 0.6);
}

TEST_F(PlotTest, SpectrogramLikeHeatmapWithNumericAxes) {
  Heatmap map;
  map.title = "Spectrogram";
  map.x_label = "time (s)";
  map.y_label = "frequency (Hz)";
  map.colorbar_label = "PSD (dB)";
  map.rows = 129;
  map.cols = 200;
  map.x_min = 0;
  map.x_max = 2;
  map.y_min = 0;
  map.y_max = 10000;
  map.row0_at_top = false;
  map.v_min = -80;
  map.v_max = 0;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      map.values.push_back(std::abs(r - 38) < 3 ? -5.0 : (c % 23 == 0 ? -20.0 : -70.0 + r * 0.1));
    }
  }
  map.values[5] = NAN;  // drawn grey, not an error
  const std::string path = Path("spectrogram.png");
  WriteHeatmap(path, map);
  const cv::Mat img = cv::imread(path);
  ASSERT_EQ(img.cols, 1400);
  ASSERT_EQ(img.rows, 800);
}

TEST_F(PlotTest, HeatmapBadInputsThrowInputError) {
  Heatmap map = KurtogramMap();
  EXPECT_THROW(WriteHeatmap(Path("no/such/dir/k.png"), map), InputError);
  Heatmap bad = map;
  bad.values.pop_back();
  EXPECT_THROW(WriteHeatmap(Path("bad.png"), bad), InputError);
  bad = map;
  bad.x_max = bad.x_min;
  EXPECT_THROW(WriteHeatmap(Path("bad.png"), bad), InputError);
  bad = map;
  for (double& v : bad.values) v = NAN;
  EXPECT_THROW(WriteHeatmap(Path("bad.png"), bad), InputError);
  bad = map;
  bad.v_min = 1;
  bad.v_max = 1;
  EXPECT_THROW(WriteHeatmap(Path("bad.png"), bad), InputError);
}

}  // namespace
}  // namespace spallkit::plot
