// Extreme coordinates (issue 16): models whose coordinates reach 1e200..1e308 or whose size is
// 1e-200 gave messages about internal quantities or blank pictures. Every reader refuses them
// at read time with a message about the input (io/coordinate_range.h), every writer refuses to
// write them, and within the range (sizes 2^-190 .. 2^190, either sign, far from 0) the
// commands' computations give the answers they give at size 1.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "support/cli_runner.h"
#include "support/invalid_input_message.h"
#include "support/temporary_directory.h"
#include "volspline/analysis/jacobian_validity.h"
#include "volspline/analysis/mass_properties.h"
#include "volspline/construct/primitives.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/io/coordinate_range.h"
#include "volspline/io/model_formats.h"
#include "volspline/render/mesh_renderer.h"
#include "volspline/spline/affine_map.h"

namespace volspline {
namespace {

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A cube scaled by `scale` (every coordinate times it), rational or not.
Model scaled_cube_model(double scale, bool rational) {
  BSplineVolume cube = box(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.5, 1, 1.5));
  std::vector<double> points = cube.points();
  for (double& x : points) x *= scale;
  std::vector<double> weights;
  if (rational) weights.assign(points.size() / 3, 0.5);
  Model model;
  model.objects.push_back({"cube", false, BSplineVolume(cube.knot_vectors(), 3, points, weights), nullptr});
  return model;
}

TEST(CoordinateRange, EveryReaderRefusesCoordinatesBeyondTheRangeNamingTheNumber) {
  for (const ModelFormat& format : model_formats()) {
    // (VTU stores each point's Jacobian too, which must stay finite for the file to be valid.)
    const bool vtu = std::string(format.name) == "vtu";
    for (const double scale : {1e61, vtu ? 1e100 : 1e200, vtu ? -1e100 : -1e307}) {
      for (const bool rational : {false, true}) {
        // The format's own text of the model (its writers do not check; write_model_file does).
        const Model model = scaled_cube_model(scale, rational);
        std::string text;
        if (std::string(format.name) == "json") {
          text = R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [1, 1, 1], "control_points": [)";
          for (int i = 0; i < 8; ++i)
            text += std::string(i ? ", " : "") + "[0, 0, " + (i == 5 ? std::to_string(scale) : std::string("1")) + "]";
          text += "]}]}";
        } else {
          text = format.text(model);
        }
        const std::string message = test_support::invalid_input_message([&] { format.parse(text, "big." + std::string(format.name)); });
        EXPECT_TRUE(mentions(message, "big." + std::string(format.name) + ": objects[0]")) << format.name << " " << scale << " " << rational << ": " << message;
        EXPECT_TRUE(mentions(message, "control_points[")) << message;
        EXPECT_TRUE(mentions(message, "at most 2^200")) << message;
      }
    }
  }
}

TEST(CoordinateRange, EveryReaderRefusesSolidsSmallerThanTheRange) {
  for (const ModelFormat& format : model_formats()) {
    if (std::string(format.name) == "json") continue;  // below, by hand
    for (const double scale : {1e-61, 1e-200, 4.9e-324}) {
      const std::string text = format.text(scaled_cube_model(scale, false));
      const std::string message = test_support::invalid_input_message([&] { format.parse(text, "tiny"); });
      EXPECT_TRUE(mentions(message, "tiny: objects[0]")) << format.name << " " << scale << ": " << message;
      EXPECT_TRUE(mentions(message, "at least 2^-200")) << format.name << " " << scale << ": " << message;
    }
  }
  const std::string json =
      R"({"volspline": 1, "objects": [{"type": "bezier_curve", "degree": [1], "control_points": [[1e-200, 0, 0], [0, 0, 0]]}]})";
  EXPECT_TRUE(mentions(test_support::invalid_input_message([&] { parse_model(json, "tiny.json"); }), "tiny.json: objects[0].control_points: expected control points spanning at least 2^-200"));
}

TEST(CoordinateRange, TheEndsOfTheRangeAreAcceptedAndTheNextNumbersRefused) {
  Model model = scaled_cube_model(1, false);
  const auto with_point = [&](double x, double y) {
    Model m = model;
    BSplineVolume& v = std::get<BSplineVolume>(m.objects[0].spline);
    std::vector<double> points = v.points();
    points[0] = x, points[3] = y;  // two control points' x: x and y
    v = BSplineVolume(v.knot_vectors(), 3, points);
    return m;
  };
  EXPECT_NO_THROW(check_coordinate_range(with_point(kMaxModelCoordinate, -kMaxModelCoordinate)));
  EXPECT_THROW(check_coordinate_range(with_point(std::nextafter(kMaxModelCoordinate, HUGE_VAL), 0)), InvalidInput);
  // All points equal (no extent) is not a size question; all but one within 2^-200 is fine.
  EXPECT_NO_THROW(check_coordinate_range(scaled_cube_model(0.0, false)));
  EXPECT_NO_THROW(check_coordinate_range(scaled_cube_model(kMinModelExtent, false)));
  EXPECT_THROW(check_coordinate_range(scaled_cube_model(std::nextafter(kMinModelExtent / 3, 0.0), false)), InvalidInput);
  // A point at infinity's direction counts for the magnitude, not for the extent.
  const BSplineVolume half = half_torus();
  Model infinite;
  infinite.objects.push_back({"half", false, half, nullptr});
  EXPECT_NO_THROW(check_coordinate_range(infinite));
}

TEST(CoordinateRange, WritersRefuseWhatReadersWouldRefuse) {
  test_support::TemporaryDirectory dir;
  for (const ModelFormat& format : model_formats()) {
    const auto path = dir.path() / (std::string("big") + format.extension);
    const std::string message = test_support::invalid_input_message([&] { write_model_file(scaled_cube_model(1e200, false), path); });
    EXPECT_TRUE(mentions(message, "objects[0].control_points[")) << message;
    EXPECT_FALSE(std::filesystem::exists(path));
  }
}

TEST(CoordinateRange, WithinTheRangeEveryComputationScales) {
  // Sizes 2^170 .. 2^-190 (and far from 0 at that size): volume, inertia and Jacobian are the unit
  // cube's times exact powers of two, and the picture of the faces shows the solid.
  const Model unit_model = scaled_cube_model(1, false);
  const BSplineVolume& unit = std::get<BSplineVolume>(unit_model.objects[0].spline);
  const MassProperties unit_mass = mass_properties(unit);
  const JacobianValidity unit_jacobian = check_jacobian(unit);
  RenderOptions render;
  render.width = 96;
  render.height = 72;
  const Image unit_picture = render_mesh(tessellate_faces(unit), render);
  for (const int e : {170, -190, 60, -60}) {
    for (const bool far : {false, true}) {
      const double s = std::ldexp(1.0, e);
      Eigen::VectorXd shift = Eigen::VectorXd::Zero(3);
      if (far) shift.setConstant(std::ldexp(1.0, e + 20));
      const BSplineVolume v = transform_affine(unit, s * Eigen::MatrixXd::Identity(3, 3), shift);
      Model model;
      model.objects.push_back({"cube", false, v, nullptr});
      EXPECT_NO_THROW(check_coordinate_range(model)) << e;
      const MassProperties mass = mass_properties(v);
      EXPECT_NEAR(mass.volume / std::ldexp(unit_mass.volume, 3 * e), 1.0, 1e-12) << e;
      EXPECT_NEAR(mass.inertia(0, 0) / std::ldexp(unit_mass.inertia(0, 0), 5 * e), 1.0, 1e-12) << e << " " << far;
      const JacobianValidity jacobian = check_jacobian(v);
      EXPECT_EQ(jacobian.verdict, unit_jacobian.verdict) << e;
      EXPECT_NEAR(jacobian.lower / std::ldexp(unit_jacobian.lower, 3 * e), 1.0, 1e-12) << e << " " << far;
      const Image picture = render_mesh(tessellate_faces(v), render);
      // The same picture up to single-precision rounding: few pixels differ, and little.
      ASSERT_EQ(picture.rgba.size(), unit_picture.rgba.size());
      std::size_t differing = 0;
      for (std::size_t i = 0; i < picture.rgba.size(); ++i) differing += std::abs(int(picture.rgba[i]) - int(unit_picture.rgba[i])) > 16;
      EXPECT_LT(differing, picture.rgba.size() / 100) << e << " " << far;
    }
  }
}

TEST(CoordinateRange, CommandsExitTwoNamingTheFileAndWriteNothing) {
  test_support::TemporaryDirectory dir;
  const auto model = dir.path() / "huge.json";
  {
    std::ofstream out(model);
    out << R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [1, 1, 1], "control_points": [)"
        << "[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1e250,1,1]]}]}";
  }
  const auto out = [&](const char* file) { return (dir.path() / file).string(); };
  for (const std::string& command : {std::string("info"), std::string("info --mass"), std::string("eval --at 0.5,0.5,0.5"), std::string("jacobian"),
                                    "faces -o " + out("f.ply"), "view -o " + out("v.png"), "convert -o " + out("c.xml"), "boundary -o " + out("b.ply")}) {
    const auto first = command.find(' ');
    const std::string name = command.substr(0, first), rest = first == std::string::npos ? "" : command.substr(first);
    const auto result = test_support::run_cli(name + " " + model.string() + rest, dir.path());
    EXPECT_EQ(result.code, 2) << command << ": " << result.err;
    EXPECT_TRUE(mentions(result.err, "huge.json: objects[0].control_points[7][0]")) << command << ": " << result.err;
    EXPECT_TRUE(mentions(result.err, "at most 2^200")) << command << ": " << result.err;
  }
  for (const char* file : {"f.ply", "v.png", "c.xml", "b.ply"}) EXPECT_FALSE(std::filesystem::exists(dir.path() / file)) << file;
  const auto made = test_support::run_cli("make box -o " + (dir.path() / "m.json").string() + " --size 1,1,1 --center 1e300,0,0", dir.path());
  EXPECT_EQ(made.code, 2) << made.err;
  EXPECT_TRUE(mentions(made.err, "at most 2^200")) << made.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "m.json"));
}

}  // namespace
}  // namespace volspline
