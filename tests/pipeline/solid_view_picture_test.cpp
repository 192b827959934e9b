// The view pipeline called directly: its mesh is exactly solid_view_mesh's for the same request
// and frame, its field is the field at the mesh's vertices, and its picture shows something.
#include <gtest/gtest.h>

#include <cmath>

#include "volspline/construct/example_solids.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/core/progress.h"
#include "volspline/extract/planar_slices.h"
#include "volspline/pipeline/solid_view_picture.h"
#include "volspline/render/colormap.h"

namespace volspline {
namespace {

// A torus segment whose attribute "x" is the x coordinate of its control points, so the field is
// the x coordinate of the solid's points (attribute_spline.h), and a curve that is not looked at.
Model torus_model() {
  const BSplineVolume volume = torus(3.0, 1.0, 270.0);
  ModelObject object{"torus", false, volume, nullptr};
  for (std::size_t i = 0; i < volume.points().size(); i += 3) object.attributes["x"].push_back(volume.points()[i]);
  Model model;
  const BSplineCurve curve(std::array<KnotVector, 1>{KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 0, 0});
  model.objects.push_back({"axis", false, curve, nullptr});
  model.objects.push_back(object);
  return model;
}

SolidViewPictureRequest small_request() {
  SolidViewPictureRequest request;
  request.view.families = {{2, 3}};
  request.view.series = {{0, 2}};
  request.view.resolution = 8;
  request.render.width = 160;
  request.render.height = 120;
  request.source_name = "torus.json";
  return request;
}

void expect_same_mesh(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.parameters, b.parameters);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.parts, b.parts);
}

// Pixels that differ from the top-left corner (background).
std::size_t shown_pixels(const Image& image) {
  std::size_t shown = 0;
  const std::uint8_t* corner = image.rgba.data();
  for (std::size_t p = 0; p < image.rgba.size(); p += 4)
    shown += !std::equal(corner, corner + 4, image.rgba.data() + p);
  return shown;
}

TEST(SolidViewPicture, MeshIsSolidViewMeshOfEveryVolumeInOneFrame) {
  Model model = torus_model();
  model.objects.push_back({"ball", false, ball(1.0, Eigen::Vector3d(0, 0, 4)), nullptr});
  const SolidViewPictureRequest request = small_request();
  const SolidViewPicture picture = solid_view_picture(model, request);
  const auto& torus_volume = std::get<BSplineVolume>(model.objects[1].spline);
  const auto& ball_volume = std::get<BSplineVolume>(model.objects[2].spline);
  auto [lo, hi] = sampled_bounding_box(torus_volume);
  const auto [ball_lo, ball_hi] = sampled_bounding_box(ball_volume);
  lo = lo.cwiseMin(ball_lo);
  hi = hi.cwiseMax(ball_hi);
  const std::vector<Plane> planes = requested_planes(request.view, lo, hi);
  ASSERT_EQ(picture.planes.size(), planes.size());
  for (std::size_t i = 0; i < planes.size(); ++i) {
    EXPECT_EQ(picture.planes[i].normal, planes[i].normal);
    EXPECT_EQ(picture.planes[i].offset, planes[i].offset);
  }
  TriangleMesh expected = solid_view_mesh(torus_volume, request.view, planes);
  expected.append(solid_view_mesh(ball_volume, request.view, planes));
  expect_same_mesh(picture.mesh, expected);
  EXPECT_EQ(picture.volumes, 2u);
  EXPECT_EQ(picture.image.width, 160);
  EXPECT_EQ(picture.image.height, 120);
  EXPECT_GT(shown_pixels(picture.image), picture.image.rgba.size() / 4 / 20);  // more than 5% of the picture
  EXPECT_EQ(picture.render.color, ColorMode::ByPart);
  EXPECT_TRUE(picture.mesh_fields.vertex_scalars.empty());
}

TEST(SolidViewPicture, AnAttributeFieldIsTheFieldAtTheVertices) {
  SolidViewPictureRequest request = small_request();
  request.color = scalar_field_named("x");
  const SolidViewPicture picture = solid_view_picture(torus_model(), request);
  ASSERT_EQ(picture.render.vertex_scalars.size(), picture.mesh.positions.size());
  ASSERT_GT(picture.mesh.positions.size(), 0u);
  // The attribute equals the x coordinate, so the field at a vertex is the vertex's x.
  for (std::size_t v = 0; v < picture.mesh.positions.size(); ++v)
    EXPECT_NEAR(picture.render.vertex_scalars[v], picture.mesh.positions[v].x(), 1e-9) << v;
  EXPECT_EQ(picture.render.color, ColorMode::Scalar);
  EXPECT_EQ(picture.render.color_bar_title, "x");
  const ScalarColoring coloring = suggested_coloring(picture.render.vertex_scalars, false);
  EXPECT_EQ(picture.render.scalar_min, coloring.min);
  EXPECT_EQ(picture.render.scalar_max, coloring.max);
  EXPECT_EQ(picture.mesh_fields.vertex_scalars, picture.render.vertex_scalars);
  // "x" names a PLY coordinate already: the field is written as color_x.
  EXPECT_EQ(picture.mesh_fields.scalar_name, "color_x");
  ASSERT_EQ(picture.mesh_fields.vertex_colors.size(), picture.mesh.positions.size());
  EXPECT_GT(shown_pixels(picture.image), picture.image.rgba.size() / 4 / 20);

  request.range = std::pair(-10.0, 10.0);
  const SolidViewPicture ranged = solid_view_picture(torus_model(), request);
  EXPECT_EQ(ranged.render.scalar_min, -10.0);
  EXPECT_EQ(ranged.render.scalar_max, 10.0);
  // The middle of the range is the middle colour of the map.
  for (std::size_t v = 0; v < ranged.mesh.positions.size(); ++v) {
    const double t = (ranged.render.vertex_scalars[v] + 10.0) / 20.0;
    EXPECT_EQ(ranged.mesh_fields.vertex_colors[v], colormap_color(ranged.render.colormap, t)) << v;
  }
}

// A field that is constant over what is shown draws one colour, the middle of the map, and the
// bar spans a small range centred on the value (issue 16): a constant attribute, the Jacobian of
// a trilinear box, u on a family of u-surfaces of one value, a constant 0 and a huge constant.
TEST(SolidViewPicture, AConstantFieldDrawsTheMiddleColour) {
  const BSplineVolume cube = box(Eigen::Vector3d(0.1, 0.3, 0.7));  // J constant up to rounding
  for (const double constant : {0.0, 7.5, -1e300, 1e-300}) {
    Model model;
    ModelObject object{"cube", false, cube, nullptr};
    object.attributes["c"] = std::vector<double>(static_cast<std::size_t>(cube.num_control_points_total()), constant);
    model.objects.push_back(object);
    for (const std::string field : {"c", "jacobian", "u"}) {
      SolidViewPictureRequest request = small_request();
      request.source_name = "cube.json";
      request.color = scalar_field_named(field);
      if (field == "u") request.view.families = {{0, 1}}, request.view.series.clear();  // one u-surface: u constant
      const SolidViewPicture picture = solid_view_picture(model, request);
      ASSERT_GT(picture.mesh.positions.size(), 0u) << field;
      EXPECT_LT(picture.render.scalar_min, picture.render.scalar_max) << field << " " << constant;
      const double value = picture.render.vertex_scalars.front();
      const double middle = 0.5 * picture.render.scalar_min + 0.5 * picture.render.scalar_max;
      EXPECT_NEAR(middle, value, 1e-6 * (picture.render.scalar_max - picture.render.scalar_min)) << field << " " << constant;
      for (const Eigen::Vector3d& colour : picture.mesh_fields.vertex_colors)
        EXPECT_LT((colour - colormap_color(Colormap::Sequential, 0.5)).norm(), 1e-9) << field << " " << constant;
      EXPECT_GT(shown_pixels(picture.image), picture.image.rgba.size() / 4 / 20) << field;
      if (field != "c") break;  // the geometry's fields do not depend on the attribute
    }
  }
}

TEST(SolidViewPicture, ReportsItsPhases) {
  std::vector<std::string> phases;
  Progress progress([&](const ProgressEvent& event) {
    if (event.kind == ProgressEvent::Kind::PhaseBegin) phases.emplace_back(event.phase);
  });
  solid_view_picture(torus_model(), small_request(), &progress);
  EXPECT_EQ(phases, (std::vector<std::string>{"surfaces", "rendering"}));
}

TEST(SolidViewPicture, ErrorsNameTheModelAndTheObject) {
  SolidViewPictureRequest request = small_request();
  request.color = scalar_field_named("density");
  try {
    solid_view_picture(torus_model(), request);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "torus.json: objects[1]");
    EXPECT_NE(e.message().find("it has x"), std::string::npos) << e.what();
  }
  Model curves = torus_model();
  curves.objects.erase(curves.objects.begin() + 1, curves.objects.end());
  try {
    solid_view_picture(curves, small_request());
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "torus.json");
    EXPECT_NE(e.message().find("no volume objects"), std::string::npos) << e.what();
  }
  request = small_request();
  request.range = std::pair(1.0, 1.0);
  EXPECT_THROW(solid_view_picture(torus_model(), request), InvalidInput);
}

}  // namespace
}  // namespace volspline
