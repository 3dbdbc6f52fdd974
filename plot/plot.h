// PNG rendering of line plots (spectra, envelope spectra, waveforms) and heatmaps (kurtograms,
// spectrograms) with OpenCV core/imgproc/imgcodecs.
//
// Why in C++: `spall diagnose` must leave a picture a person can read without Python. The look
// follows the usual scientific defaults: white background, black frame, light grid, ticks at
// "nice" values (1, 2, 5 x 10^k), anti-aliased Hershey Simplex text, a legend box, viridis for
// heatmaps. Nothing from OpenCV appears in this header, so users of the API need no OpenCV flags.
//
// Output is encoded in memory (cv::imencode) and written atomically (core/atomic_file.h); a bad
// path, empty data or inconsistent sizes throw spallkit::InputError with one line.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace spallkit::plot {

struct Rgb {
  unsigned char r = 0, g = 0, b = 0;
};

// The 10-colour Tableau palette (matplotlib's default cycle): PaletteColor(0) is blue,
// 1 orange, 2 green, 3 red, 4 purple, 5 brown, 6 pink, 7 grey, 8 olive, 9 cyan; wraps around.
Rgb PaletteColor(size_t index);

struct LineSeries {
  std::vector<double> x, y;  // same length; x empty = sample index 0, 1, 2, ...
  Rgb color;
  std::string label;       // legend entry; empty = not in the legend
  double thickness = 1.5;  // pixels
};

// A vertical line at x with a small label (fault-family lines k*f_b, sidebands, band edges).
// Labels are written rotated upwards just right of the line near the top of the plot area and are
// staggered downwards when they would overlap a previous label. Markers outside the x range are
// not drawn.
struct Marker {
  double x = 0;
  std::string label;  // may be empty
  Rgb color;
  bool dashed = true;
  bool thin = false;  // thinner and lighter line, smaller label: sidebands
};

struct LinePlot {
  static constexpr double kAuto = std::numeric_limits<double>::quiet_NaN();

  std::string title, x_label, y_label;  // put the units in the labels: "frequency (Hz)"
  std::vector<LineSeries> series;
  std::vector<Marker> markers;
  // Axis ranges; NaN = automatic (x: data range; y: data range with 5 % headroom, or, with
  // log_y, the positive data range widened to whole decades when it spans less than one).
  double x_min = kAuto, x_max = kAuto, y_min = kAuto, y_max = kAuto;
  bool log_y = false;              // values <= 0 are not drawn on a log axis
  int width = 1600, height = 800;  // pixels, each in [200, 8000]
  bool legend = true;              // legend box in the top-right corner (only entries with a label)
};

// Renders `plot` to a PNG file of exactly width x height pixels. Throws InputError for a path
// that cannot be written, a series whose x and y lengths differ, no finite point at all, or an
// empty/inverted axis range.
void WriteLinePlot(const std::string& png_path, const LinePlot& plot);
// The same, returned as PNG bytes (for tests, or for embedding).
std::vector<unsigned char> RenderLinePlotPng(const LinePlot& plot);

// A grid of values drawn as coloured cells with a viridis colorbar.
//
// Geometry: `values` is row-major, rows x cols. Column j covers x in
// [x_min + j*(x_max-x_min)/cols, x_min + (j+1)*(x_max-x_min)/cols]. Rows likewise cover
// [y_min, y_max], with row 0 at the y_min edge. With row0_at_top (the default, as in a kurtogram
// where level 0 is the top row) y_min is at the TOP of the image and the y axis increases
// downwards; set row0_at_top = false for spectrogram-like data (frequency rows, y_min at the
// bottom).
struct Heatmap {
  static constexpr double kAuto = std::numeric_limits<double>::quiet_NaN();

  std::string title, x_label, y_label, colorbar_label;
  std::vector<double> values;  // rows*cols, row-major; NaN cells are drawn light grey
  int rows = 0, cols = 0;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  double v_min = kAuto, v_max = kAuto;  // colour range; NaN = finite data range
  // Optional categorical row labels (kurtogram levels "0", "1", "1.6", ...): when its size equals
  // `rows`, each row is labelled at its centre instead of numeric y ticks.
  std::vector<std::string> y_tick_labels;
  bool row0_at_top = true;
  // Optional highlighted cell (the chosen kurtogram band): a white frame; -1 = none.
  int highlight_row = -1, highlight_col = -1;
  int width = 1400, height = 800;
};

// Renders `map` to a PNG of exactly width x height pixels (viridis, colorbar with ticks and
// label). Throws InputError on a bad path, rows*cols != values.size(), no finite value, or an
// empty x/y range.
void WriteHeatmap(const std::string& png_path, const Heatmap& map);
std::vector<unsigned char> RenderHeatmapPng(const Heatmap& map);

// "Nice" tick positions covering [lo, hi] with about `target` intervals: steps of 1, 2 or 5 x
// 10^k, every tick inside [lo, hi] (within a rounding tolerance). Exposed for tests and for
// callers that label their own axes.
std::vector<double> NiceTicks(double lo, double hi, int target = 8);
// Formats a tick value with the fewest digits that tell neighbouring ticks apart (`step`);
// "0" for values within step*1e-9 of zero, exponent form for very large or small values.
std::string FormatTick(double value, double step);

}  // namespace spallkit::plot
