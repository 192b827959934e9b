#pragma once
// Trivariate simplex splines M(x | x_0..x_{n+3}) (Hua, He and Qin 2004, §3.1, eqs. 1-2) and their
// line integrals (§6.1, eqs. 13-16), with the bivariate simplex splines that the projection
// identity of the line integrals needs. docs/simplex-splines.md derives the formulas.
//
// Conventions:
// * M(x | x_0..x_{n+3}) has degree n = #knots - 4. Degree 0 is 1/|det[x1-x0, x2-x0, x3-x0]|
//   (= 1/(6 vol), not 1/vol as printed in the paper) on the half-open tetrahedron, and eq. 1
//   carries no factor, so that ∫_{R^3} M = n!/(n+3)! and the DMS basis N = |d|·M of eq. 5 sums
//   to 1 (dms_tetrahedron_basis.h).
// * Half-open rule: x belongs to the half-open hull of four knots iff x + ε e_x + ε² e_y + ε³ e_z
//   lies inside the tetrahedron for all small ε > 0 (lexicographic symbolic perturbation). Every
//   M is the limit of its values along that perturbation, so eq. 1 holds at every point, knot
//   planes, edges and knots included, whichever four knots W it is applied with.
// * Knot subsets without four affinely independent knots (all knots coplanar) are measure-zero
//   distributions; they contribute 0 (their factor λ_j in eq. 1 vanishes on their plane).
#include <Eigen/Core>
#include <span>

namespace volspline {

/// The highest degree the simplex-spline routines accept (n + 4 <= 9 knots).
inline constexpr int kMaxSimplexSplineDegree = 5;

/// Whether x belongs to the half-open tetrahedron (a, b, c, d): x + ε e_x + ε² e_y + ε³ e_z is
/// inside for all small ε > 0. Decided exactly: the orientation of (face, x) by an exact
/// predicate; where it is 0, the sign of the face normal's x-component (a 2-D orientation of the
/// face projected onto the yz-plane), then its y-component (zx-plane), then z (xy-plane).
/// A degenerate (coplanar) tetrahedron contains no point: false.
bool in_half_open_tetrahedron(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d);

/// The same rule in the plane with the perturbation ε e_x + ε² e_y; a degenerate (collinear)
/// triangle contains no point.
bool in_half_open_triangle(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c);

/// M(x | knots) by eq. 1 without memoisation: the reference, and the benchmark's baseline. Each
/// step uses the four knots W whose half-open tetrahedron contains x, the one of largest |det|
/// among those (the largest |det| overall when none contains x).
/// \throw InvalidInput for fewer than 4 or more than kMaxSimplexSplineDegree + 4 knots, or a
/// non-finite point or knot (as every function below).
double simplex_spline_value(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots);

/// M, its gradient and its Hessian at one point.
struct SimplexSplineJet {
  double value = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

/// The value, for order >= 1 the gradient (eq. 2 along e_x, e_y, e_z), for order 2 the Hessian
/// (eq. 2 applied twice, symmetrised), memoised over knot subsets. Derivatives are those of the
/// polynomial piece the half-open rule selects.
/// \throw InvalidInput for a bad knot count (as simplex_spline_value) or order outside 0..2.
SimplexSplineJet simplex_spline_jet(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots, int order);

/// D_v M(x | knots) by eq. 2. \throw InvalidInput for a bad knot count.
double simplex_spline_directional_derivative(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots,
                                             const Eigen::Vector3d& v);

/// The bivariate simplex spline of degree m = #knots - 3: degree 0 is 1/|det| (1/(2·area)) on the
/// half-open triangle, ∫_{R^2} M = m!/(m+2)!. Accepts 3..kMaxSimplexSplineDegree + 5 knots (the
/// projections of the trivariate ones). \throw InvalidInput for other knot counts.
double bivariate_simplex_spline_value(const Eigen::Vector2d& y, std::span<const Eigen::Vector2d> knots);

/// ∫_a^b M(origin + t·direction | knots) dt (direction need not be unit; t is the parameter; a and
/// b may be infinite). By eq. 16 with the boundary terms of the integration by parts that eq. 15
/// drops (the paper integrates over the whole chord):
///   F_n = n/(n+1) Σ_j λ_j(origin | W) F_{n-1}(V \ x_kj) + 1/(n+1) [t M(origin + t·direction | V)]_a^b,
/// degree 0 = (length of [a, b] ∩ the chord of the tetrahedron) / |det|; flat knot subsets (where
/// M jumps: repeated or coplanar knots) enter with the line integrals of their planar measures.
/// Memoised.
/// \throw InvalidInput for a bad knot count or a > b.
double simplex_spline_line_integral(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                    double b, std::span<const Eigen::Vector3d> knots);

/// ∫_{-∞}^{∞} M(x + t·d | knots) dt by the projection identity:
///   1/((n+1)·|d|) · M_2(P x | P knots),
/// P the orthogonal projection onto d^⊥ in an orthonormal basis of it, M_2 the bivariate simplex
/// spline. \throw InvalidInput for a bad knot count or d = 0.
double simplex_spline_full_line_integral_by_projection(const Eigen::Vector3d& x, const Eigen::Vector3d& d,
                                                       std::span<const Eigen::Vector3d> knots);

}  // namespace volspline
