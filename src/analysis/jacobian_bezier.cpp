#include "volspline/analysis/jacobian_bezier.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "volspline/core/bernstein_tensor.h"
#include "unit_roundoff.h"
#include "volspline/core/error.h"

namespace volspline {

namespace {

// Higham's gamma_k = k u / (1 - k u): the relative error of k chained roundings.
double gamma(double k) { return k * kUnitRoundoff / (1 - k * kUnitRoundoff); }


using Scaled = ScaledBernsteinTensor<3>;

// The cell's homogeneous coefficients as one polynomial with coefficient_size() components: a
// Bézier cell's control points are its Bernstein coefficients.
BernsteinTensor<3> homogeneous_polynomial(const BSplineVolume& cell) {
  BernsteinTensor<3> h;
  h.degrees = cell.degrees();
  h.components = cell.coefficient_size();
  h.coefficients = cell.homogeneous();
  return h;
}

double cell_length(const BSplineVolume& cell, int direction) { return cell.domain_max(direction) - cell.domain_min(direction); }

// The homogeneous coefficients differentiated along `direction` (-1: not differentiated) with
// respect to the global parameter, component by component, in the scaled basis.
std::array<Scaled, 4> scaled_components(const BSplineVolume& cell, const BernsteinTensor<3>& h, int direction,
                                        const std::array<int, 4>& components, int count) {
  const BernsteinTensor<3> f = direction < 0 ? h : bernstein_derivative(h, direction, cell_length(cell, direction));
  std::array<Scaled, 4> s;
  for (std::size_t c = 0; c < static_cast<std::size_t>(count); ++c) s[c] = bernstein_scaled(bernstein_components(f, components[c]));
  return s;
}

// The largest 1-norm of the (unscaled) coefficient vectors of h differentiated along `direction`
// (-1: not differentiated) with respect to the global parameter, over components [first, first +
// count): the A_i of the bound (docs/jacobian.md), sum |h_{a+e} - h_a| times |n / length|.
double max_one_norm(const BSplineVolume& cell, const BernsteinTensor<3>& h, int first, int count, int direction) {
  double factor = 1;
  std::array<int, 3> step{0, 0, 0}, m{h.size(0), h.size(1), h.size(2)};
  if (direction >= 0) {
    m[static_cast<std::size_t>(direction)] -= 1;
    step[static_cast<std::size_t>(direction)] = 1;
    factor = h.degrees[static_cast<std::size_t>(direction)] / cell_length(cell, direction);
  }
  double best = 0;
  for (int k = 0; k < m[2]; ++k) {
    for (int j = 0; j < m[1]; ++j) {
      for (int i = 0; i < m[0]; ++i) {
        double norm = 0;
        for (int c = first; c < first + count; ++c) {
          norm += direction >= 0 ? std::abs(h.at({i + step[0], j + step[1], k + step[2]}, c) - h.at({i, j, k}, c))
                                 : std::abs(h.at({i, j, k}, c));
        }
        best = std::max(best, norm * std::abs(factor));
      }
    }
  }
  return best;
}

Scaled zero_product(const Scaled& a, const Scaled& b) { return Scaled(product_degrees(a.degrees, b.degrees)); }

// Error bound of a multilinear Bernstein product of factors whose coefficient vectors have
// 1-norms at most A_i (computed) and perturbations at most rho_i: rounding gamma_K Prod(A_i +
// rho_i) plus the perturbation Prod(A_i + rho_i) - Prod(A_i), summed telescopically.
double product_error_bound(const std::vector<double>& A, const std::vector<double>& rho, double roundings) {
  double full = 1;
  for (std::size_t i = 0; i < A.size(); ++i) full *= A[i] + rho[i];
  double perturbation = 0;
  for (std::size_t i = 0; i < A.size(); ++i) {
    double term = rho[i];
    for (std::size_t j = 0; j < A.size(); ++j) {
      if (j < i) term *= A[j] + rho[j];
      if (j > i) term *= A[j];
    }
    perturbation += term;
  }
  // The factor 1.01 covers the roundings made while computing this bound itself.
  return 1.01 * (gamma(roundings) * full + perturbation);
}

}  // namespace

JacobianBernstein jacobian_bezier_coefficients(const BSplineVolume& cell, double input_error) {
  if (cell.dimension() != 3) {
    throw InvalidInput("the Jacobian determinant needs control points in R^3, got dimension " + std::to_string(cell.dimension()));
  }
  for (int d = 0; d < 3; ++d) {
    if (!cell.knot_vector(d).is_bezier()) {
      throw InvalidInput("jacobian_bezier_coefficients needs a single Bézier cell; direction " + std::to_string(d) +
                         " has interior knots (split it with bezier_pieces first)");
    }
  }
  if (!(input_error >= 0) || !std::isfinite(input_error)) throw InvalidInput("input_error must be finite and >= 0");
  const auto deg = cell.degrees();
  const bool rational = cell.is_rational();
  JacobianBernstein result;
  result.homogeneous = rational;
  std::array<double, 3> inverse_size{};
  for (int d = 0; d < 3; ++d) inverse_size[static_cast<std::size_t>(d)] = deg[static_cast<std::size_t>(d)] / (cell.domain_max(d) - cell.domain_min(d));

  // J is invariant under translation; relative to the local origin the products below round
  // relative to the cell's size (a rational D = det[P; P_u; P_v; P_w] holds P itself).
  const BernsteinTensor<3> h = homogeneous_polynomial(cell.translated_to_local_origin());
  if (!rational) {
    // J = p_u . (p_v x p_w), Joy–Duchaineau §4.
    const std::array<int, 4> xyz{0, 1, 2, 0};
    const auto du = scaled_components(cell, h, 0, xyz, 3), dv = scaled_components(cell, h, 1, xyz, 3),
               dw = scaled_components(cell, h, 2, xyz, 3);
    Scaled j = zero_product(du[0], zero_product(dv[0], dw[0]));
    Scaled cross = zero_product(dv[0], dw[0]);
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t a = (c + 1) % 3, b = (c + 2) % 3;
      std::fill(cross.coefficients.begin(), cross.coefficients.end(), 0.0);
      scaled_product_add(dv[a], dw[b], 1.0, cross);
      scaled_product_add(dv[b], dw[a], -1.0, cross);
      scaled_product_add(du[c], cross, 1.0, j);
    }
    result.coefficients = bernstein_unscaled(std::move(j));
    const double roundings = 16 + 2.0 * static_cast<double>(dv[0].count()) + 3.0 * static_cast<double>(du[0].count());
    std::vector<double> A{max_one_norm(cell, h, 0, 3, 0), max_one_norm(cell, h, 0, 3, 1), max_one_norm(cell, h, 0, 3, 2)};
    std::vector<double> rho(3);
    for (std::size_t d = 0; d < 3; ++d) rho[d] = 3 * 2 * input_error * inverse_size[d];
    result.error_bound = product_error_bound(A, rho, roundings);
    return result;
  }

  // Rational: D = det[P; P_u; P_v; P_w] with columns (w, wx, wy, wz) equals w^4 J. Expanded
  // along the row P: D = sum_j (-1)^j P_j T_j, T_j the 3 x 3 minor of (P_u, P_v, P_w) without
  // column j, each built from the 2 x 2 minors of (P_v, P_w).
  const std::array<int, 4> column{3, 0, 1, 2};  // homogeneous storage is (wx, wy, wz, w)
  const auto p = scaled_components(cell, h, -1, column, 4), du = scaled_components(cell, h, 0, column, 4),
             dv = scaled_components(cell, h, 1, column, 4), dw = scaled_components(cell, h, 2, column, 4);
  Scaled minor2[4][4];
  for (std::size_t a = 0; a < 4; ++a) {
    for (std::size_t b = a + 1; b < 4; ++b) {
      minor2[a][b] = zero_product(dv[0], dw[0]);
      scaled_product_add(dv[a], dw[b], 1.0, minor2[a][b]);
      scaled_product_add(dv[b], dw[a], -1.0, minor2[a][b]);
    }
  }
  Scaled minor3 = zero_product(du[0], minor2[0][1]);
  Scaled d = zero_product(p[0], minor3);
  for (std::size_t j = 0; j < 4; ++j) {
    std::array<std::size_t, 3> s{};
    std::size_t m = 0;
    for (std::size_t c = 0; c < 4; ++c) {
      if (c != j) s[m++] = c;
    }
    std::fill(minor3.coefficients.begin(), minor3.coefficients.end(), 0.0);
    scaled_product_add(du[s[0]], minor2[s[1]][s[2]], 1.0, minor3);
    scaled_product_add(du[s[1]], minor2[s[0]][s[2]], -1.0, minor3);
    scaled_product_add(du[s[2]], minor2[s[0]][s[1]], 1.0, minor3);
    scaled_product_add(p[j], minor3, (j % 2 == 0) ? 1.0 : -1.0, d);
  }
  result.coefficients = bernstein_unscaled(std::move(d));
  const double roundings = 16 + 2.0 * static_cast<double>(dv[0].count()) + 3.0 * static_cast<double>(du[0].count()) +
                           4.0 * static_cast<double>(p[0].count());
  std::vector<double> A{max_one_norm(cell, h, 0, 4, -1), max_one_norm(cell, h, 0, 4, 0), max_one_norm(cell, h, 0, 4, 1),
                        max_one_norm(cell, h, 0, 4, 2)};
  std::vector<double> rho{4 * input_error, 4 * 2 * input_error * inverse_size[0], 4 * 2 * input_error * inverse_size[1],
                          4 * 2 * input_error * inverse_size[2]};
  result.error_bound = product_error_bound(A, rho, roundings);
  result.weights = bernstein_components(h, 3);
  return result;
}

double extraction_error_bound(const BSplineVolume& volume) {
  // Extraction is done on the spline at its local origin (JacobianSubdivision), so the rounding
  // is relative to those coefficients.
  const BSplineVolume local = volume.translated_to_local_origin();
  const std::vector<double>& h = local.homogeneous();
  double largest = 0;
  for (double c : h) largest = std::max(largest, std::abs(c));
  double insertions = 0;
  for (int d = 0; d < 3; ++d) {
    const KnotVector& kv = volume.knot_vector(d);
    const int interior = static_cast<int>(kv.breakpoints().size()) - 2;
    insertions += static_cast<double>((kv.degree() + 1) * (interior + (kv.is_clamped() ? 0 : 2)));
  }
  // A rational spline's homogeneous coefficients are products w x of stored numbers: one more
  // rounding each.
  const double per_insertion = 8 * kUnitRoundoff;
  return 1.01 * (insertions * per_insertion + (volume.is_rational() ? 2 : 0) * kUnitRoundoff) * largest;
}

}  // namespace volspline
