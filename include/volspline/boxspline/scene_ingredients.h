#pragma once
// What a blend is made of, meshed without the box spline: Peters & Wittman show each blend
// beside its ingredients (Fig. 2a/2b: the sphere and the rod, then their union with its crease;
// Fig. 3a/3b likewise; Fig. 4a the torus primitive). `volspline blend --show` draws these.
#include "volspline/boxspline/implicit_scene.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

enum class SceneIngredients {
  /// The pointwise minimum of the root's children: the CSG union, creased where they meet.
  Union,
  /// Each child of the root meshed on its own (overlapping where they overlap).
  Primitives,
};

/// The spacing of the ingredients' grid where none is given: the blend's own grid after `levels`
/// refinements, h / 2^levels (ZeroSetStats::grid_spacing), so both are drawn alike.
double default_ingredient_spacing(const Scene& scene, int levels);

/// The ingredients of `scene` over the region scene_zero_set meshes (the box, grown to the
/// domain where there is one), marched on a grid of `spacing` (implicit_zero_set); every
/// triangle is Part::BlendPrimitive. A root without children is its own single ingredient.
/// \throw InvalidInput for a bad spacing or too many grid nodes.
TriangleMesh scene_ingredients_mesh(const Scene& scene, SceneIngredients what, double spacing);

}  // namespace volspline
