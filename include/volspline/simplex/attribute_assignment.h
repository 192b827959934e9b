#pragma once
// Giving an attribute of a DMS spline volume the values of a field f(x) — a skeleton field
// (Hua–He–Qin §4.3, eqs. 8–9; construct/skeleton_field.h) or any function of the position.
//
// Two ways, both evaluating f at physical positions (the geometry s(x), which the skeleton is
// drawn in):
// * ControlPoints, the paper's: "the scalar control coefficients ... are assigned as the
//   evaluations of the blending of field functions at the positions of corresponding control
//   points". Cheap and local, but it reproduces only constants and smooths f (a quasi-
//   interpolant of order one).
// * LeastSquares: the coefficients minimising Σ_s (Σ_r g_r N_r(x_s) − f(s(x_s)))² over samples x_s
//   of every domain tetrahedron (its barycentric lattice of order n + 2, so every basis function
//   sees enough of them), solved as a sparse problem with a small Tikhonov term toward the
//   ControlPoints values, λ = 1e-8 of the normal matrix's mean diagonal, so that a coefficient
//   whose basis function sees (almost) no sample stays defined. Reproduces every polynomial of
//   degree <= n exactly (up to that regularisation).
#include <functional>
#include <string>

#include <Eigen/Core>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

enum class AttributeAssignment { ControlPoints, LeastSquares };

struct AttributeAssignmentReport {
  /// Where the spline was compared with f: the samples (LeastSquares) or the lattice of order
  /// n + 2 of every tetrahedron (ControlPoints).
  int samples = 0;
  /// max and root mean square of |spline − f| there.
  double max_error = 0;
  double rms_error = 0;
};

/// Sets attribute `name` (added if the volume lacks it) to approximate f.
/// \throw InvalidInput for a name the volume cannot take (x, y, z, empty); Error if the
/// least-squares system cannot be factored; whatever f throws.
AttributeAssignmentReport assign_attribute(DmsSplineVolume& volume, const std::string& name,
                                           const std::function<double(const Eigen::Vector3d&)>& f, AttributeAssignment method);

}  // namespace volspline
