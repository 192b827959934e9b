#pragma once
// Isoparametric surfaces of a trivariate solid: the images V(u_i, v, w), V(u, v_j, w),
// V(u, v, w_k) of the planes of constant parameter (Lasser 1994 §IV, Figs. 8-10). A family of
// them shows how the parameterisation fills the solid; the three through one point show its
// interior structure around that point.
#include <array>
#include <vector>

#include "volspline/core/knot_vector.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct IsoparametricOptions {
  /// Segments across the domain in each of the two free directions, plus every knot (as
  /// face_samples), so the surface bends exactly where the spline may.
  int resolution = 24;
};

/// `count` parameter values of a family across the domain of `knots`: evenly spaced with both
/// ends for count >= 2 (the two end surfaces are boundary faces), the middle for count == 1.
/// \throw InvalidInput if count < 1.
std::vector<double> isoparametric_values(const KnotVector& knots, int count);

/// The surface where parameter `direction` (0 = u, 1 = v, 2 = w) equals `value`, as a grid of
/// triangles with per-vertex parameters, part isoparametric_part(direction) (Part::IsoU..IsoW,
/// mesh/parts.h).
/// \throw InvalidInput if the direction is not 0..2, the value lies outside the domain, the
/// resolution is < 1, or the control points are not in R^3.
TriangleMesh isoparametric_surface(const BSplineVolume& volume, int direction, double value,
                                   const IsoparametricOptions& options = {});

/// The family of `count` surfaces of constant parameter `direction` (isoparametric_values).
TriangleMesh isoparametric_family(const BSplineVolume& volume, int direction, int count,
                                  const IsoparametricOptions& options = {});

/// The three surfaces u = t[0], v = t[1], w = t[2] through the point V(t) (Lasser Fig. 10).
TriangleMesh isoparametric_surfaces_through(const BSplineVolume& volume, const std::array<double, 3>& t,
                                            const IsoparametricOptions& options = {});

}  // namespace volspline
