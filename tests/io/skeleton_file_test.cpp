#include "volspline/io/skeleton_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "support/temporary_directory.h"
#include "support/test_splines.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using Kind = SkeletonElement::Kind;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same(const SkeletonField& a, const SkeletonField& b) {
  ASSERT_EQ(a.elements().size(), b.elements().size());
  for (std::size_t i = 0; i < a.elements().size(); ++i) {
    const SkeletonElement& x = a.elements()[i];
    const SkeletonElement& y = b.elements()[i];
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.name, y.name);
    EXPECT_TRUE(same_bits(x.weight, y.weight));
    ASSERT_EQ(x.points.size(), y.points.size());
    for (std::size_t j = 0; j < x.points.size(); ++j)
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(same_bits(x.points[j][k], y.points[j][k]));
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(same_bits(x.centre[k], y.centre[k]));
      EXPECT_TRUE(same_bits(x.semi_axes[k], y.semi_axes[k]));
      for (int l = 0; l < 3; ++l) EXPECT_TRUE(same_bits(x.rotation(k, l), y.rotation(k, l)));
    }
    ASSERT_EQ(x.curve.has_value(), y.curve.has_value());
    if (x.curve) {
      EXPECT_EQ(x.curve->knot_vector(0), y.curve->knot_vector(0));
      EXPECT_EQ(x.curve->points(), y.curve->points());
      EXPECT_EQ(x.curve->weights(), y.curve->weights());
    }
    EXPECT_EQ(x.falloff.kind, y.falloff.kind);
    EXPECT_TRUE(same_bits(x.falloff.scale, y.falloff.scale));
    EXPECT_TRUE(same_bits(x.falloff.radius, y.falloff.radius));
    ASSERT_EQ(x.falloff.coefficients.size(), y.falloff.coefficients.size());
    for (std::size_t k = 0; k < x.falloff.coefficients.size(); ++k)
      EXPECT_TRUE(same_bits(x.falloff.coefficients[k], y.falloff.coefficients[k]));
  }
}

SkeletonField every_kind() {
  std::mt19937 rng(9);
  std::vector<SkeletonElement> elements(6);
  elements[0].kind = Kind::Point;
  elements[0].points = {{0.1, -0.0, 1.0 / 3.0}};
  elements[0].name = "point \"p\" ü";
  elements[1].kind = Kind::Segment;
  elements[1].points = {{0, 0, 0}, {1e-300, 2, 3}};
  elements[1].weight = -0.25;
  elements[2].kind = Kind::Polyline;
  elements[2].points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
  elements[2].falloff.kind = SkeletonFalloff::Kind::Polynomial;
  elements[2].falloff.coefficients = {1.0, 0.0, -1.0 / 0.09, 0.0, 1.0 / 0.0081};
  elements[2].falloff.radius = 0.3;
  elements[3].kind = Kind::Curve;
  elements[3].curve = test_support::random_spline<1>(rng, {3}, 4, 3, true);
  elements[3].falloff.scale = 0.1;
  elements[4].kind = Kind::Curve;
  elements[4].curve = test_support::random_spline<1>(rng, {2}, 3, 3, false, false);
  elements[5].kind = Kind::Ellipsoid;
  elements[5].centre = {0.5, 0.25, std::sqrt(2.0)};
  elements[5].semi_axes = {1.0 / 7.0, 2, 3};
  elements[5].rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return SkeletonField(std::move(elements));
}

TEST(SkeletonFile, RoundTripIsBitForBit) {
  const SkeletonField field = every_kind();
  const std::string text = skeleton_to_json(field);
  const SkeletonField again = parse_skeleton(text, "written.json");
  expect_same(field, again);
  EXPECT_EQ(skeleton_to_json(again), text);
  const Eigen::Vector3d x(0.3, 0.2, 0.1);
  EXPECT_EQ(field(x), again(x));

  test_support::TemporaryDirectory directory;
  write_skeleton(field, directory / "skeleton.json");
  expect_same(field, read_skeleton(directory / "skeleton.json"));
}

TEST(SkeletonFile, DefaultsAndAxisAngleRotation) {
  const SkeletonField field = parse_skeleton(R"({"volspline_skeleton": 1, "elements": [
      {"kind": "point", "points": [[1, 2, 3]]},
      {"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [3, 2, 1], "rotation": {"axis": [0, 0, 2], "degrees": 90}}]})",
                                             "s.json");
  const SkeletonElement& p = field.elements()[0];
  EXPECT_EQ(p.weight, 1.0);
  EXPECT_EQ(p.falloff.kind, SkeletonFalloff::Kind::InverseSquare);
  EXPECT_EQ(p.falloff.scale, 1.0);
  // A quarter turn about z takes the 3-long axis onto y: (0, 5, 0) is 2 from the tip (0, 3, 0).
  EXPECT_NEAR(field.distance(1, {0, 5, 0}), 2.0, 1e-15);
  EXPECT_NEAR(field.distance(1, {4, 0, 0}), 2.0, 1e-15);
  EXPECT_NEAR(field({1, 2, 3}), 1.0 + 1.0 / (1.0 + field.distance(1, {1, 2, 3}) * field.distance(1, {1, 2, 3})), 1e-15);
}

// Every error names the file and the JSON path.
TEST(SkeletonFile, ErrorsNameFileAndPath) {
  const std::string head = R"({"volspline_skeleton": 1, "elements": [)";
  const std::string point = R"({"kind": "point", "points": [[0, 0, 0]]})";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[]", "f.json: expected a JSON object"},
      {"{", "f.json: line 1, column 2"},
      {R"({"elements": [)" + point + "]}", "f.json: missing key \"volspline_skeleton\""},
      {R"({"volspline_skeleton": 2, "elements": [)" + point + "]}", "f.json: volspline_skeleton: expected the format version 1"},
      {R"({"volspline_skeleton": 1, "elements": []})", "f.json: elements: expected a nonempty array"},
      {R"({"volspline_skeleton": 1, "elements": [], "extra": 1})", "f.json: extra: unknown key"},
      {head + point + R"(, {"kind": "blob"}]})", "f.json: elements[1].kind: expected one of point, segment"},
      {head + R"({"points": [[0, 0, 0]]}]})", "f.json: elements[0]: missing key \"kind\""},
      {head + point + ", " + point + R"(, {"kind": "polyline", "points": [[0, 0, 0], [1, 2]]}]})",
       "f.json: elements[2].points[1]: expected an array of 3 numbers"},
      {head + R"({"kind": "segment", "points": [[0, 0, 0], [1, "x", 0]]}]})", "f.json: elements[0].points[1][1]: expected a number"},
      {head + R"({"kind": "segment", "points": [[0, 0, 0]]}]})", "f.json: elements[0].points: expected 2 points for a segment"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "centre": [0, 0, 0]}]})", "f.json: elements[0].centre: unknown key"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "weight": "heavy"}]})", "f.json: elements[0].weight: expected a number"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "falloff": {"kind": "gauss"}}]})",
       "f.json: elements[0].falloff.kind: expected \"inverse_square\" or \"polynomial\""},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "falloff": {"kind": "inverse_square", "scale": -1}}]})",
       "f.json: elements[0].falloff.scale: expected a finite scale > 0"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "falloff": {"kind": "polynomial", "coefficients": [1, -2], "radius": 1}}]})",
       "f.json: elements[0].falloff.coefficients: expected a polynomial >= 0 on [0, radius]"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "falloff": {"kind": "polynomial", "coefficients": [1]}}]})",
       "f.json: elements[0].falloff: missing key \"radius\""},
      {head + R"({"kind": "curve", "curve": {"type": "bezier_curve", "degree": [1], "control_points": [[0, 0, 0], [1, 1]]}}]})",
       "f.json: elements[0].curve.control_points[1]: expected a control point with 3 coordinates"},
      {head + R"({"kind": "curve", "curve": {"type": "bezier_curve", "degree": [1], "control_points": [[0, 0], [1, 1]]}}]})",
       "f.json: elements[0].curve.control_points: expected a curve in 3 dimensions"},
      {head + R"({"kind": "curve", "curve": {"type": "bspline_curve", "degree": [1], "knots": [[0, 0, 2, 1, 1]], )"
                  R"("control_points": [[0, 0, 0], [1, 1, 1], [2, 0, 0]]}}]})",
       "f.json: elements[0].curve.knots[0]"},
      {head + R"({"kind": "curve", "curve": {"type": "bspline_surface"}}]})", "f.json: elements[0].curve.type: expected a curve"},
      {head + R"({"kind": "curve"}]})", "f.json: elements[0]: missing key \"curve\""},
      {head + R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, 0, 1]}]})",
       "f.json: elements[0].semi_axes[1]: expected a finite semi-axis > 0"},
      {head + R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, 1, 1], "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 2]]}]})",
       "f.json: elements[0].rotation: expected a rotation"},
      {head + R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, 1, 1], "rotation": [[1, 0, 0], [0, 1, 0]]}]})",
       "f.json: elements[0].rotation: expected a rotation: an array of 3 rows"},
      {head + R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, 1, 1], "rotation": {"axis": [0, 0, 0], "degrees": 5}}]})",
       "f.json: elements[0].rotation.axis: expected a nonzero rotation axis"},
      {head + R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, 1, 1], "rotation": {"axis": [0, 0, 1]}}]})",
       "f.json: elements[0].rotation: missing key \"degrees\""},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "name": 3}]})", "f.json: elements[0].name: expected a string"},
      {head + R"({"kind": "point", "points": [[0, 0, 0]], "kind": "point"}]})", "f.json: elements[0].kind"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parse_skeleton(text, "f.json");
      ADD_FAILURE() << "no error for " << text;
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << e.what() << "\n  expected: " << expected;
    }
  }
  EXPECT_THROW(read_skeleton("/nonexistent/skeleton.json"), IoError);
}

std::filesystem::path example(const std::string& name) { return std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / "skeletons" / name; }

// Samples of every element: its points, 50 points along a curve or a polyline, and points of an
// ellipsoid's surface.
std::vector<Eigen::Vector3d> skeleton_samples(const SkeletonField& field) {
  std::vector<Eigen::Vector3d> samples;
  for (const SkeletonElement& e : field.elements()) {
    if (e.kind == Kind::Curve) {
      for (int i = 0; i <= 50; ++i) {
        const double t = e.curve->domain_min(0) + (e.curve->domain_max(0) - e.curve->domain_min(0)) * i / 50;
        samples.push_back(e.curve->evaluate({t}));
      }
    } else if (e.kind == Kind::Ellipsoid) {
      for (int i = 0; i < 12; ++i) {
        for (int j = -2; j <= 2; ++j) {
          const double theta = 2 * std::numbers::pi * i / 12, phi = std::numbers::pi / 2 * j / 2.5;
          const Eigen::Vector3d y(e.semi_axes[0] * std::cos(theta) * std::cos(phi), e.semi_axes[1] * std::sin(theta) * std::cos(phi),
                                  e.semi_axes[2] * std::sin(phi));
          samples.push_back(e.centre + e.rotation * y);
        }
      }
    } else {
      for (std::size_t i = 0; i + 1 < e.points.size(); ++i)
        for (int k = 0; k < 10; ++k) samples.push_back(e.points[i] + (e.points[i + 1] - e.points[i]) * (k / 10.0));
      samples.push_back(e.points.back());
    }
  }
  return samples;
}

TEST(SkeletonFile, TorusExampleLiesInsideTheTorus) {
  const SkeletonField field = read_skeleton(example("skeleton-torus-sm.json"));
  ASSERT_EQ(field.elements().size(), 2u);
  // The solid torus of radii 2 and 0.75 about z: (ρ - 2)² + z² < 0.75², with a margin.
  for (const Eigen::Vector3d& x : skeleton_samples(field)) EXPECT_LT(std::hypot(std::hypot(x[0], x[1]) - 2.0, x[2]), 0.6) << x.transpose();
  EXPECT_GT(field({-0.5, -2, 0}), field({0, 2, 0}));  // the letters are at the front (y < 0)
}

// A closed triangle mesh with each triangle's box in the xy-plane, for inside tests.
struct ClosedMesh {
  std::vector<std::array<Eigen::Vector3d, 3>> triangles;
  std::vector<std::array<double, 4>> xy_boxes;  // x min, x max, y min, y max

  // The parity of the crossings of the ray from x along +z (the samples are not on edges).
  bool inside(const Eigen::Vector3d& x) const {
    int crossings = 0;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
      const std::array<double, 4>& box = xy_boxes[i];
      if (x[0] < box[0] || x[0] > box[1] || x[1] < box[2] || x[1] > box[3]) continue;
      const auto& [a, b, c] = triangles[i];
      const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
      if (det == 0) continue;
      const double u = ((x[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (x[1] - a[1])) / det;
      const double w = ((b[0] - a[0]) * (x[1] - a[1]) - (x[0] - a[0]) * (b[1] - a[1])) / det;
      if (u < 0 || w < 0 || u + w > 1) continue;
      if ((1 - u - w) * a[2] + u * b[2] + w * c[2] > x[2]) ++crossings;
    }
    return crossings % 2 == 1;
  }
};

TEST(SkeletonFile, BunnyExampleLiesInsideTheBunny) {
  const std::filesystem::path bunny = std::filesystem::path(VOLSPLINE_SOURCE_DIR) / ".." / "shared" / "data" / "volumes" / "bunny00.off";
  const SkeletonField field = read_skeleton(example("skeleton-bunny-digestion.json"));
  ASSERT_EQ(field.elements().size(), 3u);
  if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " is absent";
  std::ifstream in(bunny);
  std::string header;
  std::size_t nv = 0, nf = 0, ne = 0;
  in >> header >> nv >> nf >> ne;
  ASSERT_EQ(header, "OFF");
  std::vector<Eigen::Vector3d> vertices(nv);
  for (auto& p : vertices) in >> p[0] >> p[1] >> p[2];
  ClosedMesh mesh;
  for (std::size_t i = 0; i < nf; ++i) {
    std::size_t n = 0, a = 0, b = 0, c = 0;
    in >> n >> a >> b >> c;
    ASSERT_TRUE(n == 3 && a < nv && b < nv && c < nv);
    mesh.triangles.push_back({vertices[a], vertices[b], vertices[c]});
    const auto& t = mesh.triangles.back();
    mesh.xy_boxes.push_back({std::min({t[0][0], t[1][0], t[2][0]}), std::max({t[0][0], t[1][0], t[2][0]}),
                             std::min({t[0][1], t[1][1], t[2][1]}), std::max({t[0][1], t[1][1], t[2][1]})});
  }
  ASSERT_TRUE(in);
  for (const Eigen::Vector3d& x : skeleton_samples(field)) EXPECT_TRUE(mesh.inside(x)) << x.transpose();
}

}  // namespace
}  // namespace volspline
