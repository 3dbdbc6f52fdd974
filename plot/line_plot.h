// Line plots (spectra, envelope spectra, waveforms, trends) rendered to PNG: series, vertical
// markers with labels, scatter points with labels, linear or log axes, legend.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "plot/color.h"

namespace spallkit::plot {

struct LineSeries {
  std::vector<double> x, y;  // same length; x empty = sample index 0, 1, 2, ...
  Rgb color;
  std::string label;       // legend entry; empty = not in the legend
  double thickness = 1.5;  // pixels
  // Scatter: a filled dot at each point instead of a line (a Pareto plot's one point per rung),
  // each labelled with point_labels[i] when given (right of the dot).
  bool points = false;
  std::vector<std::string> point_labels;
  // Empty, or one value per point: a vertical bar of +/- y_error[i] with caps and a dot at the
  // point (the spread of the cases a trend's point averages); 0 or NaN draws none there.
  std::vector<double> y_error;
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
  bool log_x = false;              // the same for x (positive x data range, decade ticks)
  int width = 1600, height = 800;  // pixels, each in [200, 8000]
  bool legend = true;              // legend box in the top-right corner (only entries with a label)
};

// Renders `plot` to a PNG file of exactly width x height pixels. Throws InputError for a path
// that cannot be written, a series whose x and y lengths differ, no finite point at all, or an
// empty/inverted axis range.
void WriteLinePlot(const std::string& png_path, const LinePlot& plot);
// The same, returned as PNG bytes (for tests, or for embedding).
std::vector<unsigned char> RenderLinePlotPng(const LinePlot& plot);

}  // namespace spallkit::plot
