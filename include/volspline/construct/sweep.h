#pragma once
// Sweep volumes: a profile surface F(u, v) moved along a path c(w) while a frame R(w) turns it,
//   V(u, v, w) = c(w) + R(w) F(u, v)                          (Conkey-Joy 2000, §4),
// and Lasser's conic directrices (Lasser 1994, eq. 9). All constructions are exact tensor-product
// splines; the only approximation in this header is the fit of a rotation-minimising or Frenet
// frame by spline frame curves, whose error is measured and reported (SweepFrameFit).
// Design notes and the conventions chosen here: docs/sweeps.md. Frames are in
// construct/sweep_frames.h, their spline fit in construct/frame_fitting.h and conic arcs in
// construct/conic_arc.h; all three are included here, so this header offers the whole sweep
// interface.
#include <array>

#include <Eigen/Core>

#include "volspline/construct/conic_arc.h"
#include "volspline/construct/frame_fitting.h"
#include "volspline/construct/sweep_frames.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

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

/// The swept solid of Conkey-Joy 2000, eq. 1: s(u, v, w, t) = c(t) + R(t) g(u, v, w), the same
/// construction with a generator solid for the profile (control points
/// M_l g_ijk, Conkey-Joy §4), t the fourth parameter over the path's domain; degrees and
/// denominators in t as above. The generator may be rational.
/// 	hrow InvalidInput as the surface version (naming "the generator solid").
BSplineHypervolume sweep_with_frame_curves(const BSplineVolume& generator, const BSplineCurve& path,
                                           const std::array<BSplineCurve, 3>& frame);

/// The profile moved along the path, given in world coordinates at the start of the path:
///   V(u, v, w) = c(w) + R(w) R(a)^T (F(u, v) - c(a)),   a = path start,
/// so V(u, v, a) = F(u, v). Fixed: R = I, which is Lasser's translation volume (Theorem 1) and
/// is exact for any rational path (conic directrices included), with the path's degree and
/// knots in w. RotationMinimizing and Frenet: R(w) = (normal, binormal, tangent) is fitted by
/// spline frame curves (fit_sweep_frame with the default tolerance), then
/// sweep_with_frame_curves. \throw InvalidInput for an input that is not 3-dimensional, a
/// path of zero length, a path whose
/// tangent vanishes or jumps (RotationMinimizing, Frenet), or, for Frenet, a path whose
/// curvature vanishes somewhere; NotConverged if the frame fit misses its tolerance.
BSplineVolume sweep(const BSplineSurface& profile, const BSplineCurve& path, SweepFrame frame);

/// The translation volume of `profile` along conic_arc(start, ...) (Lasser 1994, Theorem 1 with
/// the directrix of eq. 9): V(u, v, w) = F(u, v) + K(w) - K(0), exact, degree 2 in w.
/// \throw InvalidInput as conic_arc, or for a profile that is not 3-dimensional.
BSplineVolume translation_along_conic(const BSplineSurface& profile, Eigen::Vector3d start, double angle_deg,
                                      double s2, Eigen::Vector3d axis_point, Eigen::Vector3d axis_direction);

}  // namespace volspline
