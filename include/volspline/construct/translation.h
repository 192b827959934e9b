#pragma once
// Translation volumes: a surface moved along a curve (Lasser 1994, Theorem 1, eq. 6), for
// B-splines in every direction, polynomial or rational.
#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The surface F moved along the curve K:
///   V(u, v, w) = F(u, v) + K(w) - K(w_min),
/// on the knot vectors of F (u, v) and K (w). Theorem 1 states V(u,v,0) = F and V(0,0,w) = K,
/// which presumes F(0,0) = K(0); when they differ, "moving F along K" means moving F along
/// the translate of K that starts at F(u_min, v_min), which is the formula above: always
/// V(u, v, w_min) = F(u, v), and V(u_min, v_min, w) = K(w) exactly when F(u_min, v_min) =
/// K(w_min). Rational F and K give the homogeneous coefficients of eq. 6, V_ijk = M_k F_ij
/// (Cartesian points x_ij + k_k - K(w_min), weights beta_ij gamma_k); points at infinity of F
/// or K are handled by the same homogeneous formula. The result is rational if F or K is.
/// \throw InvalidInput (where() "path") if F and K have different dimensions.
BSplineVolume translation_volume(const BSplineSurface& F, const BSplineCurve& K);

/// The surface F moved along the straight segment `vector`: translation_volume with a degree-1
/// Bézier path on [0, 1] (Lasser's n = 1 case, V_ij1 = F_ij + T).
/// \throw InvalidInput (where() "vector") unless F lies in R^3 and `vector` is finite and
/// nonzero.
BSplineVolume extrude(const BSplineSurface& F, const Eigen::Vector3d& vector);

}  // namespace volspline
