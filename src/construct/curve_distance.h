#pragma once
// The distance from points to one B-spline or NURBS curve in R³, with the curve's Bézier pieces
// and the Bernstein forms of their critical-point equations prepared once (skeleton curves,
// construct/skeleton_field.h).
#include <vector>

#include <Eigen/Geometry>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

class CurveDistance {
 public:
  /// \throw InvalidInput if the curve is not in R³.
  explicit CurveDistance(const BSplineCurve& curve);

  /// min over the curve's domain of |c(t) - x|. Thread-safe.
  double operator()(const Eigen::Vector3d& x) const;

 private:
  // One Bézier piece c = P / w on its local s in [0, 1]. With Q = P - x w, the derivative of
  // |c - x|² has the sign of Q·(Q' w - Q w') = Q·T, T = P' w - P w' (the x terms cancel), so the
  // critical points are the roots of A - x·B with A = P·T and B = w T, both independent of x.
  // A polynomial piece has w = 1: A = P·P', B = P'.
  struct Piece {
    BernsteinTensor<1> homogeneous;  // (w x, w y, w z, w), or (x, y, z) for a polynomial curve
    BernsteinTensor<1> a;            // scalar
    BernsteinTensor<1> b;            // 3 components, the degree of a
    double a_max = 0, b_max = 0;     // largest |coefficient|, for the rounding level of A - x·B
    // The box of the Cartesian control points, which holds the piece when every weight is
    // positive (convex hull property); empty otherwise.
    Eigen::AlignedBox3d box;
  };

  Eigen::Vector3d point(const Piece& piece, double s) const;

  std::vector<Piece> pieces_;
  bool rational_ = false;
};

}  // namespace volspline
