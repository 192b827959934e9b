#pragma once
// Polynomials in D = 1..4 variables in tensor-product Bernstein form on the unit box [0, 1]^D,
// with vector-valued coefficients: the one Bernstein algebra of volspline. The Jacobian
// determinant of a Bézier cell is computed (products of derivatives), bounded (convex hull of
// the coefficients) and subdivided (de Casteljau) in this form; free-form deformation composes
// Bernstein polynomials with it, and sweeps multiply the homogeneous forms of their curves.
//
// Layout: coefficient vector a = (a_0, ..., a_{D-1}) (0 <= a_d <= degrees[d]) has linear index
// a_0 + (n_0)(a_1 + (n_1)(a_2 + ...)), n_d = degrees[d] + 1, i.e. the first direction fastest
// like control points (core/conventions.h); its `components` numbers are contiguous, so a Bézier
// piece's homogeneous control points are its Bernstein coefficients as they stand.
//
// Products follow Farouki and Rajan, "Algorithms for polynomials in Bernstein form" (1988):
// B_i^m B_j^n = C(m,i) C(n,j) / C(m+n,i+j) B_{i+j}^{m+n} in each variable, so in the scaled
// basis C(n,i) B_i^n a product is a plain convolution of coefficient arrays
// (ScaledBernsteinTensor, scaled_product_add); bernstein_product scales, convolves and unscales.
#include <array>
#include <concepts>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "volspline/core/binomial.h"

namespace volspline {

/// Coefficients on a tensor grid with vector values; the basis is given by the derived type.
template <int D>
struct TensorCoefficients {
  static_assert(D >= 1 && D <= 4, "Bernstein tensors have 1 to 4 variables");
  /// Degree in each direction (>= 0).
  std::array<int, D> degrees{};
  /// Numbers per coefficient (>= 1).
  int components = 1;
  /// count() * components numbers, first direction fastest, components innermost.
  std::vector<double> coefficients;

  TensorCoefficients() = default;
  /// All coefficients zero. \throw InvalidInput if a degree is negative or components < 1.
  explicit TensorCoefficients(const std::array<int, D>& degrees, int components = 1);

  int size(int direction) const { return degrees[static_cast<std::size_t>(direction)] + 1; }
  /// Number of coefficient vectors (prod (degrees[d] + 1) once constructed).
  std::size_t count() const { return coefficients.size() / static_cast<std::size_t>(components); }
  /// Distance between neighbouring coefficient vectors along `direction`, in vectors.
  std::size_t stride(int direction) const {
    std::size_t s = 1;
    for (int d = 0; d < direction; ++d) s *= static_cast<std::size_t>(size(d));
    return s;
  }
  /// Linear index of the coefficient vector a (in vectors, not numbers).
  std::size_t index(const std::array<int, D>& a) const {
    std::size_t linear = 0;
    for (int d = D - 1; d >= 0; --d) {
      linear = linear * static_cast<std::size_t>(size(d)) + static_cast<std::size_t>(a[static_cast<std::size_t>(d)]);
    }
    return linear;
  }
  /// The multi-index of linear index `linear`.
  std::array<int, D> multi_index(std::size_t linear) const {
    std::array<int, D> a{};
    for (int d = 0; d < D; ++d) {
      a[static_cast<std::size_t>(d)] = static_cast<int>(linear % static_cast<std::size_t>(size(d)));
      linear /= static_cast<std::size_t>(size(d));
    }
    return a;
  }
  double& at(const std::array<int, D>& a, int component = 0) {
    return coefficients[index(a) * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
  }
  double at(const std::array<int, D>& a, int component = 0) const {
    return coefficients[index(a) * static_cast<std::size_t>(components) + static_cast<std::size_t>(component)];
  }
  /// The first component of coefficient (i, j, ...): at(i, j, k) for a trivariate scalar.
  template <std::integral... I>
    requires(sizeof...(I) == D)
  double& at(I... i) {
    return at(std::array<int, D>{static_cast<int>(i)...});
  }
  template <std::integral... I>
    requires(sizeof...(I) == D)
  double at(I... i) const {
    return at(std::array<int, D>{static_cast<int>(i)...});
  }
};

/// A polynomial sum_a c_a B_{a_0}^{n_0}(s_0) ... B_{a_{D-1}}^{n_{D-1}}(s_{D-1}) on [0, 1]^D.
template <int D>
struct BernsteinTensor : TensorCoefficients<D> {
  using TensorCoefficients<D>::TensorCoefficients;
};

/// The same polynomial in the scaled basis: coefficient a is c_a C(n_0, a_0) ... C(n_{D-1},
/// a_{D-1}). A distinct type so that scaled coefficients are never evaluated or bounded as if
/// they were Bernstein coefficients.
template <int D>
struct ScaledBernsteinTensor : TensorCoefficients<D> {
  using TensorCoefficients<D>::TensorCoefficients;
};

/// Parameters and degrees of a D-variate tensor, as function parameters whose D is taken from
/// the tensor argument (std::array's size is a std::size_t, which would not deduce an int D).
template <int D>
using BernsteinPoint = typename std::type_identity<std::array<double, D>>::type;
template <int D>
using BernsteinDegrees = typename std::type_identity<std::array<int, D>>::type;

/// degrees(f) + degrees(g): the degrees of a product.
template <std::size_t N>
std::array<int, N> product_degrees(const std::array<int, N>& f, const std::array<int, N>& g) {
  std::array<int, N> d{};
  for (std::size_t i = 0; i < N; ++i) d[i] = f[i] + g[i];
  return d;
}

/// The value of a scalar f at s in [0, 1]^D (de Casteljau, one direction at a time).
/// \throw InvalidInput if f has more than one component.
template <int D>
double bernstein_evaluate(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s);

/// The value of every component of f at s, written to values[0 .. f.components).
template <int D>
void bernstein_evaluate(const BernsteinTensor<D>& f, const BernsteinPoint<D>& s, double* values);

/// The pieces on [0, t] and [t, 1] of `direction`, each reparameterised to [0, 1]. Every new
/// coefficient is a convex combination of old ones; for t = 1/2 the weights are exact, so each of
/// the degree levels of averaging adds at most one rounding of the largest |coefficient|.
/// \throw InvalidInput if direction is not in [0, D).
template <int D>
std::pair<BernsteinTensor<D>, BernsteinTensor<D>> bernstein_split(const BernsteinTensor<D>& f, int direction, double t = 0.5);
/// The same, written into `left` and `right`, which are resized and whose storage is reused: a
/// subdivision that splits into the same tensors again and again does not allocate.
/// \throw InvalidInput if direction is not in [0, D) or the outputs are not two tensors distinct
/// from f.
template <int D>
void bernstein_split(const BernsteinTensor<D>& f, int direction, double t, BernsteinTensor<D>& left, BernsteinTensor<D>& right);

/// The restriction of f to the face s_direction = side (0 or 1), a polynomial in the other D - 1
/// variables (in their order): the coefficients with a_direction = 0 or degree.
/// \throw InvalidInput if direction is not in [0, D) or side is not 0 or 1.
template <int D>
  requires(D >= 2)
BernsteinTensor<D - 1> bernstein_face(const BernsteinTensor<D>& f, int direction, int side);

/// The quotient q of f = s_direction q (side 0) or f = (1 - s_direction) q (side 1), one degree
/// lower along `direction`: q_j = f_{j+1} n / (j + 1), or q_j = f_j n / (n - j), from
/// s B_j^{n-1} = (j + 1)/n B_{j+1}^n and (1 - s) B_j^{n-1} = (n - j)/n B_j^n. Exact when f
/// vanishes on that face; f's coefficients on the face are not read (the caller establishes that
/// they vanish). A factor that vanishes on a face of the box is positive inside it, so q has
/// the zeros and signs of f in the open box.
/// \throw InvalidInput if direction is not in [0, D), side is not 0 or 1, or the degree along
/// direction is 0.
template <int D>
BernsteinTensor<D> bernstein_divide_by_face(const BernsteinTensor<D>& f, int direction, int side);

/// The smallest and the largest coefficient of `component`: by the convex hull property they
/// bound that component of f on the box.
/// \throw InvalidInput if f has no coefficients or the component does not exist.
template <int D>
std::pair<double, double> bernstein_coefficient_range(const BernsteinTensor<D>& f, int component = 0);

/// The largest |coefficient| over all components (0 for no coefficients).
template <int D>
double bernstein_max_abs(const BernsteinTensor<D>& f);

/// The derivative with respect to a parameter that runs over an interval of length
/// `interval_length` while the local one runs over [0, 1] (1: the local derivative), in
/// Bernstein form of one degree less along `direction`: (n / length) (c_{a+e} - c_a), with the
/// factor n / length rounded once. A direction of degree 0 gives the zero polynomial of degree 0
/// there. \throw InvalidInput if direction is not in [0, D).
template <int D>
BernsteinTensor<D> bernstein_derivative(const BernsteinTensor<D>& f, int direction, double interval_length = 1.0);

/// The smallest and the largest coefficient of the local derivative of `component` along
/// `direction` (bernstein_derivative without forming it); {0, 0} for degree 0.
/// \throw InvalidInput if direction is not in [0, D) or the component does not exist.
template <int D>
std::pair<double, double> bernstein_derivative_range(const BernsteinTensor<D>& f, int direction, int component = 0);

/// The product f g in Bernstein form, of degree f.degrees + g.degrees: each coefficient is a
/// convex combination of products f_a g_b (Vandermonde's identity), computed by convolution in
/// the scaled basis. Components: equal counts multiply componentwise; a scalar factor scales
/// every component of the other. \throw InvalidInput for other combinations.
template <int D>
BernsteinTensor<D> bernstein_product(const BernsteinTensor<D>& f, const BernsteinTensor<D>& g);

/// f^n (n >= 0; f^0 is the scalar constant 1 of degree 0). \throw InvalidInput if n < 0 or f is
/// not scalar (for n >= 2).
template <int D>
BernsteinTensor<D> bernstein_power(const BernsteinTensor<D>& f, int n);

/// The same polynomial with each degree raised to `degrees` (>= the current ones): the product
/// with the constant 1 written in degree (degrees - f.degrees).
/// \throw InvalidInput if a target degree is below the current one.
template <int D>
BernsteinTensor<D> bernstein_elevate(const BernsteinTensor<D>& f, const BernsteinDegrees<D>& degrees);

/// sum += f (same degrees and components). \throw InvalidInput if they differ.
template <int D>
void bernstein_add(BernsteinTensor<D>& sum, const BernsteinTensor<D>& f);

/// Components [first, first + count) of f as a polynomial with `count` components.
/// \throw InvalidInput if that range is not inside [0, f.components).
template <int D>
BernsteinTensor<D> bernstein_components(const BernsteinTensor<D>& f, int first, int count = 1);

/// The blossom (polar form) of a univariate f of degree n at the local parameters
/// arguments[0 .. n) (de Casteljau with one argument per level; Ramshaw 1989), written to
/// values[0 .. f.components). At n equal arguments t it is f(t).
void bernstein_blossom(const BernsteinTensor<1>& f, const double* arguments, double* values);

/// f in the scaled basis: each coefficient times its binomials, multiplied in direction order.
template <int D>
ScaledBernsteinTensor<D> bernstein_scaled(const BernsteinTensor<D>& f);
/// The same, reusing the storage of a temporary (no allocation).
template <int D>
ScaledBernsteinTensor<D> bernstein_scaled(BernsteinTensor<D>&& f);

/// The Bernstein coefficients of a scaled tensor: each divided by the product of its binomials.
template <int D>
BernsteinTensor<D> bernstein_unscaled(const ScaledBernsteinTensor<D>& f);
/// The same, reusing the storage of a temporary (no allocation).
template <int D>
BernsteinTensor<D> bernstein_unscaled(ScaledBernsteinTensor<D>&& f);

/// out += sign * (a b) in the scaled basis, where out has degrees a.degrees + b.degrees: one
/// multiply-add per pair of coefficients and no allocation (the inner loop of every product).
/// Components as in bernstein_product, out having the larger count.
/// \throw InvalidInput if out's degrees or components do not fit.
template <int D>
void scaled_product_add(const ScaledBernsteinTensor<D>& a, const ScaledBernsteinTensor<D>& b, double sign,
                        ScaledBernsteinTensor<D>& out);

}  // namespace volspline
