#include "volspline/boxspline/blend_examples.h"

#include "volspline/boxspline/scene_ingredients.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/mesh/parts.h"

namespace volspline {

namespace {

SceneNode primitive(const ImplicitPrimitive& p) {
  SceneNode node;
  node.primitive = p;
  return node;
}

SceneNode sphere(const Eigen::Vector3d& centre, double radius) {
  ImplicitPrimitive p;
  p.kind = PrimitiveKind::Sphere;
  p.origin = centre;
  p.radius = radius;
  return primitive(p);
}

SceneNode with_axis(PrimitiveKind kind, const Eigen::Vector3d& origin, const Eigen::Vector3d& axis) {
  ImplicitPrimitive p;
  p.kind = kind;
  p.origin = origin;
  p.rotation = frame_with_z_axis(axis);
  return primitive(p);
}

SceneNode cylinder(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius) {
  SceneNode n = with_axis(PrimitiveKind::Cylinder, point, axis);
  n.primitive.radius = radius;
  return n;
}

SceneNode plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) { return with_axis(PrimitiveKind::Plane, point, normal); }

SceneNode operation(SceneOperation op, std::vector<SceneNode> children, double radius = 0.0) {
  SceneNode n;
  n.operation = op;
  n.children = std::move(children);
  n.radius = radius;
  return n;
}

/// A cylinder cut by the two planes a·axis = ±half_length through `centre`.
SceneNode capped_cylinder(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double radius, double half_length) {
  const Eigen::Vector3d a = axis.normalized();
  return operation(SceneOperation::Intersection,
                   {cylinder(centre, a, radius), plane(centre + half_length * a, a), plane(centre - half_length * a, -a)});
}

}  // namespace

Scene cylinder_intersection_scene() {
  Scene s;
  s.spacing = 0.25;
  s.box_min = Eigen::Vector3d::Constant(-1.25);
  s.box_max = Eigen::Vector3d::Constant(1.25);
  s.root = operation(SceneOperation::Intersection, {cylinder(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 1.0),
                                                    cylinder(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY(), 1.0)});
  return s;
}

Scene sphere_and_rod_scene() {
  Scene s;
  s.spacing = 0.1;
  s.box_min = Eigen::Vector3d(-1.2, -0.9, -0.9);
  s.box_max = Eigen::Vector3d(1.2, 0.9, 0.9);
  s.domain = std::pair{Eigen::Vector3d(-2.0, -1.0, -1.0), Eigen::Vector3d(2.0, 1.0, 1.0)};
  s.root = operation(SceneOperation::Blend,
                     {sphere(Eigen::Vector3d::Zero(), 0.8), capped_cylinder(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.4, 1.8)},
                     0.25);
  return s;
}

Scene various_primitives_scene() {
  Scene s;
  s.spacing = 0.1;
  s.box_min = Eigen::Vector3d(-1.5, -1.5, -1.2);
  s.box_max = Eigen::Vector3d(1.5, 1.5, 1.6);
  ImplicitPrimitive ellipsoid;
  ellipsoid.kind = PrimitiveKind::Ellipsoid;
  ellipsoid.radii = Eigen::Vector3d(1.0, 0.7, 0.45);
  SceneNode torus = with_axis(PrimitiveKind::Torus, Eigen::Vector3d(0, 0, -0.35), Eigen::Vector3d::UnitZ());
  torus.primitive.radius = 0.95;
  torus.primitive.minor_radius = 0.2;
  SceneNode cone = with_axis(PrimitiveKind::Cone, Eigen::Vector3d(0, 0, 1.45), -Eigen::Vector3d::UnitZ());
  cone.primitive.half_angle = 0.35;
    // The quadric is a double cone: the plane through the apex removes the upper nappe.
  const SceneNode capped_cone = operation(SceneOperation::Intersection, {cone, plane(Eigen::Vector3d(0, 0, 0.2), -Eigen::Vector3d::UnitZ()),
                                                                         plane(Eigen::Vector3d(0, 0, 1.45), Eigen::Vector3d::UnitZ())});
  s.root = operation(SceneOperation::Blend,
                     {primitive(ellipsoid), torus, capped_cylinder(Eigen::Vector3d(0, 0, -0.5), Eigen::Vector3d::UnitY(), 0.18, 1.3),
                      capped_cone},
                     0.2);
  return s;
}

Scene two_tori_scene() {
  Scene s;
  s.spacing = 0.15;
  s.box_min = Eigen::Vector3d(-0.75, -1.2, -0.6);
  s.box_max = Eigen::Vector3d(0.75, 1.2, 0.6);
  s.domain = std::pair{Eigen::Vector3d(-2.5, -1.6, -0.6), Eigen::Vector3d(2.5, 1.6, 0.6)};
  SceneNode a = with_axis(PrimitiveKind::Torus, Eigen::Vector3d(-0.95, 0, 0), Eigen::Vector3d::UnitZ());
  a.primitive.radius = 1.0, a.primitive.minor_radius = 0.3;
  SceneNode b = a;
  b.primitive.origin = Eigen::Vector3d(0.95, 0, 0);
  s.root = operation(SceneOperation::Union, {a, b});
  return s;
}

std::vector<BlendFigure> paper_blend_figures() {
  // Each figure is what `volspline blend SCENE --show ...` draws from the scene files of
  // examples/scenes (docs/blend.md "The figures of the paper"); the ingredients at spacing 0.05.
  constexpr double kIngredientSpacing = 0.05;
  const ZeroSetOptions blend{.levels = 2, .method = ZeroSetMethod::Control};
  std::vector<BlendFigure> figures;
  const Scene fig1 = cylinder_intersection_scene();
  for (int level = 0; level <= 2; ++level) {
    const std::string letter(1, static_cast<char>('a' + level));
    figures.push_back({"blend-fig1" + letter,
                       "Fig. 1" + letter + ": cylinder intersection, control polyhedron after " + std::to_string(level) + " subdivision(s)",
                       scene_zero_set(fig1, {.levels = level, .method = ZeroSetMethod::Control}).mesh});
  }
  const Scene fig2 = sphere_and_rod_scene();
  figures.push_back({"blend-fig2a", "Fig. 2a: two primitives, a sphere and a capped rod",
                     scene_ingredients_mesh(fig2, SceneIngredients::Primitives, kIngredientSpacing)});
  figures.push_back({"blend-fig2b", "Fig. 2b: their union (pointwise minimum: a crease)",
                     scene_ingredients_mesh(fig2, SceneIngredients::Union, kIngredientSpacing)});
  figures.push_back({"blend-fig2c", "Fig. 2c: their smooth blend; the box-spline surface is highlighted", scene_zero_set(fig2, blend).mesh});
  const Scene fig3 = various_primitives_scene();
  figures.push_back({"blend-fig3a", "Fig. 3a: an ellipsoid, a torus, a capped rod and a capped cone",
                     scene_ingredients_mesh(fig3, SceneIngredients::Primitives, kIngredientSpacing)});
  figures.push_back({"blend-fig3b", "Fig. 3b: their union (pointwise minimum)",
                     scene_ingredients_mesh(fig3, SceneIngredients::Union, kIngredientSpacing)});
  figures.push_back({"blend-fig3c", "Fig. 3c: the primitives blended by the box spline", scene_zero_set(fig3, blend).mesh});
  const Scene fig4 = two_tori_scene();
  figures.push_back({"blend-fig4a", "Fig. 4a: the two torus primitives, each on its own",
                     scene_ingredients_mesh(fig4, SceneIngredients::Primitives, kIngredientSpacing)});
  const TriangleMesh joined = scene_zero_set(fig4, blend).mesh;
  figures.push_back({"blend-fig4b", "Fig. 4b: the box-spline part of the join of two tori", triangles_of_part(joined, Part::BlendSpline)});
  figures.push_back({"blend-fig4c", "Fig. 4c: the complete joined object (box spline highlighted, tori outside)", joined});
  return figures;
}

}  // namespace volspline
