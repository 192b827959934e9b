#include "volspline/boxspline/scene_ingredients.h"

#include <cmath>

#include "volspline/boxspline/zero_set.h"

namespace volspline {

double default_ingredient_spacing(const Scene& scene, int levels) { return std::ldexp(scene.spacing, -levels); }

TriangleMesh scene_ingredients_mesh(const Scene& scene, SceneIngredients what, double spacing) {
  Eigen::Vector3d lo = scene.box_min, hi = scene.box_max;
  if (scene.domain) {
    lo = lo.cwiseMin(scene.domain->first);
    hi = hi.cwiseMax(scene.domain->second);
  }
  const std::vector<SceneNode>& children = scene.root.children;
  if (children.empty()) return implicit_zero_set(scene.root, lo, hi, spacing);
  if (what == SceneIngredients::Union) {
    SceneNode union_node;
    union_node.operation = SceneOperation::Union;
    union_node.children = children;
    return implicit_zero_set(union_node, lo, hi, spacing);
  }
  TriangleMesh out;
  for (const SceneNode& child : children) out.append(implicit_zero_set(child, lo, hi, spacing));
  return out;
}

}  // namespace volspline
