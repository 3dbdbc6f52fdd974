// Heatmaps (kurtograms, spectrograms) rendered to PNG with a viridis colorbar.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace spallkit::plot {

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

}  // namespace spallkit::plot
