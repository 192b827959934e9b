#pragma once
// Mass properties of a trivariate solid (unit density): volume, centroid and inertia tensor by
// Gauss-Legendre quadrature of the Jacobian determinant over the knot cells. Method, exactness,
// rational volumes and folded (self-overlapping) volumes: docs/mass-properties.md.
#include <cstdint>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct MassPropertiesOptions {
  /// Target for estimated_relative_error where quadrature is not exact (rational volumes,
  /// knot cells in which the Jacobian changes sign).
  double relative_tolerance = 1e-13;
  /// The error of an n-point rule is estimated against the (n + extra_points)-point rule.
  int extra_points = 4;
  /// Budget: adaptive refinement stops before more quadrature points than this are evaluated
  /// in total (the exact pass over all knot cells always runs).
  std::int64_t max_quadrature_points = 20'000'000;
  /// Evaluate knot cells and subregions in parallel (oneTBB).
  bool parallel = true;
};

struct MassProperties {
  /// The integral of |J| over the parameter domain, J = p_u . (p_v x p_w): positive for right-
  /// and left-handed parameterisations alike. Where J changes sign the volume is folded and
  /// overlapping regions count as often as they are covered (docs/mass-properties.md).
  double volume = 0.0;
  /// (1 / volume) * integral of x |J|; NaN if the volume is 0.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// About the centroid, unit density: I = integral of (|r|^2 Id - r r^T) |J|, r = x - centroid;
  /// NaN if the volume is 0.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  /// The integral of J itself (negative for a left-handed parameterisation). For a folded
  /// volume |signed_volume| < volume.
  double signed_volume = 0.0;
  /// Estimated error of the quadrature relative to the volume: 0 where every knot cell was
  /// integrated exactly (polynomial, no sign change of J seen), so that only rounding remains;
  /// otherwise the sum over the final subregions of the difference between the n- and
  /// (n+k)-point rules (a conservative estimate of the returned (n+k)-point result's error),
  /// moments scaled by the size of the solid. See docs/mass-properties.md.
  double estimated_relative_error = 0.0;
  /// False if the adaptive refinement ran out of its budget before reaching the tolerance.
  bool converged = true;
  /// Quadrature points evaluated in all (every rule, every subregion).
  std::int64_t quadrature_points = 0;
  /// Nonempty knot cells, and those in which J was seen to change sign (folded).
  int knot_cells = 0;
  int folded_cells = 0;
};

/// Mass properties of a volume in R^3 (unit density). Every nonempty knot cell is integrated
/// with a tensor Gauss-Legendre rule on its own; for a polynomial volume of degrees (p, q, r)
/// the rule has ceil(5p/2) x ceil(5q/2) x ceil(5r/2) points, which integrates x x^T |J| exactly
/// (degree 5p-1 in u, ...) as long as J keeps its sign in the cell. Cells where J changes sign,
/// and all cells of a rational volume, are refined adaptively (see MassPropertiesOptions).
/// \throw InvalidInput if the volume's dimension is not 3 or options.extra_points < 1.
MassProperties mass_properties(const BSplineVolume& volume, const MassPropertiesOptions& options = {});

/// The n-point Gauss-Legendre rule on [-1, 1]: nodes ascending, weights (n >= 1).
/// \throw InvalidInput if n < 1.
void gauss_legendre(int n, double* nodes, double* weights);

}  // namespace volspline
