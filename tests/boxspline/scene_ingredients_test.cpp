// The ingredients of a blend (Peters & Wittman Figs. 2a, 2b, 3a, 3b, 4a): two overlapping spheres
// meshed one by one bound the sum of their volumes, their union bounds the sum less the lens they
// share (π(4r + d)(2r − d)²/12), and every vertex lies on the surface it belongs to.
#include "volspline/boxspline/scene_ingredients.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "volspline/boxspline/zero_set.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

SceneNode ingredient_sphere(const Eigen::Vector3d& centre, double radius) {
  SceneNode node;
  node.primitive.kind = PrimitiveKind::Sphere;
  node.primitive.origin = centre;
  node.primitive.radius = radius;
  return node;
}

Scene two_spheres(double distance) {
  Scene scene;
  scene.spacing = 0.25;
  scene.box_min = Eigen::Vector3d(-0.5, -0.5, -0.5);
  scene.box_max = Eigen::Vector3d(0.5, 0.5, 0.5);
  scene.domain = std::pair{Eigen::Vector3d(-2.0, -1.5, -1.5), Eigen::Vector3d(2.0, 1.5, 1.5)};
  scene.root.operation = SceneOperation::Blend;
  scene.root.radius = 0.3;
  scene.root.children = {ingredient_sphere({-distance / 2, 0, 0}, 1.0), ingredient_sphere({distance / 2, 0, 0}, 1.0)};
  return scene;
}

constexpr double kSpacing = 0.05;

TEST(SceneIngredients, PrimitivesBoundTheSumOfTheirVolumesAndLieOnTheirSpheres) {
  const double d = 1.2;
  const TriangleMesh mesh = scene_ingredients_mesh(two_spheres(d), SceneIngredients::Primitives, kSpacing);
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  const double ball = 4.0 / 3.0 * std::numbers::pi;
  EXPECT_NEAR(enclosed_volume(mesh), 2 * ball, 0.01 * 2 * ball);
  for (const Eigen::Vector3d& x : mesh.positions) {
    const double a = (x - Eigen::Vector3d(-d / 2, 0, 0)).norm() - 1.0, b = (x - Eigen::Vector3d(d / 2, 0, 0)).norm() - 1.0;
    EXPECT_LT(std::min(std::abs(a), std::abs(b)), 2e-3) << x.transpose();
  }
  for (const int part : mesh.parts) EXPECT_EQ(part, part_number(Part::BlendPrimitive));
}

TEST(SceneIngredients, TheUnionBoundsTheSpheresLessTheirLens) {
  const double d = 1.2, r = 1.0;
  const TriangleMesh mesh = scene_ingredients_mesh(two_spheres(d), SceneIngredients::Union, kSpacing);
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  const double lens = std::numbers::pi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12.0;
  const double expected = 2 * 4.0 / 3.0 * std::numbers::pi - lens;
  EXPECT_NEAR(enclosed_volume(mesh), expected, 0.01 * expected);
  // On the surface of min(a, b): on one sphere and not inside the other.
  for (const Eigen::Vector3d& x : mesh.positions) {
    const double a = (x - Eigen::Vector3d(-d / 2, 0, 0)).norm() - r, b = (x - Eigen::Vector3d(d / 2, 0, 0)).norm() - r;
    EXPECT_LT(std::abs(std::min(a, b)), 2e-3) << x.transpose();
  }
  // The blend of the same scene is smooth where the union is creased: it bounds more.
  const ZeroSet blend = scene_zero_set(two_spheres(d), {.levels = 2, .statistics = false});
  EXPECT_GT(enclosed_volume(blend.mesh), enclosed_volume(mesh));
  // Drawn without a spacing of their own, the ingredients use the blend's grid.
  EXPECT_EQ(default_ingredient_spacing(two_spheres(d), 2), blend.stats.grid_spacing);
  EXPECT_EQ(default_ingredient_spacing(two_spheres(d), 2), 0.25 / 4);
}

TEST(SceneIngredients, ARootWithoutChildrenIsItsOwnIngredientOverTheWholeDomain) {
  Scene scene = two_spheres(1.0);
  scene.root = ingredient_sphere({1.2, 0, 0}, 0.6);  // mostly outside the box, inside the domain
  const TriangleMesh u = scene_ingredients_mesh(scene, SceneIngredients::Union, kSpacing);
  const TriangleMesh p = scene_ingredients_mesh(scene, SceneIngredients::Primitives, kSpacing);
  const TriangleMesh direct = implicit_zero_set(scene.root, scene.domain->first, scene.domain->second, kSpacing);
  ASSERT_EQ(u.num_triangles(), direct.num_triangles());
  ASSERT_EQ(p.num_triangles(), direct.num_triangles());
  EXPECT_EQ(u.positions, direct.positions);
  EXPECT_EQ(p.triangles, direct.triangles);
  EXPECT_NEAR(u.bounding_box().second.x(), 1.8, 1e-3);
  EXPECT_THROW(scene_ingredients_mesh(scene, SceneIngredients::Union, 0.0), InvalidInput);
}

}  // namespace
}  // namespace volspline
