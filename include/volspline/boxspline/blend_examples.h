#pragma once
// The page of examples of Peters & Wittman 1995, built in code (`volspline demo` writes them):
//  1a-c a cylinder intersection after zero, one and two subdivisions (control method);
//  2a-c two primitives, their union (pointwise minimum, creased) and their smooth blend, the
//       spline part highlighted (Part::BlendSpline) and the primitives outside the box
//       (Part::BlendPrimitive, mesh/parts.h);
//  3a-c various primitives blended: the primitives, their union, the blend;
//  4a-c the join of two tori: the two torus primitives, the box-spline part of the join, the whole
//       joined object.
#include <string>
#include <vector>

#include "volspline/boxspline/implicit_scene.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// Fig. 1: the intersection of two perpendicular cylinders of radius 1 (axes x and y), box
/// [-1.25, 1.25]³, spacing 0.25.
Scene cylinder_intersection_scene();
/// Fig. 2: a sphere pierced by a capped rod; the box around the contact circles, a smooth blend
/// of radius 0.25.
Scene sphere_and_rod_scene();
/// Fig. 3: an ellipsoid, a torus, a cylinder and a cone blended with radius 0.2.
Scene various_primitives_scene();
/// Fig. 4: two tori side by side, joined (union of coefficients) in a box around their contact.
Scene two_tori_scene();

struct BlendFigure {
  std::string name;
  std::string description;
  TriangleMesh mesh;
};

/// The twelve figures 1a .. 4c with their meshes.
std::vector<BlendFigure> paper_blend_figures();

}  // namespace volspline
