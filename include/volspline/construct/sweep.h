#pragma once
// Sweep volumes: a profile surface F(u, v) moved along a path c(w) while a frame R(w) turns it,
//   V(u, v, w) = c(w) + R(w) F(u, v)                          (Conkey-Joy 2000, §4),
// and Lasser's conic directrices (Lasser 1994, eq. 9). All constructions are exact tensor-product
// splines; the only approximation in this header is the fit of a rotation-minimising or Frenet
// frame by spline frame curves, whose error is measured and reported (SweepFrameFit).
// Design notes and the conventions chosen here: docs/sweeps.md.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

enum class SweepFrame {
  /// The rotation-minimising frame of the path (double reflection, Wang et al. 2008).
  RotationMinimizing,
  /// The Frenet frame (normal, binormal, tangent); undefined where the curvature vanishes.
  Frenet,
  /// No rotation: a translation of the profile along the path (Lasser 1994, Theorem 1).
  Fixed,
};

/// V(u, v, w) = c(w) + R(w) F(u, v), where the columns of R(w) are frame[0], frame[1], frame[2]:
/// the profile's coordinates are coordinates in the moving frame whose origin is c(w). Exact:
/// the result's homogeneous control points are V_ijk = M_k F_ij with M(w) the 4 x 4 matrix
/// [[delta R, delta c], [0, delta]] written as one spline (Lasser 1994, eq. 6 with a general
/// M(w); Conkey-Joy §4 for a common knot vector). Path and frame curves may have different
/// degrees, knot vectors (over one common domain) and be rational: their homogeneous forms are
/// put over the common denominator delta (the product of their distinct weight functions) by
/// exact products of Bernstein polynomials on the merged spans. The w-degree is the largest
/// degree of an entry of M, i.e. deg(path) or deg(frame) for polynomial inputs, plus the
/// degrees of the other distinct denominators for rational ones; every merged breakpoint gets
/// the smallest continuity of the inputs there. The profile may be rational.
/// \throw InvalidInput if an input is not 3-dimensional, or the path and the frame curves have
/// different parameter domains.
BSplineVolume sweep_with_frame_curves(const BSplineSurface& profile, const BSplineCurve& path,
                                      const std::array<BSplineCurve, 3>& frame);

/// The profile moved along the path, given in world coordinates at the start of the path:
///   V(u, v, w) = c(w) + R(w) R(a)^T (F(u, v) - c(a)),   a = path start,
/// so V(u, v, a) = F(u, v). Fixed: R = I, which is Lasser's translation volume (Theorem 1) and
/// is exact for any rational path (conic directrices included), with the path's degree and
/// knots in w. RotationMinimizing and Frenet: R(w) = (normal, binormal, tangent) is fitted by
/// spline frame curves (fit_sweep_frame with the default tolerance), then
/// sweep_with_frame_curves. \throw InvalidInput for a path of zero length, a path whose
/// tangent vanishes or jumps (RotationMinimizing, Frenet), or, for Frenet, a path whose
/// curvature vanishes somewhere; NotConverged if the frame fit misses its tolerance.
BSplineVolume sweep(const BSplineSurface& profile, const BSplineCurve& path, SweepFrame frame);

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
/// orthonormality error is at most `tolerance`. \throw as sweep; NotConverged after 12 halvings.
SweepFrameFit fit_sweep_frame(const BSplineCurve& path, SweepFrame frame, double tolerance = kSweepFrameTolerance);

/// The Frenet frame (normal, binormal, tangent as columns) at t.
/// \throw InvalidInput where the tangent or the curvature vanishes.
Eigen::Matrix3d frenet_frame(const BSplineCurve& path, double t);

/// The rotation-minimising frame (columns r, s = t x r, t) at each of `parameters` (ascending,
/// in the domain), starting at the first one from the frame `start` (columns as returned;
/// its first column is projected to be normal to the tangent) or, if `start` is the zero
/// matrix, from the Frenet frame there (or, where the curvature vanishes, the normal of the
/// path's plane, or an axis least aligned with the tangent). Double reflection (Wang, Jüttler,
/// Zheng and Liu 2008), marched with steps of at most (b - a) / 4096, whose O(h^4) error is
/// then far below the fit tolerance. \throw InvalidInput where the tangent vanishes.
std::vector<Eigen::Matrix3d> rotation_minimizing_frames(const BSplineCurve& path, const std::vector<double>& parameters,
                                                        const Eigen::Matrix3d& start = Eigen::Matrix3d::Zero());

/// Lasser 1994, eq. 9: the rational quadratic Bézier arc K(w) = sum_k s_k M_k K_0 B_k^2(w),
/// s_0 = s_2 = 1, with M_k the rotation of Theorem 2 about the axis through `axis_point` along
/// `axis_direction` (right-handed, angle in degrees, 0 < |angle| <= 180). The middle control
/// point is where the end tangents of the circular arc meet, with weight s2 cos(angle / 2):
/// a circle for s2 = 1, a parabola for s2 = 1 / cos(angle / 2) (all weights 1: polynomial),
/// a hyperbola for larger s2, an ellipse for smaller. At |angle| = 180 the middle point is at
/// infinity (weight 0) and the arc is half an ellipse (half a circle for s2 = 1).
/// \throw InvalidInput for a zero or non-finite axis, a start on the axis, an angle outside
/// that range, or s2 <= 0.
BSplineCurve conic_arc(Eigen::Vector3d start, double angle_deg, double s2, Eigen::Vector3d axis_point,
                       Eigen::Vector3d axis_direction);

/// The translation volume of `profile` along conic_arc(start, ...) (Lasser 1994, Theorem 1 with
/// the directrix of eq. 9): V(u, v, w) = F(u, v) + K(w) - K(0), exact, degree 2 in w.
BSplineVolume translation_along_conic(const BSplineSurface& profile, Eigen::Vector3d start, double angle_deg,
                                      double s2, Eigen::Vector3d axis_point, Eigen::Vector3d axis_direction);

}  // namespace volspline
