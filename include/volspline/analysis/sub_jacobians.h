#pragma once
// The four 3 x 3 sub-Jacobian determinants of a 4-variate map s(u, v, w, t) into R^3 (a swept
// solid, Conkey–Joy 2000 §3), exactly, in Bernstein form on a Bézier cell.
//
// The Jacobian of s is 4 x 3 with rows s_u, s_v, s_w, s_t; its rank is <= 2 exactly where
//   J123 = det[s_u s_v s_w], J124 = det[s_u s_v s_t], J134 = det[s_u s_w s_t], J234 = det[s_v s_w s_t]
// vanish together (Abdel-Malek–Yeh, Conkey–Joy §3). For a polynomial cell of degree (p, q, r, m)
// each is a polynomial; all four are written in the one Bernstein basis of degree (3p, 3q, 3r, 3m)
// (degree elevation), so that the coefficients with the same multi-index form 4-vectors whose
// convex hull contains every value (J123, J124, J134, J234) on the cell. For a rational cell with
// homogeneous point P = (w, wx, wy, wz), det[s_a s_b s_c] = det[P; P_a; P_b; P_c] / w^4 (subtract
// multiples of the row P = w (1, s) from P_a = w_a (1, s) + w (0, s_a)), so the four share the
// positive denominator w^4 and the numerators, of common degree (4p, 4q, 4r, 4m), decide where
// they vanish (as analysis/jacobian_bezier.h does for the 3-D Jacobian).
#include <array>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct SubJacobiansBernstein {
  /// Four components per coefficient, in the order (J123, J124, J134, J234); for a rational
  /// cell the numerators w^4 J_abc. Local parameters [0, 1]^4 over the cell, derivatives with
  /// respect to the global parameters.
  BernsteinTensor<4> minors;
  /// True for a rational cell (the coefficients are those of the numerators).
  bool homogeneous = false;
};

/// The Bernstein coefficients of the four sub-Jacobians over a single Bézier cell (every knot
/// vector a single clamped span, e.g. from bezier_pieces) of a map into R^3.
/// \throw InvalidInput if the map is not a single Bézier cell in R^3.
SubJacobiansBernstein sub_jacobian_coefficients(const BSplineHypervolume& cell);

/// (J123, J124, J134, J234) at the global parameter t, from the evaluated first partials (the
/// Cartesian ones, so the true determinants also for a rational map).
/// \throw InvalidInput if t is outside the domain or the map is not into R^3.
std::array<double, 4> sub_jacobians_at(const BSplineHypervolume& map, const std::array<double, 4>& t);

/// Which proof shows that the four sub-Jacobians cannot vanish together on a cell.
enum class RankCertificate {
  /// None found: the cell may hold rank-deficient points.
  None,
  /// One of the four keeps a strict sign: all its Bernstein coefficients beyond the margin.
  Sign,
  /// A direction d with d . c_i > margin for every coefficient 4-vector c_i: the convex hull of
  /// the c_i, which contains every value (J123, J124, J134, J234) on the cell, misses the origin.
  Hull,
  /// Cone bounds (Conkey–Joy §5, Joy–Duchaineau §5): the cones of the partial derivatives
  /// prove that one triple product keeps a sign.
  Cone,
  /// J123 keeps a weak sign (no coefficient beyond the margin on the other side): the generator
  /// does not fold on the cell. Points where J123 touches zero without changing sign (a ball's
  /// centre, a cylinder's axis: degenerate parameterisations) may be rank-deficient, but the
  /// map at fixed t is open there, so they are interior points of the moving generator or lie
  /// on the domain's boundary, whose images the 2- and 3-faces cover (docs/envelopes.md). Not a
  /// proof that the four cannot vanish together, but that no boundary point of the swept
  /// volume comes from the cell's interior.
  NoFold,
};

/// The Bernstein certificate for a cell: Sign, else NoFold, else Hull, else None. `minors` is the four-
/// component tensor of SubJacobiansBernstein; `margins[k]` bounds the rounding error of the
/// coefficients of component k (a coefficient counts as positive only when > margins[k], and a
/// direction d proves only when d . c_i > sum_k |d_k| margins[k], so a c_i with |c_ik| <= margins[k]
/// for every k, the minors' value at a point of the set, leaves None at once). The separating direction is
/// looked for as the mean of the normalised c_i, then as the point of their convex hull nearest the origin
/// (Wolfe's minimum-norm-point algorithm), which separates the normalised vectors whenever their
/// hull misses the origin (the margin test can still refuse it where the lengths differ by many
/// orders); any direction found is a sound certificate, since the test above decides.
RankCertificate bernstein_rank_certificate(const BernsteinTensor<4>& minors, const std::array<double, 4>& margins);

/// The cone certificate for a cell of a polynomial map whose points (x, y, z) are `geometry`
/// (three components, Bernstein form on the cell; `lengths` the cell's sizes in the global
/// parameters): Cone when cone_jacobian_bound (analysis/cone_bounds.h) proves one of the four
/// triple products of the derivative control vectors keeps a sign, else None. Polynomial maps
/// only (the cones bound polynomial derivatives).
/// \throw InvalidInput if geometry does not have three components.
RankCertificate cone_rank_certificate(const BernsteinTensor<4>& geometry, const std::array<double, 4>& lengths);

}  // namespace volspline
