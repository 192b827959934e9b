#include "volspline/render/color_bar.h"

#include <gtest/gtest.h>

#include <cmath>

#include "volspline/render/colormap.h"
#include "volspline/render/text.h"

namespace volspline {
namespace {

double luminance(const Eigen::Vector3d& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

TEST(Colormap, SequentialLightnessIncreasesAndDivergingIsLightInTheMiddle) {
  double previous = -1;
  for (int i = 0; i <= 50; ++i) {
    const double l = luminance(colormap_color(Colormap::Sequential, i / 50.0));
    EXPECT_GT(l, previous);
    previous = l;
  }
  const double middle = luminance(colormap_color(Colormap::Diverging, 0.5));
  EXPECT_GT(middle, luminance(colormap_color(Colormap::Diverging, 0.0)));
  EXPECT_GT(middle, luminance(colormap_color(Colormap::Diverging, 1.0)));
  EXPECT_EQ(colormap_color(Colormap::Sequential, -3), colormap_color(Colormap::Sequential, 0));
  EXPECT_EQ(colormap_color(Colormap::Sequential, 7), colormap_color(Colormap::Sequential, 1));
}

TEST(Colormap, SuggestedColoringCentresSignedFieldsOfBothSignsOnZero) {
  const auto both = suggested_coloring({-1.0, 0.5, 3.0}, true);
  EXPECT_EQ(both.map, Colormap::Diverging);
  EXPECT_EQ(both.min, -3.0);
  EXPECT_EQ(both.max, 3.0);
  const auto positive = suggested_coloring({1.0, 0.5, 3.0}, true);
  EXPECT_EQ(positive.map, Colormap::Sequential);
  EXPECT_EQ(positive.min, 0.5);
  const auto unsigned_field = suggested_coloring({-1.0, 2.0}, false);
  EXPECT_EQ(unsigned_field.map, Colormap::Sequential);
  EXPECT_EQ(unsigned_field.min, -1.0);
}

TEST(Colormap, AConstantFieldGetsARangeCentredOnItsValue) {
  for (const double c : {0.0, 1.0, -2.5e-7, 1e-300, 4.9e-324, 1e300, -1.7976931348623157e308, 1.7976931348623157e308}) {
    for (const bool signed_field : {false, true}) {
      const ScalarColoring coloring = suggested_coloring({c, c, c}, signed_field);
      EXPECT_EQ(coloring.map, Colormap::Sequential);
      EXPECT_TRUE(std::isfinite(coloring.min) && std::isfinite(coloring.max)) << c;
      EXPECT_LT(coloring.min, coloring.max) << c;
      EXPECT_LE(coloring.min, c) << c;  // (the value is an end of the range within 1e-6 of ±DBL_MAX)
      EXPECT_GE(coloring.max, c) << c;
      // c sits in the middle: it draws the middle colour.
      const double t = (c - coloring.min) / (coloring.max - coloring.min);
      if (std::abs(c) < 1e300) {
        EXPECT_NEAR(t, 0.5, 1e-9) << c;
      }
    }
  }
  // Constant up to rounding is constant; a real spread keeps its ends.
  const ScalarColoring rounded = suggested_coloring({6.0, 6.0 * (1 + 1e-15), 6.0 * (1 - 2e-16)}, true);
  EXPECT_NEAR(0.5 * rounded.min + 0.5 * rounded.max, 6.0, 1e-14);
  EXPECT_GT(rounded.max - rounded.min, 1e-6);
  const ScalarColoring spread = suggested_coloring({6.0, 6.0 * (1 + 1e-9)}, false);
  EXPECT_EQ(spread.min, 6.0);
  EXPECT_EQ(spread.max, 6.0 * (1 + 1e-9));
  EXPECT_EQ(widened_range(-1.0, 2.0), std::make_pair(-1.0, 2.0));
}

TEST(Text, DrawsInkOnlyInsideItsBox) {
  Image image(200, 60, 255, 255, 255, 255);
  const auto size = text_size("J 0.25", 2);
  ASSERT_GT(size[0], 0);
  draw_text(image, 10, 10, "J 0.25", 2, {0, 0, 0});
  int inside = 0, outside = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const bool ink = image.pixel(x, y)[0] == 0;
      const bool in_box = x >= 10 && x < 10 + size[0] && y >= 10 && y < 10 + size[1];
      (in_box ? inside : outside) += ink;
    }
  EXPECT_GT(inside, 40);
  EXPECT_EQ(outside, 0);
  draw_text(image, 190, 50, "clipped at the corner", 3, {0, 0, 0});  // must not write outside
}

TEST(Text, EveryGlyphOfALongLabelIsDrawnWhole) {
  // Glyphs do not overlap, so a string of n copies of the busiest digit has n times its ink
  // (a too small quad buffer once cut off the last '8' of "68").
  auto ink = [](const std::string& text) {
    Image image(400, 40, 255, 255, 255, 255);
    draw_text(image, 2, 2, text, 2, {0, 0, 0});
    int count = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) count += image.rgba[i] == 0;
    return count;
  };
  for (const std::string glyph : {"8", "@", "0", "-"}) EXPECT_EQ(ink(std::string(12, glyph[0])), 12 * ink(glyph)) << glyph;
}

TEST(ColorBar, StripShowsTheMapFromMaxAtTheTopToMinAtTheBottom) {
  Image image(600, 400, 250, 250, 250, 255);
  draw_color_bar(image, {Colormap::Sequential, -2.0, 5.0, "density"});
  const int width = color_bar_width(600, 400);
  ASSERT_GT(width, 20);
  // Find the strip's column: the one whose top and bottom match the map's ends.
  const Eigen::Vector3d top = colormap_color(Colormap::Sequential, 1), bottom = colormap_color(Colormap::Sequential, 0);
  auto close = [](const std::uint8_t* p, const Eigen::Vector3d& c) {
    for (int i = 0; i < 3; ++i)
      if (std::abs(p[i] - 255 * c[i]) > 3) return false;
    return true;
  };
  bool found = false;
  for (int x = 600 - width; x < 600 && !found; ++x)
    found = close(image.pixel(x, 400 / 8 + 1), top) && close(image.pixel(x, 400 - 400 / 8 - 1), bottom);
  EXPECT_TRUE(found);
  // Nothing is drawn left of the bar's columns.
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 600 - width; ++x) ASSERT_EQ(image.pixel(x, y)[0], 250);
  EXPECT_EQ(color_bar_label(0.1 + 0.2), "0.3");
  EXPECT_EQ(color_bar_label(-28.5412), "-28.54");
}

}  // namespace
}  // namespace volspline
