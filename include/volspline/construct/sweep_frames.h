#pragma once
// Moving frames along a sweep path: Frenet (normal, binormal, tangent) and rotation-minimising
// (double reflection, Wang, Jüttler, Zheng and Liu 2008). Sweeps use them through the spline
// fit of construct/frame_fitting.h; design notes in docs/sweeps.md.
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

}  // namespace volspline
