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

/// s = (u, v, h(u, v, w)) + t d as a Bézier piece of degrees (degrees, 1), degrees >= 1 and at
/// least those of h.
inline BSplineHypervolume translated_generator(const std::vector<Monomial>& h, std::array<int, 3> degrees,
                                               const std::array<double, 3>& direction) {
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
          points.push_back(static_cast<double>(i) / degrees[0] + l * direction[0]);
          points.push_back(static_cast<double>(j) / degrees[1] + l * direction[1]);
          points.push_back(z + l * direction[2]);
        }
      }
    }
  }
  return BSplineHypervolume({KnotVector::bezier(degrees[0]), KnotVector::bezier(degrees[1]), KnotVector::bezier(degrees[2]),
                             KnotVector::bezier(1)},
                            3, std::move(points));
}

}  // namespace volspline::test_support
