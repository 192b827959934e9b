#pragma once
// A moving frame of a sweep path (construct/sweep_frames.h) fitted by spline frame curves: the
// only approximation in a sweep, with its error measured and reported (docs/sweeps.md).
#include <array>

#include "volspline/construct/sweep_frames.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The default bound on the fitted frame's orthonormality error max |R^T R - I| (entrywise).
inline constexpr double kSweepFrameTolerance = 1e-6;

/// A moving frame fitted by spline curves, and how good the fit is.
struct SweepFrameFit {
  /// Columns of R(w): normal, binormal, tangent. They share the path's (refined) knot vector,
  /// degree and, for a rational path, its weights, so the sweep keeps the path's degree.
  std::array<BSplineCurve, 3> curves;
  /// The path on the same refined knot vector (the same curve).
  BSplineCurve path;
  /// max |R^T R - I| over check points between the interpolation sites (the achieved error).
  double orthonormality_error = 0.0;
  /// max |R_fit - R_exact| (entrywise) over the same check points.
  double frame_error = 0.0;
  /// Nonempty spans of the frame curves.
  int spans = 0;
};

/// Samples the frame of `path` (SweepFrame::Fixed gives the identity) and interpolates it at the
/// Greville abscissae of the path's knot vector, halving every span until the
/// orthonormality error is at most `tolerance`. \throw InvalidInput for a path that is not
/// 3-dimensional or has zero length, a tolerance <= 0, a path whose tangent vanishes or jumps
/// (RotationMinimizing, Frenet), or, for Frenet, whose curvature vanishes somewhere;
/// NotConverged after 12 halvings.
SweepFrameFit fit_sweep_frame(const BSplineCurve& path, SweepFrame frame, double tolerance = kSweepFrameTolerance);

}  // namespace volspline
