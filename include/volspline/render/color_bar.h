#pragma once
// The key to a picture coloured by a scalar: a vertical strip of the colour map with the values
// at its ends and middle and the field's name above it.
#include <string>

#include "volspline/render/colormap.h"
#include "volspline/render/image.h"

namespace volspline {

struct ColorBar {
  Colormap map = Colormap::Sequential;
  double min = 0;
  double max = 1;
  /// Shown above the strip (for example "jacobian").
  std::string title;
};

/// Columns at the right of a picture of this size that draw_color_bar uses.
int color_bar_width(int width, int height);

/// Draws `bar` into the rightmost color_bar_width columns of `image`.
void draw_color_bar(Image& image, const ColorBar& bar);

/// A short label for a value on a bar: 4 significant digits, no trailing noise.
std::string color_bar_label(double value);

}  // namespace volspline
