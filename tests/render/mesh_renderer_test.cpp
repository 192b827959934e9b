#include "volspline/render/mesh_renderer.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <cstdlib>
#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"
#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/render/image.h"

namespace volspline {
namespace {

// Eigen leaves `{}` uninitialised, so parameters that do not matter are spelled out.
const Eigen::Vector3d kNoParameter = Eigen::Vector3d::Zero();

using test_support::TemporaryDirectory;

// Small pictures keep the suite fast; the properties tested do not depend on the size.
RenderOptions small(int width = 160, int height = 120) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  return options;
}

RenderOptions transparent(RenderOptions options) {
  options.transparent_background = true;
  return options;
}

double coverage(const Image& image) {
  std::size_t covered = 0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) covered += image.rgba[i] > 0 ? 1 : 0;
  return static_cast<double>(covered) / (static_cast<double>(image.width) * image.height);
}

std::set<std::tuple<int, int, int>> colours_of_opaque_pixels(const Image& image) {
  std::set<std::tuple<int, int, int>> colours;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    if (image.rgba[i + 3] == 255)
      colours.emplace(image.rgba[i], image.rgba[i + 1], image.rgba[i + 2]);
  }
  return colours;
}

void expect_corners_transparent(const Image& image) {
  for (const auto& [x, y] :
       {std::pair{0, 0}, std::pair{image.width - 1, 0}, std::pair{0, image.height - 1},
        std::pair{image.width - 1, image.height - 1}}) {
    EXPECT_EQ(image.pixel(x, y)[3], 0) << "corner " << x << ", " << y;
  }
}

TEST(RenderMesh, CubeIsAShadedObjectFillingPartOfTheFrame) {
  const Image image = render_mesh(test_support::unit_cube(), transparent(small()));
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 120);
  ASSERT_EQ(image.rgba.size(), 4u * 160 * 120);
  const double share = coverage(image);
  EXPECT_GT(share, 0.10);
  EXPECT_LT(share, 0.90);
  expect_corners_transparent(image);
  // Flat faces under three lights give at least three tones, and the silhouette blends more.
  EXPECT_GT(colours_of_opaque_pixels(image).size(), 3u);
}

TEST(RenderMesh, OpaqueBackgroundIsLightAndDiffersFromTheObject) {
  const Image image = render_mesh(test_support::unit_cube(), small());
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) ASSERT_EQ(image.rgba[i], 255);
  const std::uint8_t* corner = image.pixel(0, 0);
  EXPECT_GT(std::min({corner[0], corner[1], corner[2]}), 200);
  const std::uint8_t* centre = image.pixel(80, 60);
  EXPECT_NE(std::memcmp(corner, centre, 3), 0) << "the cube should cover the centre";
  EXPECT_GT(colours_of_opaque_pixels(image).size(), 10u);
}

TEST(RenderMesh, VisibleFacesShowTheirPartColours) {
  // The default view looks at the x = 1, y = 1 and z = 1 faces: parts 1 (light blue),
  // 3 (light green) and 5 (lavender). Shading scales the channels alike and highlights add
  // grey, so the order of the channels identifies the hue.
  const Image image = render_mesh(test_support::unit_cube(), transparent(small()));
  std::size_t blue = 0, green = 0, lavender = 0, covered = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    if (image.rgba[i + 3] != 255) continue;
    ++covered;
    const int r = image.rgba[i], g = image.rgba[i + 1], b = image.rgba[i + 2];
    blue += (b > g && g > r) ? 1 : 0;
    green += (g > r && g > b) ? 1 : 0;
    lavender += (b > r && r > g) ? 1 : 0;
  }
  ASSERT_GT(covered, 0u);
  for (const std::size_t n : {blue, green, lavender}) EXPECT_GT(n, covered / 10);
}

TEST(RenderMesh, ColourModesUseOrIgnoreParts) {
  TriangleMesh one_part = test_support::unit_cube();
  std::fill(one_part.parts.begin(), one_part.parts.end(), 0);
  EXPECT_NE(render_mesh(test_support::unit_cube(), small()).rgba, render_mesh(one_part, small()).rgba);
  RenderOptions single = small();
  single.color = ColorMode::Single;
  EXPECT_EQ(render_mesh(test_support::unit_cube(), single).rgba, render_mesh(one_part, single).rgba);
}

TEST(RenderMesh, EdgesDrawDarkLines) {
  RenderOptions with_edges = small();
  with_edges.edges = true;
  const Image plain = render_mesh(test_support::unit_cube(), small());
  const Image lined = render_mesh(test_support::unit_cube(), with_edges);
  std::size_t darker = 0, lighter = 0;
  for (std::size_t i = 0; i < plain.rgba.size(); i += 4) {
    const int before = plain.rgba[i] + plain.rgba[i + 1] + plain.rgba[i + 2];
    const int after = lined.rgba[i] + lined.rgba[i + 1] + lined.rgba[i + 2];
    darker += after < before - 90 ? 1 : 0;
    lighter += after > before ? 1 : 0;
  }
  // 18 edges, of which 9 or so are visible, each some 50 pixels long at this size.
  EXPECT_GT(darker, 200u);
  EXPECT_EQ(lighter, 0u);
}

TEST(RenderMesh, IsDeterministicDespiteRunningInParallel) {
  const TriangleMesh sphere = test_support::icosphere(3);
  RenderOptions options = small(200, 150);
  options.edges = true;
  EXPECT_EQ(render_mesh(sphere, options).rgba, render_mesh(sphere, options).rgba);
}

TEST(RenderMesh, SphereLooksRoundAndCentred) {
  RenderOptions options = transparent(small(150, 150));
  const Image image = render_mesh(test_support::icosphere(3), options);
  // A disc spanning about 90% of the frame covers about pi/4 * 0.9^2 of it.
  EXPECT_NEAR(coverage(image), std::numbers::pi / 4 * 0.81, 0.05);
  EXPECT_EQ(image.pixel(75, 75)[3], 255);
  expect_corners_transparent(image);
}

TEST(RenderMesh, FramingDoesNotDependOnWhereTheMeshIs) {
  // Far from the origin, single-precision coordinates would be too coarse without re-centring.
  TriangleMesh far = test_support::icosphere(2);
  for (auto& p : far.positions) p += Eigen::Vector3d(3e7, -1e7, 5e6);
  const RenderOptions options = transparent(small());
  EXPECT_NEAR(coverage(render_mesh(far, options)),
              coverage(render_mesh(test_support::icosphere(2), options)), 0.01);
}

TEST(RenderMesh, OddViewsAndShapesStillFrameTheMesh) {
  RenderOptions top_down = transparent(small());
  top_down.view_direction = {0, 0, -1};  // parallel to the default up vector
  RenderOptions tall = transparent(small(60, 200));
  tall.supersample = false;
  tall.smooth_normals = false;
  for (const RenderOptions& options : {top_down, tall}) {
    const double share = coverage(render_mesh(test_support::unit_cube(), options));
    EXPECT_GT(share, 0.10);
    EXPECT_LT(share, 0.90);
  }
}

TEST(RenderMesh, OpenAndInsideOutMeshesAreShadedOnBothSides) {
  TriangleMesh inside_out = test_support::unit_cube();
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  const Image a = render_mesh(inside_out, small()), b = render_mesh(test_support::unit_cube(), small());
  // Reversed corners change the order of floating-point sums, so allow rounding differences.
  std::size_t different = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    different += std::abs(int(a.rgba[i]) - int(b.rgba[i])) > 3 ? 1 : 0;
  }
  EXPECT_LT(different, a.rgba.size() / 200);
}

TEST(RenderMesh, NothingToSeeGivesTheBackground) {
  TriangleMesh point;
  point.add_vertex({1, 2, 3}, kNoParameter);
  point.add_triangle(0, 0, 0, Part::JacobianZero);
  for (const TriangleMesh& mesh : {TriangleMesh{}, point}) {
    const Image opaque = render_mesh(mesh, small());
    ASSERT_EQ(opaque.rgba.size(), 4u * 160 * 120);
    for (int y = 0; y < opaque.height; ++y) {
      for (int x = 0; x < opaque.width; ++x) {
        ASSERT_EQ(std::memcmp(opaque.pixel(x, y), opaque.pixel(0, y), 4), 0);
      }
    }
    const Image clear = render_mesh(mesh, transparent(small()));
    EXPECT_EQ(coverage(clear), 0.0);
  }
}

TEST(RenderMesh, RejectsBadOptionsAndMalformedMeshes) {
  const TriangleMesh cube = test_support::unit_cube();
  RenderOptions options = small();
  options.width = 0;
  EXPECT_THROW(render_mesh(cube, options), InvalidInput);
  options = small();
  options.field_of_view_deg = 0;
  EXPECT_THROW(render_mesh(cube, options), InvalidInput);
  options = small();
  options.view_direction = Eigen::Vector3d::Zero();
  EXPECT_THROW(render_mesh(cube, options), InvalidInput);
  options = small();
  options.single_color = {1.5, 0, 0};
  EXPECT_THROW(render_mesh(cube, options), InvalidInput);
  TriangleMesh bad = cube;
  bad.triangles[0][0] = 100;
  EXPECT_THROW(render_mesh(bad, small()), InvalidInput);
}

TEST(Png, StartsWithTheSignatureAndDescribesAnRgbaImage) {
  const Image image = render_mesh(test_support::unit_cube(), small(64, 48));
  const std::string png = png_bytes(image);
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  const auto big_endian = [&png](std::size_t at) {
    return (std::uint32_t(std::uint8_t(png[at])) << 24) |
           (std::uint32_t(std::uint8_t(png[at + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[at + 2])) << 8) |
           std::uint32_t(std::uint8_t(png[at + 3]));
  };
  EXPECT_EQ(big_endian(16), 64u);
  EXPECT_EQ(big_endian(20), 48u);
  EXPECT_EQ(png[24], 8);  // bits per channel
  EXPECT_EQ(png[25], 6);  // colour type RGBA
}

TEST(Png, WritesTheEncodedBytesAtomically) {
  const TemporaryDirectory dir;
  const Image image = render_mesh(test_support::unit_cube(), small(64, 48));
  write_png(image, dir / "cube.png");
  EXPECT_EQ(read_file(dir / "cube.png"), png_bytes(image));
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(Png, MissingDirectoryThrowsIoErrorAndLeavesNoFile) {
  const TemporaryDirectory dir;
  const Image image = render_mesh(test_support::unit_cube(), small(64, 48));
  EXPECT_THROW(write_png(image, dir / "missing" / "cube.png"), IoError);
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(Png, RejectsImagesWhosePixelsDoNotMatchTheirSize) {
  Image image(4, 3);
  image.rgba.pop_back();
  EXPECT_THROW(png_bytes(image), InvalidInput);
  EXPECT_THROW(png_bytes(Image{}), InvalidInput);
  EXPECT_THROW(Image(-1, 2), InvalidInput);
}

}  // namespace
}  // namespace volspline
