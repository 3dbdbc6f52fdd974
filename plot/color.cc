#include "plot/color.h"

namespace spallkit::plot {

Rgb PaletteColor(size_t index) {
  static const Rgb kTableau[10] = {{31, 119, 180},
                                   {255, 127, 14},
                                   {44, 160, 44},
                                   {214, 39, 40},
                                   {148, 103, 189},
                                   {140, 86, 75},
                                   {227, 119, 194},
                                   {127, 127, 127},
                                   {188, 189, 34},
                                   {23, 190, 207}};
  return kTableau[index % 10];
}

}  // namespace spallkit::plot
