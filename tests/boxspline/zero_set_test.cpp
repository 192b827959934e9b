// Zero sets of box-spline fields (§7): closed, oriented meshes; the control method converges
// quadratically; the exact method puts a sphere's vertices on the sphere; a single sheet stays
// single under refinement; locality (§6) and Boolean operations on coefficients.
#include "volspline/boxspline/zero_set.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numeric>
#include <numbers>

#include "support/test_meshes.h"
#include "volspline/boxspline/blend_examples.h"
#include "volspline/boxspline/lattice_isosurface.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::components_and_euler;

SceneNode sphere_node(const Eigen::Vector3d& c, double r) {
  SceneNode n;
  n.primitive.kind = PrimitiveKind::Sphere;
  n.primitive.origin = c;
  n.primitive.radius = r;
  return n;
}

Scene sphere_scene(double h) {
  Scene s;
  s.spacing = h;
  s.box_min = Eigen::Vector3d::Constant(-1.0);
  s.box_max = Eigen::Vector3d::Constant(1.0);
  s.root = sphere_node(Eigen::Vector3d(0.03, -0.02, 0.01), 0.7);
  return s;
}


TEST(MarchTetrahedra, PlaneIsExactAndSphereClosed) {
  // A linear function is reproduced exactly by the piecewise linear interpolant.
  TetrahedralGrid grid(Eigen::Vector3d(-1, -1, -1), 0.25, {8, 8, 8});
  const auto n = grid.nodes();
  const Eigen::Vector3d normal = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  for (int c = 0; c < n[2]; ++c)
    for (int b = 0; b < n[1]; ++b)
      for (int a = 0; a < n[0]; ++a) grid.value(a, b, c) = normal.dot(grid.node_position(a, b, c)) - 0.1;
  const TriangleMesh plane = march_tetrahedra(grid);
  ASSERT_GT(plane.num_triangles(), 100u);
  for (const auto& x : plane.positions) EXPECT_NEAR(normal.dot(x), 0.1, 1e-14);
  // Triangles face the positive side.
  for (const auto& t : plane.triangles) {
    const Eigen::Vector3d a = plane.positions[t[0]], b = plane.positions[t[1]], c = plane.positions[t[2]];
    EXPECT_GE((b - a).cross(c - a).dot(normal), -1e-15);
  }
  for (int c = 0; c < n[2]; ++c)
    for (int b = 0; b < n[1]; ++b)
      for (int a = 0; a < n[0]; ++a) grid.value(a, b, c) = grid.node_position(a, b, c).norm() - 0.6;
  const TriangleMesh sphere = march_tetrahedra(grid);
  const EdgeStatistics e = edge_statistics(sphere);
  EXPECT_TRUE(e.closed_and_oriented());
  EXPECT_EQ(components_and_euler(sphere), (std::pair<int, long>{1, 2}));
  EXPECT_GT(enclosed_volume(sphere), 0.0);
}

TEST(ZeroSet, ControlMethodConvergesQuadraticallyOnASphere) {
  std::vector<double> errors;
  for (int level = 0; level <= 3; ++level) {
    const ZeroSet z = scene_zero_set(sphere_scene(0.2), {.levels = level, .method = ZeroSetMethod::Control});
    EXPECT_TRUE(z.stats.closed) << "level " << level;
    EXPECT_EQ(edge_statistics(z.mesh).inconsistently_oriented_edges, 0u);
    ASSERT_TRUE(z.stats.max_distance.has_value());
    errors.push_back(*z.stats.max_distance);
  }
  for (int i = 0; i + 1 < 4; ++i) {
    const double ratio = errors[i] / errors[i + 1];
    EXPECT_GT(ratio, 3.3) << "levels " << i << " -> " << i + 1 << ": " << errors[i] << " -> " << errors[i + 1];
    EXPECT_LT(ratio, 4.8) << "levels " << i << " -> " << i + 1 << ": " << errors[i] << " -> " << errors[i + 1];
  }
}

TEST(ZeroSet, ExactMethodPutsTheSphereOnTheSphere) {
  // The sphere's function is quadratic, reproduced exactly: the spline's zero set is the sphere.
  const Scene scene = sphere_scene(0.25);
  for (int level = 0; level <= 2; ++level) {
    const ZeroSet plain = scene_zero_set(scene, {.levels = level, .method = ZeroSetMethod::Exact});
    const double g = plain.stats.grid_spacing;
    EXPECT_TRUE(plain.stats.closed);
    // Linear interpolation along an edge of length <= g sqrt(3)/2 on a sphere of radius r.
    EXPECT_LT(*plain.stats.max_distance, 0.75 * g * g / 0.7) << "level " << level;
    const ZeroSet projected = scene_zero_set(scene, {.levels = level, .method = ZeroSetMethod::Exact, .project = true});
    EXPECT_LT(*projected.stats.max_distance, 1e-12) << "level " << level;
    EXPECT_LT(projected.stats.max_abs_value, 1e-12);
    EXPECT_TRUE(projected.stats.closed);
  }
}

TEST(ZeroSet, SingleSheetedFirstApproximationStaysSingleSheeted) {
  // §7: averaging adds no sheets. Two spheres joined by the box spline (union of coefficients).
  Scene s;
  s.spacing = 0.25;
  s.box_min = Eigen::Vector3d(-1.6, -1.0, -1.0);
  s.box_max = Eigen::Vector3d(1.6, 1.0, 1.0);
  s.root.operation = SceneOperation::Union;
  s.root.children = {sphere_node(Eigen::Vector3d(-0.6, 0, 0), 0.6), sphere_node(Eigen::Vector3d(0.6, 0.1, 0), 0.55)};
  const auto first = components_and_euler(scene_zero_set(s, {.levels = 0}).mesh);
  ASSERT_EQ(first, (std::pair<int, long>{1, 2}));
  for (int level = 1; level <= 3; ++level) {
    const ZeroSet z = scene_zero_set(s, {.levels = level});
    EXPECT_TRUE(z.stats.closed);
    EXPECT_EQ(components_and_euler(z.mesh), first) << "level " << level;
  }
}

TEST(ZeroSet, BooleanOperationsActOnCoefficients) {
  Scene s;
  s.spacing = 0.2;
  s.box_min = Eigen::Vector3d::Constant(-1.0);
  s.box_max = Eigen::Vector3d::Constant(1.0);
  const SceneNode a = sphere_node(Eigen::Vector3d(-0.3, 0, 0), 0.5), b = sphere_node(Eigen::Vector3d(0.3, 0, 0), 0.5);
  Scene sa = s, sb = s;
  sa.root = a, sb.root = b;
  const LatticeField fa = scene_field(sa), fb = scene_field(sb);
  for (const auto op : {SceneOperation::Union, SceneOperation::Intersection, SceneOperation::Difference, SceneOperation::Blend}) {
    s.root.operation = op;
    s.root.radius = 0.3;
    s.root.children = {a, b};
    const LatticeField f = scene_field(s);
    for (std::size_t j = 0; j < f.coefficients.size(); ++j) {
      const double ca = fa.coefficients[j], cb = fb.coefficients[j];
      const double expected = op == SceneOperation::Union          ? std::min(ca, cb)
                              : op == SceneOperation::Intersection ? std::max(ca, cb)
                              : op == SceneOperation::Difference   ? std::max(ca, -cb)
                                                                   : smooth_minimum(std::array{ca, cb}, 0.3);
      EXPECT_EQ(f.coefficients[j], expected);
      if (op == SceneOperation::Blend) {
        EXPECT_NEAR(f.coefficients[j], smooth_minimum(ca, cb, 0.3), 1e-15);
      }
    }
    // Where one primitive's coefficients win on a whole neighbourhood, the spline is that
    // primitive exactly: far from the other sphere the union is the first sphere.
    if (op == SceneOperation::Union) {
      const Eigen::Vector3d x(-0.8, 0.0, 0.05);
      EXPECT_NEAR(f.value(x), a.primitive.value(x), 1e-13);
    }
  }
}

TEST(ZeroSet, SmoothMinimumIsTwiceDifferentiable) {
  const double k = 0.5;
  for (double d : {-0.5, 0.0, 0.5}) {
    // One-sided second differences agree at the joins |a − b| = k and a = b.
    const double e = 1e-4;
    const auto f = [&](double t) { return smooth_minimum(t, 0.0, k); };
    const double left = (f(d) - 2 * f(d - e) + f(d - 2 * e)) / (e * e), right = (f(d + 2 * e) - 2 * f(d + e) + f(d)) / (e * e);
    EXPECT_NEAR(left, right, 1e-2) << "at a − b = " << d;
  }
  EXPECT_EQ(smooth_minimum(1.0, 0.2, 0.5), 0.2);
  EXPECT_NEAR(smooth_minimum(0.0, 0.0, 0.6), -0.1, 1e-15);
}

TEST(ZeroSet, LocalityUsesPrimitivesOutsideTheBoxWithoutCracks) {
  const Scene scene = two_tori_scene();
  const ZeroSet z = scene_zero_set(scene, {.levels = 1});
  const EdgeStatistics e = edge_statistics(z.mesh);
  EXPECT_TRUE(e.closed_and_oriented());
  EXPECT_EQ(components_and_euler(z.mesh).second, -2);  // genus 2: two tori joined
  std::size_t spline = 0, primitive = 0;
  for (std::size_t t = 0; t < z.mesh.num_triangles(); ++t) {
    const Eigen::Vector3d c = (z.mesh.positions[z.mesh.triangles[t][0]] + z.mesh.positions[z.mesh.triangles[t][1]] +
                               z.mesh.positions[z.mesh.triangles[t][2]]) / 3.0;
    const bool in_box = (c.array() >= scene.box_min.array() - z.stats.grid_spacing).all() &&
                        (c.array() <= scene.box_max.array() + z.stats.grid_spacing).all();
    if (z.mesh.parts[t] == part_number(Part::BlendSpline)) {
      ++spline;
      EXPECT_TRUE(in_box);
    } else {
      ++primitive;
    }
  }
  EXPECT_GT(spline, 100u);
  EXPECT_GT(primitive, 100u);
  // The torus is quartic: at the seam the spline differs from it by O(h⁴) only.
  EXPECT_LT(z.stats.seam_value_difference, 2e-3);
}

TEST(ZeroSet, TorusZeroSetErrorIsFourthOrder) {
  std::vector<double> errors;
  for (double h : {0.2, 0.1}) {
    Scene s;
    s.spacing = h;
    s.box_min = Eigen::Vector3d(-1.5, -1.5, -0.5);
    s.box_max = Eigen::Vector3d(1.5, 1.5, 0.5);
    s.root.primitive.kind = PrimitiveKind::Torus;
    s.root.primitive.radius = 1.0;
    s.root.primitive.minor_radius = 0.35;
    const ZeroSet z = scene_zero_set(s, {.levels = 1, .method = ZeroSetMethod::Exact, .project = true});
    EXPECT_TRUE(z.stats.closed);
    errors.push_back(*z.stats.max_distance);
  }
  EXPECT_GT(errors[0] / errors[1], 11.0) << errors[0] << " " << errors[1];
  EXPECT_LT(errors[0], 5e-3);
}

TEST(ZeroSet, RejectsBadOptions) {
  EXPECT_THROW(scene_zero_set(sphere_scene(0.25), {.levels = -1}), InvalidInput);
  EXPECT_THROW(scene_zero_set(sphere_scene(0.25), {.levels = 9}), InvalidInput);
}

}  // namespace
}  // namespace volspline
