// Scene files: every example parses, the writer round-trips, and every malformed scene names the
// file, the JSON path and what was expected.
#include "volspline/boxspline/scene_file.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "volspline/core/error.h"

namespace volspline {
namespace {

std::string scene_error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.json");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

std::string scene_with_root(const std::string& root, const std::string& spacing = "0.5",
                            const std::string& box = R"({"min": [0, 0, 0], "max": [1, 1, 1]})") {
  return R"({"volspline_scene": 1, "spacing": )" + spacing + R"(, "box": )" + box + R"(, "root": )" + root + "}";
}

TEST(SceneFile, ExamplesParseAndRoundTrip) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes")) {
    if (entry.path().filename().string().rfind("scene-", 0) != 0) continue;
    const Scene scene = read_scene(entry.path());
    const Scene again = parse_scene(scene_to_json(scene), "again.json");
    EXPECT_EQ(again.spacing, scene.spacing);
    EXPECT_EQ(count_primitives(again.root), count_primitives(scene.root));
    // Same function everywhere.
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d x = scene.box_min + (scene.box_max - scene.box_min).cwiseProduct(Eigen::Vector3d::Random().cwiseAbs());
      EXPECT_NEAR(scene_value(again.root, x), scene_value(scene.root, x), 1e-12) << entry.path();
    }
    ++count;
  }
  EXPECT_GE(count, 4);
}

TEST(SceneFile, PrimitivesAndPlacement) {
  const Scene s = parse_scene(scene_with_root(R"({"place": {"translate": [1, 2, 3], "rotate": {"axis": [0, 0, 1], "angle_deg": 90},
      "of": {"cylinder": {"point": [1, 0, 0], "axis": [1, 0, 0], "radius": 0.5}}}})"),
                              "s.json");
  ASSERT_EQ(s.root.operation, SceneOperation::Primitive);
  // The cylinder's axis x rotated a quarter turn about z is y; its point (1,0,0) goes to (0,1,0) + (1,2,3).
  EXPECT_LT((s.root.primitive.origin - Eigen::Vector3d(1, 3, 3)).norm(), 1e-15);
  EXPECT_LT((s.root.primitive.rotation.col(2) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_NEAR(scene_value(s.root, Eigen::Vector3d(1.5, 7, 3)), 0.0, 1e-15);
}

// Extreme coordinates (issue 16): the range of models (docs/model-format.md) holds for scenes
// too; beyond it a blend of huge or tiny spheres meshed to nothing with exit 0.
TEST(SceneFile, CoordinatesAndLengthsOutsideTheRangeAreRefused) {
  const std::string sphere = R"({"sphere": {"center": [0, 0, 0], "radius": 1}})";
  EXPECT_NE(scene_error_of(scene_with_root(R"({"sphere": {"center": [1e300, 0, 0], "radius": 1}})")).find("scene.json: root.sphere.center[0]: expected a coordinate of magnitude at most 2^200"), std::string::npos);
  EXPECT_NE(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0, 0], "radius": 5e299}})")).find("scene.json: root.sphere.radius: expected a positive radius between 2^-200 and 2^200"), std::string::npos);
  EXPECT_NE(scene_error_of(scene_with_root(R"({"torus": {"center": [0, 0, 0], "axis": [0, 0, 1], "major": 1, "minor": 1e-201}})")).find("root.torus.minor: expected a positive minor radius between 2^-200 and 2^200"), std::string::npos);
  EXPECT_NE(scene_error_of(scene_with_root(R"({"ellipsoid": {"center": [0, 0, 0], "radii": [1, 1e-250, 1]}})")).find("root.ellipsoid.radii[1]: expected a semi-axis of at least 2^-200"), std::string::npos);
  EXPECT_NE(scene_error_of(scene_with_root(sphere, "1e-201")).find("scene.json: spacing: expected a positive lattice spacing between 2^-200 and 2^200"), std::string::npos);
  EXPECT_NE(scene_error_of(scene_with_root(sphere, "0.5", R"({"min": [-1e300, 0, 0], "max": [1, 1, 1]})")).find("scene.json: box.min[0]: expected a coordinate of magnitude at most 2^200"), std::string::npos);
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [1e60, 0, 0], "radius": 1e-60}})")), "(no error)");
}

TEST(SceneFile, ErrorsNameFilePathAndExpectation) {
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"cube": {"size": 1}})")),
            "scene.json: root.cube: unknown node \"cube\": expected one of sphere, ellipsoid, cylinder, cone, torus, plane, "
            "union, intersection, difference, blend or place");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"union": [{"sphere": {"center": [0, 0, 0], "radius": 1}}, {"sphere": {"center": [0, 0, 0], "radius": -2}}]})")),
            "scene.json: root.union[1].sphere.radius: expected a positive radius, got -2");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})", "0")),
            "scene.json: spacing: expected a positive lattice spacing, got 0");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})", "-0.1")),
            "scene.json: spacing: expected a positive lattice spacing, got -0.1");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})", "0.5",
                                     R"({"min": [0, 0, 0], "max": [1, 0, 1]})")),
            "scene.json: box: expected a nonempty box, max > min in every coordinate, got min 0 and max 0 in coordinate 1");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0], "radius": 1}})")),
            "scene.json: root.sphere.center: expected the centre (an array of 3 numbers), got an array of 2 elements");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"difference": [{"sphere": {"center": [0, 0, 0], "radius": 1}}]})")),
            "scene.json: root.difference: expected an array of exactly 2 nodes, got an array of 1 element");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"cone": {"apex": [0, 0, 0], "axis": [0, 0, 1], "half_angle_deg": 90}})")),
            "scene.json: root.cone.half_angle_deg: expected a half angle strictly between 0 and 90 degrees, got 90");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"torus": {"center": [0, 0, 0], "axis": [0, 0, 0], "major": 1, "minor": 0.2}})")),
            "scene.json: root.torus.axis: expected a nonzero axis direction, got an array of 3 elements");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"blend": {"radius": 0.1, "of": [], "x": 1}})")),
            "scene.json: root.blend.x: unknown key \"x\": expected one of radius, of");
  EXPECT_EQ(scene_error_of(scene_with_root(R"({"sphere": {"center": [0, 0, 0], "radius": 1}})", "1e-4")),
            "scene.json: spacing: expected a spacing that gives at most 4000000 lattice points over the box, got about "
            "1001500750125 (use a larger spacing or a smaller box)");
  EXPECT_EQ(scene_error_of(R"({"volspline_scene": 2})"), "scene.json: volspline_scene: expected the scene format version 1, got 2");
  EXPECT_EQ(scene_error_of("{\"volspline_scene\": 1,\n  \"spacing\": }"), "scene.json: line 2, column 14: invalid JSON: syntax error while parsing value - unexpected '}'; expected '[', '{', or a literal");
}

}  // namespace
}  // namespace volspline
