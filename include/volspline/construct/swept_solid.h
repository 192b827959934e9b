#pragma once
// The swept trivariate solid of Conkey and Joy 2000 (§1, §4): a generator solid g(u, v, w), one
// or more volume patches, moved along a trajectory c(t) while a frame R(t) turns it,
//   s(u, v, w, t) = c(t) + R(t) g(u, v, w)                      (Conkey-Joy 2000, eq. 1),
// where the columns of R(t) are the frame curves b(t), n(t), t(t). For each generator patch s is
// an exact 4-variate spline (BSplineHypervolume, parameters (u, v, w, t)), rational when the
// generator, the path or the frame is. Frames, the parameter conventions and how the
// denominators combine: docs/sweeps.md, "Swept solids".
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/construct/frame_fitting.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The largest |angle| of a Rotation frame, 100 turns (400 arcs): the frame's size grows with it.
inline constexpr double kMaxRotationDegrees = 36000.0;

/// How the generator turns along the path.
struct SweptSolidFrame {
  enum class Kind {
    /// R = I: a translation of the generator along the path.
    Fixed,
    /// The Frenet frame (normal, binormal, tangent), fitted by spline curves.
    Frenet,
    /// The rotation-minimising frame (normal, binormal, tangent), fitted by spline curves.
    RotationMinimizing,
    /// The rotation about `axis` (through the generator's local origin) by `degrees` * t: an
    /// exact rational frame.
    Rotation,
    /// The three curves in `curves` (b, n, t), used as given.
    Curves,
  };
  Kind kind = Kind::Fixed;
  /// Rotation: the axis (any nonzero length) and the total angle, any sign, at most
  /// kMaxRotationDegrees in size.
  Eigen::Vector3d axis{0.0, 0.0, 1.0};
  double degrees = 0.0;
  /// Curves: exactly three 3-D curves b, n, t (any degrees, knots and weights; not necessarily
  /// orthonormal), mapped affinely onto [0, 1] like the path.
  std::vector<BSplineCurve> curves;
  /// Frenet and RotationMinimizing: the bound on the fit's orthonormality error.
  double tolerance = kSweepFrameTolerance;

  /// A frame of `kind` with the defaults above.
  static SweptSolidFrame of_kind(Kind kind) {
    SweptSolidFrame frame;
    frame.kind = kind;
    return frame;
  }
  /// The rotation about `axis` by `degrees` * t (exact at arc ends; make_swept_solid).
  static SweptSolidFrame rotation(const Eigen::Vector3d& axis, double degrees) {
    SweptSolidFrame frame = of_kind(Kind::Rotation);
    frame.axis = axis;
    frame.degrees = degrees;
    return frame;
  }
  /// The given curves b, n, t.
  static SweptSolidFrame of_curves(std::vector<BSplineCurve> curves) {
    SweptSolidFrame frame = of_kind(Kind::Curves);
    frame.curves = std::move(curves);
    return frame;
  }
};

/// A swept solid ready to be evaluated: every curve is over t in [0, 1].
struct SweptSolid {
  /// The generator patches g(u, v, w), in coordinates of the moving frame (origin c(t)).
  std::vector<BSplineVolume> generator;
  /// c(t), t in [0, 1]: the given path mapped affinely onto [0, 1].
  BSplineCurve path;
  /// b(t), n(t), t(t) on [0, 1], the columns of R(t): exact (fixed, rotate, curves) or fitted
  /// (frenet, rmf). det R(t) has one sign and does not vanish on [0, 1].
  std::array<BSplineCurve, 3> frame;
  /// "fixed", "frenet", "rmf", "rotate" or "curves".
  std::string frame_name;
  /// The achieved fit error max |R^T R - I| of a fitted frame (frenet, rmf); 0 for exact frames.
  double frame_fit_error = 0.0;
};

/// The swept solid of `generator` along `path` with `frame`. The path and frame curves are mapped
/// affinely onto t in [0, 1] (their own domains may differ). Rotation: R(t) is the rotation about
/// `axis` by an angle theta(t) that runs monotonically from 0 to `degrees`, built exactly from
/// ceil(|degrees| / 90) rational quadratic arcs of equal angle on equal parts of [0, 1]; theta(t)
/// equals degrees * t at the arc ends (t = k / arcs) only, because a rational quadratic circle
/// is not parameterised by angle. Frenet and RotationMinimizing: fit_sweep_frame of the path.
/// \throw InvalidInput for an empty generator, a generator patch or path that is not
/// 3-dimensional ("generator[i]", "path"), a Curves frame without exactly three 3-D curves, a
/// zero or non-finite rotation axis, an angle that is not finite or beyond kMaxRotationDegrees,
/// a frame whose determinant vanishes or changes sign on [0, 1] (require_nonsingular_frame), or
/// as fit_sweep_frame; NotConverged as fit_sweep_frame.
SweptSolid make_swept_solid(std::vector<BSplineVolume> generator, BSplineCurve path, const SweptSolidFrame& frame);

/// The exact 4-variate spline s(u, v, w, t) = c(t) + R(t) g_patch(u, v, w) of one generator
/// patch: u, v, w over the patch's own domain, t over [0, 1] (sweep_with_frame_curves).
/// \throw InvalidInput if `patch` is not an index of solid.generator, or as
/// sweep_with_frame_curves for a SweptSolid not made by make_swept_solid.
BSplineHypervolume swept_patch(const SweptSolid& solid, std::size_t patch);

/// swept_patch for every generator patch, in order.
/// \throw InvalidInput as swept_patch.
std::vector<BSplineHypervolume> swept_patches(const SweptSolid& solid);

/// R(t) at t in [0, 1]: the frame curves as columns. \throw InvalidInput outside [0, 1].
Eigen::Matrix3d swept_frame_at(const SweptSolid& solid, double t);

/// The sign (+1 or -1) of det R(t) = b(t) . (n(t) x t(t)) over the frame curves' common domain,
/// certified: the numerator of the determinant (the denominators are positive) is formed exactly
/// in Bernstein form on every span of the merged knots, and a span is accepted when all its
/// coefficients have one sign beyond their rounding bound; spans with mixed signs are halved.
/// \throw InvalidInput naming the t where det R vanishes (|det R| below 1e-12 |b| |n| |t|, or a
/// sign change; t given to 6 digits), or the curves are not three 3-D curves on one
/// domain.
int require_nonsingular_frame(const std::array<BSplineCurve, 3>& frame);

}  // namespace volspline
