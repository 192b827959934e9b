// Trivariate simplex splines (Hua, He and Qin 2004, §3.1 and §6.1): normalisation, the half-open
// rule, independence of the recurrence from its choice of knots, derivatives, invariances and
// line integrals, each against an independent computation.
#include "volspline/simplex/simplex_spline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "simplex/simplex_recurrence.h"
#include "support/simplex_domains.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::factorial;
using test_support::kInfinity;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Knots = std::vector<Vector3d>;


Knots random_knots(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Knots knots(count);
  for (auto& k : knots) k = Vector3d(u(rng), u(rng), u(rng));
  return knots;
}

// A point of the knots' convex hull: a random convex combination.
Vector3d random_point_in_hull(std::mt19937& rng, const Knots& knots) {
  std::exponential_distribution<double> e(1.0);
  Vector3d x = Vector3d::Zero();
  double total = 0;
  for (const auto& k : knots) {
    const double w = e(rng);
    x += w * k;
    total += w;
  }
  return x / total;
}

// Gauss–Legendre rules on [-1, 1]: 3 points (exact to degree 5) and 4 points (degree 7).
struct GaussRule {
  std::array<double, 4> nodes;
  std::array<double, 4> weights;
  int size;
};
constexpr GaussRule kGauss3 = {{-0.7745966692414834, 0.0, 0.7745966692414834, 0.0},
                               {0.5555555555555556, 0.8888888888888888, 0.5555555555555556, 0.0},
                               3};
constexpr GaussRule kGauss4 = {{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526},
                               {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538},
                               4};

// ∫ f over [lo, hi] by `rule` on each piece between sorted breakpoints: exact for piecewise
// polynomials of the rule's degree with breaks only there.
template <class F>
double piecewise_gauss(std::vector<double> breaks, double lo, double hi, const GaussRule& rule, F&& f) {
  breaks.push_back(lo);
  breaks.push_back(hi);
  std::sort(breaks.begin(), breaks.end());
  double sum = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = std::max(lo, breaks[i]);
    const double b = std::min(hi, breaks[i + 1]);
    if (!(b > a)) continue;
    for (int g = 0; g < rule.size; ++g) {
      sum += 0.5 * (b - a) * rule.weights[g] * f(0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[g]);
    }
  }
  return sum;
}

// ∫_a^b M(o + t d) dt by quadrature of point values (the memoised point recurrence) between the
// crossings of the line with every plane through three knots: M is a polynomial of degree
// n <= 5 on each piece.
double line_integral_by_quadrature(const Vector3d& o, const Vector3d& d, double a, double b, const Knots& knots) {
  std::vector<double> breaks;
  const int m = static_cast<int>(knots.size());
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      for (int k = j + 1; k < m; ++k) {
        const Vector3d n = (knots[j] - knots[i]).cross(knots[k] - knots[i]);
        const double denominator = n.dot(d);
        if (denominator != 0) breaks.push_back(n.dot(knots[i] - o) / denominator);
      }
    }
  }
  // Outside the knots' bounding box M vanishes: clip infinite bounds there.
  double lo = a;
  double hi = b;
  for (int c = 0; c < 3; ++c) {
    double kmin = kInfinity;
    double kmax = -kInfinity;
    for (const auto& k : knots) {
      kmin = std::min(kmin, k[c]);
      kmax = std::max(kmax, k[c]);
    }
    if (d[c] != 0) {
      double t0 = (kmin - o[c]) / d[c];
      double t1 = (kmax - o[c]) / d[c];
      if (t0 > t1) std::swap(t0, t1);
      lo = std::max(lo, t0);
      hi = std::min(hi, t1);
    }
  }
  if (!(hi > lo)) return 0;
  return piecewise_gauss(breaks, lo, hi, kGauss3, [&](double t) { return simplex_spline_jet(o + t * d, knots, 0).value; });
}

// ∫_{R^3} M exactly up to rounding: G(x) = ∫∫ M(x, y, z) dy dz is a univariate spline of degree
// n + 2 with breaks at the knots' x (the projection of the simplex measure onto a line), so
// 4-point Gauss per knot interval is exact for n + 2 <= 7; for fixed x, L(y) = ∫ M(x, y, z) dz is
// a polynomial of degree n + 1 <= 5 between the crossings of the vertical line with the lines
// through two projected knots (3-point Gauss); L itself comes from the line-integral recurrence
// along z (not the projection identity).
double integral_over_space(const Knots& knots) {
  std::vector<double> xs;
  for (const auto& k : knots) xs.push_back(k.x());
  const auto [xlo, xhi] = std::minmax_element(xs.begin(), xs.end());
  return piecewise_gauss(xs, *xlo, *xhi, kGauss4, [&](double x) {
    // The knot net of the projected (bivariate) spline is the segments between two projected
    // knots; their crossings with the vertical line are its breaks, and the extreme ones bound the
    // projected hull.
    std::vector<double> ys;
    for (std::size_t i = 0; i < knots.size(); ++i) {
      for (std::size_t j = i + 1; j < knots.size(); ++j) {
        const Vector3d& p = knots[i];
        const Vector3d& q = knots[j];
        if (p.x() != q.x() && (x - p.x()) * (x - q.x()) <= 0) {
          ys.push_back(p.y() + (x - p.x()) * (q.y() - p.y()) / (q.x() - p.x()));
        }
      }
    }
    if (ys.empty()) return 0.0;
    const auto [ylo, yhi] = std::minmax_element(ys.begin(), ys.end());
    return piecewise_gauss(ys, *ylo, *yhi, kGauss3, [&](double y) {
      return simplex_spline_line_integral(Vector3d(x, y, 0), Vector3d::UnitZ(), -kInfinity, kInfinity, knots);
    });
  });
}

TEST(SimplexSpline, DegreeZeroIsOneOverDeterminantOnTheHalfOpenTetrahedron) {
  const Knots knots = {Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 3, 0), Vector3d(0, 0, 1)};
  EXPECT_DOUBLE_EQ(simplex_spline_value(Vector3d(0.2, 0.3, 0.1), knots), 1.0 / 6.0);
  EXPECT_EQ(simplex_spline_value(Vector3d(2, 3, 1), knots), 0.0);
  // The origin is a knot; the perturbation + ε e_x + ε² e_y + ε³ e_z enters the tetrahedron.
  EXPECT_DOUBLE_EQ(simplex_spline_value(Vector3d(0, 0, 0), knots), 1.0 / 6.0);
  // (2, 0, 0): the perturbation leaves through x + y/3... (x/2 + y/3 + z > 1).
  EXPECT_EQ(simplex_spline_value(Vector3d(2, 0, 0), knots), 0.0);
}

TEST(SimplexSpline, IntegralOverSpaceIsNFactorialOverNPlusThreeFactorial) {
  std::mt19937 rng(11);
  for (int n = 0; n <= 4; ++n) {
    const Knots knots = random_knots(rng, n + 4);
    EXPECT_NEAR(integral_over_space(knots), factorial(n) / factorial(n + 3), 1e-12 * factorial(n) / factorial(n + 3))
        << "degree " << n;
  }
}

// The half-open tetrahedra of Kuhn's triangulation of the unit cube (x_σ0 >= x_σ1 >= x_σ2)
// partition the half-open cube [0, 1)^3: every grid point of it, on faces and edges shared by
// tetrahedra too, lies in exactly one; points with a coordinate 1 lie in none.
TEST(SimplexSpline, HalfOpenTetrahedraOfATriangulationPartitionTheCube) {
  std::array<int, 3> order = {0, 1, 2};
  std::vector<std::array<Vector3d, 4>> tetrahedra;
  do {
    std::array<Vector3d, 4> t;
    t[0] = Vector3d::Zero();
    for (int i = 0; i < 3; ++i) t[i + 1] = t[i] + Vector3d::Unit(order[i]);
    tetrahedra.push_back(t);
  } while (std::next_permutation(order.begin(), order.end()));
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      for (int k = 0; k <= 4; ++k) {
        const Vector3d x(i / 4.0, j / 4.0, k / 4.0);
        int holders = 0;
        for (const auto& t : tetrahedra) holders += in_half_open_tetrahedron(x, t[0], t[1], t[2], t[3]);
        EXPECT_EQ(holders, (i < 4 && j < 4 && k < 4) ? 1 : 0) << x.transpose();
      }
    }
  }
  EXPECT_FALSE(in_half_open_tetrahedron(Vector3d::Zero(), Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                        Vector3d(1, 1, 0)));
}

TEST(SimplexSpline, HalfOpenTrianglesOfATriangulationPartitionTheSquare) {
  const Vector2d a(0, 0), b(1, 0), c(1, 1), d(0, 1);
  for (int i = 0; i <= 4; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const Vector2d y(i / 4.0, j / 4.0);
      const int holders = in_half_open_triangle(y, a, b, c) + in_half_open_triangle(y, a, c, d);
      EXPECT_EQ(holders, (i < 4 && j < 4) ? 1 : 0) << y.transpose();
    }
  }
  EXPECT_FALSE(in_half_open_triangle(a, a, b, Vector2d(2, 0)));
}

// Eq. 1 with W chosen by a test: the first independent four in increasing knot order, or a
// pseudo-random independent four (among those not far smaller than the largest, so that the
// comparison is not one of lost digits).
double value_with_choice(const Vector3d& x, const Knots& knots, bool first_independent, unsigned seed) {
  simplex_detail::KnotBinding binding;
  binding.bind(knots.data(), static_cast<int>(knots.size()), simplex_detail::BarycentricChoice::kLargest);
  const simplex_detail::CustomChoice choice = [&](simplex_detail::KnotMask subset, std::array<int, 4>& w) {
    std::array<int, simplex_detail::kMaxRecurrenceKnots> idx{};
    const int m = simplex_detail::subset_indices(subset, idx);
    std::vector<std::array<int, 4>> candidates;
    std::vector<double> sizes;
    for (int a = 0; a < m; ++a)
      for (int b = a + 1; b < m; ++b)
        for (int c = b + 1; c < m; ++c)
          for (int d = c + 1; d < m; ++d) {
            const std::array<int, 4> q = {idx[a], idx[b], idx[c], idx[d]};
            if (simplex_detail::exactly_coplanar(knots[q[0]], knots[q[1]], knots[q[2]], knots[q[3]])) continue;
            candidates.push_back(q);
            sizes.push_back(std::abs(simplex_detail::oriented_det(knots[q[0]], knots[q[1]], knots[q[2]], knots[q[3]])));
          }
    if (candidates.empty()) return false;
    if (first_independent) {
      w = candidates.front();
      return true;
    }
    const double largest = *std::max_element(sizes.begin(), sizes.end());
    std::vector<std::array<int, 4>> good;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (sizes[i] >= 0.2 * largest) good.push_back(candidates[i]);
    }
    w = good[(seed * 2654435761u + subset * 40503u) % good.size()];
    return true;
  };
  binding.set_custom_choice(&choice);
  simplex_detail::PointRecurrence recurrence;
  recurrence.attach(&binding, 1024);
  recurrence.set_point(x);
  return recurrence.value((simplex_detail::KnotMask{1} << knots.size()) - 1);
}

TEST(SimplexSpline, RecurrenceIsIndependentOfTheChosenKnotsAtRandomPoints) {
  std::mt19937 rng(5);
  for (int n = 1; n <= 5; ++n) {
    const Knots knots = random_knots(rng, n + 4);
    for (int trial = 0; trial < 8; ++trial) {
      const Vector3d x = random_point_in_hull(rng, knots);
      const double reference = simplex_spline_value(x, knots);
      const double memoised = simplex_spline_jet(x, knots, 0).value;
      EXPECT_NEAR(memoised, reference, 1e-12 * std::max(1.0, std::abs(reference)));
      for (unsigned seed = 1; seed <= 3; ++seed) {
        EXPECT_NEAR(value_with_choice(x, knots, false, seed), reference, 1e-12 * std::max(1.0, std::abs(reference)))
            << "degree " << n;
      }
      // The first independent four may be slivers: digits are lost, not the value.
      EXPECT_NEAR(value_with_choice(x, knots, true, 0), reference, 1e-10 * std::max(1.0, std::abs(reference)));
    }
  }
}

// Knots on the integer grid {0, 1, 2}^3 and points on the half-integer grid: most points lie on
// knot planes, edges or knots, and many knot subsets are coplanar. The half-open rule makes every
// choice of W give the same value there.
TEST(SimplexSpline, RecurrenceIsIndependentOfTheChosenKnotsOnKnotPlanes) {
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> coordinate(0, 2);
  for (int n = 1; n <= 3; ++n) {
    Knots knots;
    while (static_cast<int>(knots.size()) < n + 4) {
      const Vector3d k(coordinate(rng), coordinate(rng), coordinate(rng));
      if (std::find(knots.begin(), knots.end(), k) == knots.end()) knots.push_back(k);
    }
    int nonzero = 0;
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        for (int k = 0; k <= 4; ++k) {
          const Vector3d x(i / 2.0, j / 2.0, k / 2.0);
          const double reference = simplex_spline_value(x, knots);
          nonzero += reference != 0;
          for (unsigned seed = 1; seed <= 2; ++seed) {
            ASSERT_NEAR(value_with_choice(x, knots, false, seed), reference, 1e-12) << x.transpose();
          }
          ASSERT_NEAR(value_with_choice(x, knots, true, 0), reference, 1e-12) << x.transpose();
        }
      }
    }
    EXPECT_GT(nonzero, 0);
  }
}

TEST(SimplexSpline, RepeatedAndCoplanarKnotsGiveFiniteValues) {
  std::mt19937 rng(3);
  // Five coplanar knots plus one: a degree-2 spline with coplanar 4- and 5-subsets; a repeated knot.
  const Knots knots = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(1, 1, 0),
                       Vector3d(0.5, 0.2, 0), Vector3d(0.3, 0.3, 1)};
  const Knots repeated = {Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0),
                          Vector3d(0, 0, 1)};
  const Knots flat = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(1, 1, 0), Vector3d(2, 3, 0)};
  for (int trial = 0; trial < 50; ++trial) {
    const Vector3d x = random_point_in_hull(rng, knots);
    EXPECT_TRUE(std::isfinite(simplex_spline_value(x, knots)));
    const auto jet = simplex_spline_jet(x, knots, 2);
    EXPECT_TRUE(std::isfinite(jet.value) && jet.gradient.allFinite() && jet.hessian.allFinite());
    EXPECT_NEAR(value_with_choice(x, knots, false, 7), simplex_spline_value(x, knots), 1e-12);
    EXPECT_EQ(simplex_spline_value(x, flat), 0.0);
    // One repeated vertex: the spline is λ_0(x)/|det| on the tetrahedron (the degree-1 Bernstein
    // polynomial of the doubled vertex, divided by |det| = 1).
    const Vector3d y = random_point_in_hull(rng, repeated);
    EXPECT_NEAR(simplex_spline_value(y, repeated), 1 - y.sum(), 1e-14);
  }
  // These splines jump across the planes of their coplanar knots; the line integrals (eq. 16 with
  // the integrals of the flat subsets) still match quadrature.
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const Knots* k : {&knots, &repeated}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Vector3d o = random_point_in_hull(rng, *k);
      const Vector3d d(normal(rng), normal(rng), normal(rng));
      for (const auto& [a, b] : {std::pair{-kInfinity, kInfinity}, std::pair{-0.1, 0.2}}) {
        EXPECT_NEAR(simplex_spline_line_integral(o, d, a, b, *k), line_integral_by_quadrature(o, d, a, b, *k), 1e-12);
      }
    }
  }
}

// Degree 1 in closed form (independent of eq. 1): M is the push-forward of the uniform measure on
// the 4-simplex, normalised to ∫ = 1/4!. The fibre over x is the segment ζ = ζ* + s ν, ζ >= 0,
// where ν spans the affine dependencies of the five knots with ν_i = ±det of the four others,
// and ζ* is any barycentric representation of x. By the coarea formula and Cauchy–Binet
// (|ν'|² = det(B Bᵀ) for B = [x_i - x_0]), M(x) is the length of the s-interval.
double degree_one_closed_form(const Vector3d& x, const Knots& k) {
  std::array<double, 5> nu{};
  for (int i = 0; i < 5; ++i) {
    std::array<Vector3d, 4> others;
    int m = 0;
    for (int j = 0; j < 5; ++j) {
      if (j != i) others[m++] = k[j];
    }
    nu[i] = ((i % 2 == 0) ? 1.0 : -1.0) * simplex_detail::oriented_det(others[0], others[1], others[2], others[3]);
  }
  // ζ* with ζ*_4 = 0: barycentric coordinates of x in the first four knots.
  simplex_detail::BarycentricFrame frame;
  if (!simplex_detail::make_frame(k[0], k[1], k[2], k[3], frame)) return -1;
  const auto l = frame.lambda(x);
  const std::array<double, 5> zeta = {l[0], l[1], l[2], l[3], 0.0};
  double lo = -kInfinity;
  double hi = kInfinity;
  for (int i = 0; i < 5; ++i) {
    if (nu[i] > 0) lo = std::max(lo, -zeta[i] / nu[i]);
    if (nu[i] < 0) hi = std::min(hi, -zeta[i] / nu[i]);
  }
  return std::max(0.0, hi - lo);
}

TEST(SimplexSpline, DegreeOneMatchesTheFibreLengthClosedForm) {
  std::mt19937 rng(23);
  const Knots knots = random_knots(rng, 5);
  // ν is an affine dependency: Σ ν_i = 0 and Σ ν_i x_i = 0.
  for (int trial = 0; trial < 100; ++trial) {
    const Vector3d x = random_point_in_hull(rng, knots);
    EXPECT_NEAR(simplex_spline_value(x, knots), degree_one_closed_form(x, knots), 1e-12);
  }
}

TEST(SimplexSpline, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(29);
  for (int n = 2; n <= 5; ++n) {
    const Knots knots = random_knots(rng, n + 4);
    for (int trial = 0; trial < (n < 5 ? 3 : 1); ++trial) {
      const Vector3d x = random_point_in_hull(rng, knots);
      const auto jet = simplex_spline_jet(x, knots, 2);
      EXPECT_NEAR(jet.value, simplex_spline_value(x, knots), 1e-12 * std::max(1.0, jet.value));
      const double h = 1e-5;
      for (int c = 0; c < 3; ++c) {
        const Vector3d e = h * Vector3d::Unit(c);
        const double fd = (simplex_spline_value(x + e, knots) - simplex_spline_value(x - e, knots)) / (2 * h);
        EXPECT_NEAR(jet.gradient[c], fd, 1e-5 * std::max(1.0, jet.gradient.norm())) << "degree " << n;
        if (n >= 3) {
          const Vector3d fd_gradient =
              (simplex_spline_jet(x + e, knots, 1).gradient - simplex_spline_jet(x - e, knots, 1).gradient) / (2 * h);
          EXPECT_LT((jet.hessian.col(c) - fd_gradient).norm(), 1e-5 * std::max(1.0, jet.hessian.norm()));
        }
      }
      EXPECT_LT((jet.hessian - jet.hessian.transpose()).norm(), 1e-12 * std::max(1.0, jet.hessian.norm()));
      const Vector3d v(0.3, -1.2, 0.7);
      EXPECT_NEAR(simplex_spline_directional_derivative(x, knots, v), jet.gradient.dot(v),
                  1e-12 * std::max(1.0, jet.gradient.norm()));
    }
  }
}

TEST(SimplexSpline, InvariantUnderKnotPermutationsAndAffineMaps) {
  std::mt19937 rng(31);
  Eigen::Matrix3d a;
  a << 1.5, 0.2, -0.3, 0.1, 0.8, 0.4, -0.2, 0.3, 2.0;
  const Vector3d shift(0.3, -2, 5);
  for (int n = 0; n <= 4; ++n) {
    Knots knots = random_knots(rng, n + 4);
    Knots mapped;
    for (const auto& k : knots) mapped.push_back(a * k + shift);
    for (int trial = 0; trial < 10; ++trial) {
      const Vector3d x = random_point_in_hull(rng, knots);
      const double value = simplex_spline_value(x, knots);
      Knots shuffled = knots;
      std::shuffle(shuffled.begin(), shuffled.end(), rng);
      EXPECT_NEAR(simplex_spline_value(x, shuffled), value, 1e-12 * std::max(1.0, value));
      EXPECT_NEAR(simplex_spline_value(a * x + shift, mapped), value / std::abs(a.determinant()),
                  1e-12 * std::max(1.0, value));
    }
  }
}

TEST(SimplexSpline, LineIntegralOfDegreeZeroIsChordOverDeterminant) {
  const Knots knots = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1)};
  // The line (0.1, 0.2, z) crosses z in [0, 0.7]; with direction 2 e_z the parameter chord is 0.35.
  const Vector3d o(0.1, 0.2, -1);
  const Vector3d d(0, 0, 2);
  EXPECT_NEAR(simplex_spline_line_integral(o, d, -kInfinity, kInfinity, knots), 0.35, 1e-15);
  EXPECT_NEAR(simplex_spline_line_integral(o, d, 0.6, 0.7, knots), 0.1, 1e-15);
  EXPECT_EQ(simplex_spline_line_integral(o, d, 0, 0.4, knots), 0.0);
  EXPECT_NEAR(simplex_spline_full_line_integral_by_projection(o, d, knots), 0.35, 1e-15);
}

TEST(SimplexSpline, LineIntegralsAgreeWithProjectionAndQuadrature) {
  std::mt19937 rng(37);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int n = 0; n <= 5; ++n) {
    const Knots knots = random_knots(rng, n + 4);
    for (int trial = 0; trial < (n < 4 ? 3 : 1); ++trial) {
      const Vector3d x = random_point_in_hull(rng, knots);
      const Vector3d d = Vector3d(normal(rng), normal(rng), normal(rng)) * (trial + 0.5);
      const double full = simplex_spline_line_integral(x, d, -kInfinity, kInfinity, knots);
      const double scale = std::max(1.0, full);
      EXPECT_NEAR(full, simplex_spline_full_line_integral_by_projection(x, d, knots), 1e-10 * scale) << "degree " << n;
      EXPECT_NEAR(full, line_integral_by_quadrature(x, d, -kInfinity, kInfinity, knots), 1e-10 * scale);
      // Partial intervals: the boundary terms of the integration by parts.
      for (const auto& [a, b] : {std::pair{-0.1, 0.2}, std::pair{-3.0, 0.05}}) {
        EXPECT_NEAR(simplex_spline_line_integral(x, d, a, b, knots), line_integral_by_quadrature(x, d, a, b, knots),
                    1e-10 * scale)
            << "degree " << n << " [" << a << ", " << b << "]";
      }
    }
  }
}

TEST(SimplexSpline, BadKnotCountsAreInvalidInput) {
  const Knots three(3, Vector3d::Zero());
  const Knots ten(10, Vector3d::Zero());
  EXPECT_THROW(simplex_spline_value(Vector3d::Zero(), three), InvalidInput);
  EXPECT_THROW(simplex_spline_value(Vector3d::Zero(), ten), InvalidInput);
  EXPECT_THROW(simplex_spline_jet(Vector3d::Zero(), ten, 1), InvalidInput);
  EXPECT_THROW(simplex_spline_jet(Vector3d::Zero(), Knots(4, Vector3d::Zero()), 3), InvalidInput);
  EXPECT_THROW(simplex_spline_line_integral(Vector3d::Zero(), Vector3d::UnitX(), 0, 1, three), InvalidInput);
  EXPECT_THROW(simplex_spline_line_integral(Vector3d::Zero(), Vector3d::UnitX(), 1, 0, Knots(4, Vector3d::Zero())),
               InvalidInput);
  EXPECT_THROW(simplex_spline_full_line_integral_by_projection(Vector3d::Zero(), Vector3d::Zero(),
                                                               Knots(4, Vector3d::UnitX())),
               InvalidInput);
  const Knots unit = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  const Vector3d nan_point(std::nan(""), 0, 0);
  EXPECT_THROW(simplex_spline_value(nan_point, unit), InvalidInput);
  EXPECT_THROW(simplex_spline_jet(nan_point, unit, 1), InvalidInput);
  EXPECT_THROW(simplex_spline_line_integral(nan_point, Vector3d::UnitX(), 0, 1, unit), InvalidInput);
  EXPECT_THROW(simplex_spline_line_integral(Vector3d::Zero(), Vector3d::UnitX(), std::nan(""), 1, unit), InvalidInput);
  const std::vector<Vector2d> two(2, Vector2d::Zero());
  EXPECT_THROW(bivariate_simplex_spline_value(Vector2d::Zero(), two), InvalidInput);
}

}  // namespace
}  // namespace volspline
