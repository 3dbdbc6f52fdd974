// Colours of plots: RGB triples and the default series palette.
#pragma once

#include <cstddef>

namespace spallkit::plot {

struct Rgb {
  unsigned char r = 0, g = 0, b = 0;
};

// The 10-colour Tableau palette (matplotlib's default cycle): PaletteColor(0) is blue,
// 1 orange, 2 green, 3 red, 4 purple, 5 brown, 6 pink, 7 grey, 8 olive, 9 cyan; wraps around.
Rgb PaletteColor(size_t index);

}  // namespace spallkit::plot
