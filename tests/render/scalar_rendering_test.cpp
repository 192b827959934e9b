// Pictures coloured by a field (ColorMode::Scalar), their colour bar, and border outlines.
#include <gtest/gtest.h>

#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/render/color_bar.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline {
namespace {

// A flat square [0, 1]^2 at z = 0 in n x n quads, seen from straight above.
TriangleMesh square(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.add_vertex(Eigen::Vector3d(double(i) / n, double(j) / n, 0), Eigen::Vector3d::Zero());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = i + (n + 1) * j;
      m.add_triangle(a, a + 1, a + n + 2, 10);
      m.add_triangle(a, a + n + 2, a + n + 1, 10);
    }
  return m;
}

RenderOptions from_above(int width = 200, int height = 200) {
  RenderOptions o;
  o.width = width;
  o.height = height;
  o.view_direction = Eigen::Vector3d(0, 0, -1);
  o.up = Eigen::Vector3d(0, 1, 0);
  o.field_of_view_deg = 10;
  return o;
}

TEST(ScalarRendering, ColoursFollowTheFieldAcrossTheSurface) {
  const TriangleMesh m = square(8);
  RenderOptions o = from_above();
  o.outline_borders = false;
  o.color = ColorMode::Scalar;
  for (const auto& p : m.positions) o.vertex_scalars.push_back(p.x());  // 0 at the left, 1 at the right
  const Image image = render_mesh(m, o);
  const std::uint8_t* left = image.pixel(40, 100);
  const std::uint8_t* right = image.pixel(160, 100);
  // The sequential map runs from dark violet (blue > green) to yellow (red, green >> blue).
  EXPECT_GT(left[2], left[1]);
  EXPECT_GT(right[0], right[2] + 60);
  EXPECT_GT(right[1], right[2] + 60);
  EXPECT_GT(int(right[0]) + right[1] + right[2], int(left[0]) + left[1] + left[2]);
  // A range twice as wide puts the whole square in the lower half of the map: darker at the right.
  RenderOptions wide = o;
  wide.scalar_min = 0;
  wide.scalar_max = 2;
  const Image wide_image = render_mesh(m, wide);
  const std::uint8_t* right_wide = wide_image.pixel(160, 100);
  EXPECT_LT(int(right_wide[0]) + right_wide[1], int(right[0]) + right[1]);
}

TEST(ScalarRendering, ColourBarTakesTheRightColumnsAndTheMeshIsFramedLeftOfIt) {
  const TriangleMesh m = square(4);
  RenderOptions o = from_above(400, 300);
  o.color = ColorMode::Scalar;
  for (const auto& p : m.positions) o.vertex_scalars.push_back(p.y());
  o.color_bar_title.assign(1, 'y');  // (not = "y": GCC 12 warns falsely, -Wrestrict)
  const Image image = render_mesh(m, o);
  const int bar = color_bar_width(400, 300);
  // The square's pixels (not the backdrop's greys) stay left of the bar.
  auto coloured = [](const std::uint8_t* p) { return std::abs(int(p[0]) - int(p[2])) > 30; };
  int in_bar_strip = 0, square_right = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 400; ++x) {
      if (!coloured(image.pixel(x, y))) continue;
      if (x >= 400 - bar) ++in_bar_strip;
      else square_right = std::max(square_right, x);
    }
  EXPECT_GT(in_bar_strip, 100);  // the strip itself
  EXPECT_GT(square_right, 100);
  EXPECT_LT(square_right, 400 - bar);
}

TEST(ScalarRendering, RejectsMissingOrBadValues) {
  const TriangleMesh m = square(2);
  RenderOptions o = from_above(64, 64);
  o.color = ColorMode::Scalar;
  o.vertex_scalars = {1.0, 2.0};
  EXPECT_THROW(render_mesh(m, o), InvalidInput);
  o.vertex_scalars.assign(m.num_vertices(), 1.0);
  EXPECT_NO_THROW(render_mesh(m, o));  // a constant field is drawn in one colour, not rejected
  o.vertex_scalars[0] = std::nan("");
  EXPECT_THROW(render_mesh(m, o), InvalidInput);
  o.vertex_scalars[0] = 1.0;
  o.scalar_min = 2;
  o.scalar_max = 1;
  EXPECT_THROW(render_mesh(m, o), InvalidInput);
}

TEST(BorderOutlines, DrawDarkLinesAtBordersOfOpenSurfacesOnly) {
  const TriangleMesh m = square(6);
  RenderOptions with = from_above(), without = from_above();
  without.outline_borders = false;
  const Image a = render_mesh(m, with), b = render_mesh(m, without);
  int darker_near_border = 0, changed_inside = 0;
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      const int da = a.pixel(x, y)[0], db = b.pixel(x, y)[0];
      const bool near_middle = std::abs(x - 100) < 60 && std::abs(y - 100) < 60;
      if (da + 40 < db) ++darker_near_border;
      if (near_middle && da != db) ++changed_inside;
    }
  EXPECT_GT(darker_near_border, 4 * 100);  // four sides, each about 170 pixels long
  EXPECT_EQ(changed_inside, 0);
  // A closed mesh has no borders: the pictures are identical.
  const TriangleMesh cube = test_support::unit_cube();
  RenderOptions c1, c2;
  c1.width = c2.width = 120;
  c1.height = c2.height = 90;
  c2.outline_borders = false;
  EXPECT_EQ(render_mesh(cube, c1).rgba, render_mesh(cube, c2).rgba);
}

}  // namespace
}  // namespace volspline
