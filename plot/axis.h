// Data-to-pixel axes, their ticks and data ranges: shared by the line plot and heatmap
// renderers (internal to plot/).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace spallkit::plot::internal {

// A linear or log10 axis mapping data values to pixels.
struct Axis {
  double lo = 0, hi = 1;  // data range (positive for log)
  bool log = false;
  double p0 = 0, p1 = 1;  // pixel positions of lo and hi
  double T(double v) const { return log ? std::log10(v) : v; }
  double ToPixel(double v) const { return p0 + (T(v) - T(lo)) / (T(hi) - T(lo)) * (p1 - p0); }
};

struct Tick {
  double value;
  std::string label;  // empty for minor ticks
};

// About `target` linear ticks over [lo, hi], labelled (plot/ticks.h).
std::vector<Tick> LinearTicks(double lo, double hi, int target);
// Log ticks: labelled decades; 2 and 5 labelled as well when the range spans few decades;
// unlabelled minor ticks at 2..9 otherwise.
std::vector<Tick> LogTicks(double lo, double hi);

// The range of the finite values added.
struct Range {
  double lo = 0, hi = 0;
  bool valid = false;
  void Add(double v) {
    if (!std::isfinite(v)) return;
    if (!valid) {
      lo = hi = v;
      valid = true;
    } else {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
};

}  // namespace spallkit::plot::internal
