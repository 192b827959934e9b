#pragma once
// The isosurface of data on a regular grid (images, generated grids): marching tetrahedra on
// the six Kuhn tetrahedra of every grid cube, the field linear on each (no ambiguous cases;
// mesh/marching_tetrahedra.h). The data's own isosurface, beside which a fit's is judged
// (Marschner–Lobb's ρ = 0.5 against a fine sampling of the formula: docs/fitting.md, "Examples").
#include <string>

#include "volspline/mesh/triangle_mesh.h"
#include "volspline/pipeline/fit_baselines.h"

namespace volspline {

/// The surface where attribute `attribute` of the grid equals `value`, oriented towards the
/// larger values; vertices carry their point as (u, v, w) = their position in the grid's box
/// scaled to [0, 1]³. Closed where it does not reach the grid's box. Part AttributeIsosurface.
/// \throw InvalidInput for an attribute the grid lacks (naming those it has) or a value that is
/// not finite.
TriangleMesh grid_isosurface(const RegularGridData& grid, const std::string& attribute, double value);

}  // namespace volspline
