#pragma once
// Trivariate polynomials in tensor-product Bernstein form on a box: the form in which the
// Jacobian determinant of a Bézier cell is computed, bounded (convex hull of the coefficients)
// and subdivided (de Casteljau). Coefficients are stored with the first direction fastest, like
// control points (core/conventions.h); the local parameters of every direction run over [0, 1].
#include <array>
#include <utility>
#include <vector>

namespace volspline {

/// The binomial coefficient C(n, k) as a double (0 outside 0 <= k <= n); exact while it stays
/// below 2^53, which covers every degree volspline accepts.
double binomial_coefficient(int n, int k);

struct BernsteinTensor {
  /// Degree in each direction (>= 0).
  std::array<int, 3> degrees{0, 0, 0};
  /// (degrees[0] + 1) (degrees[1] + 1) (degrees[2] + 1) numbers, first direction fastest.
  std::vector<double> coefficients;

  BernsteinTensor() = default;
  /// All coefficients zero.
  explicit BernsteinTensor(std::array<int, 3> degrees);
  int size(int direction) const { return degrees[static_cast<std::size_t>(direction)] + 1; }
  std::size_t count() const { return coefficients.size(); }
  double& at(int i, int j, int k) { return coefficients[index(i, j, k)]; }
  double at(int i, int j, int k) const { return coefficients[index(i, j, k)]; }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(size(0)) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(size(1)) * static_cast<std::size_t>(k));
  }
};

/// The value at local parameters s in [0, 1]^3 (de Casteljau, one direction at a time).
double bernstein_evaluate(const BernsteinTensor& f, const std::array<double, 3>& s);

/// The pieces on [0, t] and [t, 1] of `direction`, each reparameterised to [0, 1]. Every new
/// coefficient is a convex combination of old ones; for t = 1/2 the weights are exact, so each of
/// the degree levels of averaging adds at most one rounding of the largest |coefficient|.
std::pair<BernsteinTensor, BernsteinTensor> bernstein_split(const BernsteinTensor& f, int direction, double t = 0.5);

/// The smallest and the largest coefficient: by the convex hull property they bound f on the box.
std::pair<double, double> bernstein_coefficient_range(const BernsteinTensor& f);

/// The largest |coefficient|.
double bernstein_max_abs(const BernsteinTensor& f);

/// The derivative with respect to the local parameter of `direction`, in Bernstein form of one
/// degree less there (n (c_{i+1} - c_i)); a direction of degree 0 gives the zero polynomial of
/// degree 0.
BernsteinTensor bernstein_derivative(const BernsteinTensor& f, int direction);

/// The product f g in Bernstein form, of degree f.degrees + g.degrees: each coefficient is a
/// convex combination of products f_i g_j (Vandermonde's identity), computed by convolution in
/// the scaled basis C(n, i) B_i^n.
BernsteinTensor bernstein_product(const BernsteinTensor& f, const BernsteinTensor& g);

/// The same polynomial with each degree raised to `degrees` (>= the current ones).
BernsteinTensor bernstein_elevate(const BernsteinTensor& f, std::array<int, 3> degrees);

}  // namespace volspline
