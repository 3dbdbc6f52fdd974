// Axis tick positions and labels.
#pragma once

#include <string>
#include <vector>

namespace spallkit::plot {

// "Nice" tick positions covering [lo, hi] with about `target` intervals: steps of 1, 2 or 5 x
// 10^k, every tick inside [lo, hi] (within a rounding tolerance). Exposed for tests and for
// callers that label their own axes.
std::vector<double> NiceTicks(double lo, double hi, int target = 8);
// Formats a tick value with the fewest digits that tell neighbouring ticks apart (`step`);
// "0" for values within step*1e-9 of zero, exponent form for very large or small values.
std::string FormatTick(double value, double step);

}  // namespace spallkit::plot
