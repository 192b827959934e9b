#pragma once
// Swept solids made in code for the rank-deficient set (Conkey–Joy 2000): a polynomial generator
// g(u, v, w) = (u, v, h(u, v, w)) on [0, 1]^3 translated along a fixed direction,
// s(u, v, w, t) = g(u, v, w) + t d, as a single Bézier piece of degree (deg h, 1) built from the
// power form of h. For such a map J123 = h_w, and on h_w = 0 the image plane of dg has normal
// p = (-h_u, -h_v, 1), so the rank-deficient set is {h_w = 0, p . d = 0} (J124 = p . d there).
#include <array>
#include <vector>

#include "volspline/core/binomial.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline::test_support {

/// c u^a v^b w^c.
struct Monomial {
  double coefficient;
  int a, b, c;
};

/// The Bézier coefficient with index i of x^a in degree n: C(i, a) / C(n, a).
inline double monomial_bernstein(int a, int n, int i) {
  return i < a ? 0.0 : binomial_coefficient(i, a) / binomial_coefficient(n, a);
}

/// s = (u, v, h(u, v, w)) + t (d + A g) (A row-major; zero: a pure translation) as a Bézier piece
/// of degrees (degrees, 1), degrees >= 1 and at least those of h. A non-zero A turns the generator
/// as it moves (R(t) = I + t A, linear in t like the paper's B-spline frames). `end_weight`: the
/// weight of the control points at t = 1 (those at t = 0 have weight 1); 1 gives a polynomial
/// map, another value the same set of points reparameterised rationally in t. `shear` adds
/// shear * w to the generator's x (so that its null direction on the fold is not e_w).
inline BSplineHypervolume translated_generator(const std::vector<Monomial>& h, std::array<int, 3> degrees,
                                               const std::array<double, 3>& direction,
                                               const std::array<double, 9>& spin = {}, double end_weight = 1.0,
                                               double shear = 0.0) {
  std::vector<double> weights;
  std::vector<double> points;
  for (int l = 0; l <= 1; ++l) {
    for (int k = 0; k <= degrees[2]; ++k) {
      for (int j = 0; j <= degrees[1]; ++j) {
        for (int i = 0; i <= degrees[0]; ++i) {
          double z = 0;
          for (const Monomial& m : h) {
            z += m.coefficient * monomial_bernstein(m.a, degrees[0], i) * monomial_bernstein(m.b, degrees[1], j) *
                 monomial_bernstein(m.c, degrees[2], k);
          }
          const std::array<double, 3> g{static_cast<double>(i) / degrees[0] + shear * k / degrees[2],
                                        static_cast<double>(j) / degrees[1], z};
          for (std::size_t r = 0; r < 3; ++r) {
            const double turned = spin[3 * r] * g[0] + spin[3 * r + 1] * g[1] + spin[3 * r + 2] * g[2];
            points.push_back(g[r] + l * (direction[r] + turned));
          }
          if (end_weight != 1.0) weights.push_back(l == 0 ? 1.0 : end_weight);
        }
      }
    }
  }
  return BSplineHypervolume({KnotVector::bezier(degrees[0]), KnotVector::bezier(degrees[1]), KnotVector::bezier(degrees[2]),
                             KnotVector::bezier(1)},
                            3, std::move(points), std::move(weights));
}

}  // namespace volspline::test_support
