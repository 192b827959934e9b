#pragma once
// Binomial coefficients C(n, k) as doubles, from one Pascal triangle computed once: the
// coefficients of the Bernstein basis (core/bernstein_tensor.h), Bézier degree elevation
// (spline/degree_elevation.h) and the composition of free-form deformations.
namespace volspline {

/// Rows 0..kBinomialTableOrder of Pascal's triangle are tabulated. Products of Bernstein
/// polynomials of degree <= 64 (kMaxModelDegree) reach degree 4 * 64 - 1 (the rational Jacobian
/// determinant), which the table covers.
inline constexpr int kBinomialTableOrder = 256;

/// C(n, k) as a double; 0 outside 0 <= k <= n. The table is built by additions, so every entry
/// below 2^53 (all of them for n <= 56) is exact; larger ones are correctly rounded sums of
/// rounded entries (relative error below n u). Beyond the table, the product formula.
double binomial_coefficient(int n, int k);

/// Row n of the table, C(n, 0..n), for 0 <= n <= kBinomialTableOrder: for loops over one degree,
/// which then look coefficients up without a call each. \throw InvalidInput for other n.
const double* binomial_row(int n);

}  // namespace volspline
