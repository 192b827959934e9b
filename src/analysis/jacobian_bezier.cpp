#include "volspline/analysis/jacobian_bezier.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "volspline/core/bernstein_tensor.h"
#include "volspline/core/error.h"

namespace volspline {

namespace {

constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;

// Higham's gamma_k = k u / (1 - k u): the relative error of k chained roundings.
double gamma(double k) { return k * kUnitRoundoff / (1 - k * kUnitRoundoff); }


// A tensor of scaled Bernstein coefficients (c_ijk C(n0, i) C(n1, j) C(n2, k)): in this basis a
// product of polynomials is a plain convolution of coefficient tensors.
struct Scaled {
  std::array<int, 3> n{1, 1, 1};  // coefficients per direction = degree + 1
  std::vector<double> c;
  Scaled() = default;
  explicit Scaled(std::array<int, 3> sizes) : n(sizes), c(static_cast<std::size_t>(sizes[0] * sizes[1] * sizes[2]), 0.0) {}
};

std::array<int, 3> product_size(const Scaled& a, const Scaled& b) {
  return {a.n[0] + b.n[0] - 1, a.n[1] + b.n[1] - 1, a.n[2] + b.n[2] - 1};
}

// out += sign * (a * b); out has product_size(a, b).
void convolve_add(const Scaled& a, const Scaled& b, double sign, Scaled& out) {
  const int a0 = a.n[0], a1 = a.n[1], a2 = a.n[2];
  const int b0 = b.n[0], b1 = b.n[1], b2 = b.n[2];
  const int o0 = out.n[0], o1 = out.n[1];
  const double* __restrict bd = b.c.data();
  double* __restrict od = out.c.data();
  for (int k = 0; k < a2; ++k) {
    for (int j = 0; j < a1; ++j) {
      for (int i = 0; i < a0; ++i) {
        const double av = sign * a.c[static_cast<std::size_t>(i + a0 * (j + a1 * k))];
        if (av == 0) continue;
        for (int kk = 0; kk < b2; ++kk) {
          for (int jj = 0; jj < b1; ++jj) {
            double* __restrict o = od + (i + o0 * ((j + jj) + o1 * (k + kk)));
            const double* __restrict bb = bd + b0 * (jj + b1 * kk);
            for (int ii = 0; ii < b0; ++ii) o[ii] += av * bb[ii];
          }
        }
      }
    }
  }
}

// The scaled Bernstein coefficients of component `component` of the cell's homogeneous
// coefficients (stride `size`), differentiated in `direction` (-1: not differentiated) with
// respect to the global parameter.
Scaled scaled_component(const BSplineVolume& cell, int component, int direction) {
  const auto deg = cell.degrees();
  const std::array<int, 3> n{deg[0] + 1, deg[1] + 1, deg[2] + 1};
  const std::vector<double>& h = cell.homogeneous();
  const int size = cell.coefficient_size();
  std::array<int, 3> m = n;
  double factor = 1;
  if (direction >= 0) {
    m[static_cast<std::size_t>(direction)] -= 1;
    factor = deg[static_cast<std::size_t>(direction)] /
             (cell.domain_max(direction) - cell.domain_min(direction));
  }
  Scaled s(m);
  for (int k = 0; k < m[2]; ++k) {
    for (int j = 0; j < m[1]; ++j) {
      for (int i = 0; i < m[0]; ++i) {
        auto at = [&](int a, int b, int c) { return h[static_cast<std::size_t>((a + n[0] * (b + n[1] * c)) * size + component)]; };
        double v = at(i, j, k);
        if (direction == 0) v = factor * (at(i + 1, j, k) - v);
        if (direction == 1) v = factor * (at(i, j + 1, k) - v);
        if (direction == 2) v = factor * (at(i, j, k + 1) - v);
        s.c[static_cast<std::size_t>(i + m[0] * (j + m[1] * k))] =
            v * binomial_coefficient(m[0] - 1, i) * binomial_coefficient(m[1] - 1, j) * binomial_coefficient(m[2] - 1, k);
      }
    }
  }
  return s;
}

// The largest 1-norm of the (unscaled) coefficient vectors of the homogeneous coefficients
// differentiated in `direction` (-1: not differentiated), over components [first, first + count).
double max_one_norm(const BSplineVolume& cell, int first, int count, int direction) {
  const auto deg = cell.degrees();
  const std::array<int, 3> n{deg[0] + 1, deg[1] + 1, deg[2] + 1};
  const std::vector<double>& h = cell.homogeneous();
  const int size = cell.coefficient_size();
  double factor = 1;
  std::array<int, 3> step{0, 0, 0};
  std::array<int, 3> m = n;
  if (direction >= 0) {
    m[static_cast<std::size_t>(direction)] -= 1;
    step[static_cast<std::size_t>(direction)] = 1;
    factor = deg[static_cast<std::size_t>(direction)] / (cell.domain_max(direction) - cell.domain_min(direction));
  }
  double best = 0;
  for (int k = 0; k < m[2]; ++k) {
    for (int j = 0; j < m[1]; ++j) {
      for (int i = 0; i < m[0]; ++i) {
        const std::size_t a = static_cast<std::size_t>((i + n[0] * (j + n[1] * k)) * size);
        const std::size_t b = static_cast<std::size_t>(((i + step[0]) + n[0] * ((j + step[1]) + n[1] * (k + step[2]))) * size);
        double norm = 0;
        for (int c = first; c < first + count; ++c) {
          norm += direction >= 0 ? std::abs(h[b + static_cast<std::size_t>(c)] - h[a + static_cast<std::size_t>(c)])
                                 : std::abs(h[a + static_cast<std::size_t>(c)]);
        }
        best = std::max(best, norm * std::abs(factor));
      }
    }
  }
  return best;
}

BernsteinTensor unscale(const Scaled& s) {
  BernsteinTensor t({s.n[0] - 1, s.n[1] - 1, s.n[2] - 1});
  for (int k = 0; k < s.n[2]; ++k) {
    for (int j = 0; j < s.n[1]; ++j) {
      for (int i = 0; i < s.n[0]; ++i) {
        t.at(i, j, k) = s.c[static_cast<std::size_t>(i + s.n[0] * (j + s.n[1] * k))] /
                        (binomial_coefficient(s.n[0] - 1, i) * binomial_coefficient(s.n[1] - 1, j) * binomial_coefficient(s.n[2] - 1, k));
      }
    }
  }
  return t;
}

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

  if (!rational) {
    // J = p_u . (p_v x p_w), Joy–Duchaineau §4.
    std::array<Scaled, 3> du, dv, dw;
    for (int c = 0; c < 3; ++c) {
      du[static_cast<std::size_t>(c)] = scaled_component(cell, c, 0);
      dv[static_cast<std::size_t>(c)] = scaled_component(cell, c, 1);
      dw[static_cast<std::size_t>(c)] = scaled_component(cell, c, 2);
    }
    std::array<Scaled, 3> cross;
    for (int c = 0; c < 3; ++c) {
      const std::size_t a = static_cast<std::size_t>((c + 1) % 3), b = static_cast<std::size_t>((c + 2) % 3);
      cross[static_cast<std::size_t>(c)] = Scaled(product_size(dv[0], dw[0]));
      convolve_add(dv[a], dw[b], 1.0, cross[static_cast<std::size_t>(c)]);
      convolve_add(dv[b], dw[a], -1.0, cross[static_cast<std::size_t>(c)]);
    }
    Scaled j(product_size(du[0], cross[0]));
    for (std::size_t c = 0; c < 3; ++c) convolve_add(du[c], cross[c], 1.0, j);
    result.coefficients = unscale(j);
    const double roundings = 16 + 2.0 * static_cast<double>(dv[0].c.size()) + 3.0 * static_cast<double>(du[0].c.size());
    std::vector<double> A{max_one_norm(cell, 0, 3, 0), max_one_norm(cell, 0, 3, 1), max_one_norm(cell, 0, 3, 2)};
    std::vector<double> rho(3);
    for (std::size_t d = 0; d < 3; ++d) rho[d] = 3 * 2 * input_error * inverse_size[d];
    result.error_bound = product_error_bound(A, rho, roundings);
    return result;
  }

  // Rational: D = det[P; P_u; P_v; P_w] with columns (w, wx, wy, wz) equals w^4 J. Expanded
  // along the row P: D = sum_j (-1)^j P_j T_j, T_j the 3 x 3 minor of (P_u, P_v, P_w) without
  // column j, each built from the 2 x 2 minors of (P_v, P_w).
  const std::array<int, 4> column{3, 0, 1, 2};  // homogeneous storage is (wx, wy, wz, w)
  std::array<Scaled, 4> p, du, dv, dw;
  for (std::size_t c = 0; c < 4; ++c) {
    p[c] = scaled_component(cell, column[c], -1);
    du[c] = scaled_component(cell, column[c], 0);
    dv[c] = scaled_component(cell, column[c], 1);
    dw[c] = scaled_component(cell, column[c], 2);
  }
  Scaled minor2[4][4];
  for (std::size_t a = 0; a < 4; ++a) {
    for (std::size_t b = a + 1; b < 4; ++b) {
      minor2[a][b] = Scaled(product_size(dv[0], dw[0]));
      convolve_add(dv[a], dw[b], 1.0, minor2[a][b]);
      convolve_add(dv[b], dw[a], -1.0, minor2[a][b]);
    }
  }
  Scaled d(product_size(p[0], Scaled(product_size(du[0], minor2[0][1]))));
  for (std::size_t j = 0; j < 4; ++j) {
    std::array<std::size_t, 3> s{};
    std::size_t m = 0;
    for (std::size_t c = 0; c < 4; ++c) {
      if (c != j) s[m++] = c;
    }
    Scaled minor3(product_size(du[0], minor2[0][1]));
    convolve_add(du[s[0]], minor2[s[1]][s[2]], 1.0, minor3);
    convolve_add(du[s[1]], minor2[s[0]][s[2]], -1.0, minor3);
    convolve_add(du[s[2]], minor2[s[0]][s[1]], 1.0, minor3);
    convolve_add(p[j], minor3, (j % 2 == 0) ? 1.0 : -1.0, d);
  }
  result.coefficients = unscale(d);
  const double roundings = 16 + 2.0 * static_cast<double>(dv[0].c.size()) + 3.0 * static_cast<double>(du[0].c.size()) +
                           4.0 * static_cast<double>(p[0].c.size());
  std::vector<double> A{max_one_norm(cell, 0, 4, -1), max_one_norm(cell, 0, 4, 0), max_one_norm(cell, 0, 4, 1),
                        max_one_norm(cell, 0, 4, 2)};
  std::vector<double> rho{4 * input_error, 4 * 2 * input_error * inverse_size[0], 4 * 2 * input_error * inverse_size[1],
                          4 * 2 * input_error * inverse_size[2]};
  result.error_bound = product_error_bound(A, rho, roundings);
  result.weights = BernsteinTensor({deg[0], deg[1], deg[2]});
  const std::vector<double>& h = cell.homogeneous();
  for (std::size_t i = 0; i < result.weights.count(); ++i) result.weights.coefficients[i] = h[i * 4 + 3];
  return result;
}

double extraction_error_bound(const BSplineVolume& volume) {
  const std::vector<double>& h = volume.homogeneous();
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
