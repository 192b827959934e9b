// The DMS basis of one domain tetrahedron (Hua, He and Qin 2004, eqs. 4-5): the memoised
// evaluation against the single-spline reference, Bernstein polynomials for collapsed knot
// clouds, line integrals, the multi-index order.
#include "volspline/simplex/dms_tetrahedron_basis.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

using test_support::factorial;
using test_support::kInfinity;
using Eigen::Vector3d;

// Knot clouds of the tetrahedron (0, e_x, e_y, e_z) with sub-knots `spread` around each vertex.
struct Clouds {
  std::array<std::vector<Vector3d>, 4> knots;
  std::array<const Vector3d*, 4> pointers() const {
    return {knots[0].data(), knots[1].data(), knots[2].data(), knots[3].data()};
  }
  std::vector<Vector3d> subset(const std::array<int, 4>& beta) const {
    std::vector<Vector3d> v;
    for (int c = 0; c < 4; ++c) {
      for (int i = 0; i <= beta[c]; ++i) v.push_back(knots[c][i]);
    }
    return v;
  }
  double scale(const std::array<int, 4>& beta) const {
    const Vector3d& a = knots[0][beta[0]];
    return std::abs((knots[1][beta[1]] - a).dot((knots[2][beta[2]] - a).cross(knots[3][beta[3]] - a)));
  }
};

Clouds make_clouds(int degree, double spread, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, spread);
  const std::array<Vector3d, 4> vertices = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                            Vector3d::UnitZ()};
  Clouds clouds;
  for (int c = 0; c < 4; ++c) {
    clouds.knots[c].push_back(vertices[c]);
    for (int i = 1; i <= degree; ++i) {
      clouds.knots[c].push_back(vertices[c] + Vector3d(normal(rng), normal(rng), normal(rng)));
    }
  }
  return clouds;
}

Vector3d random_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  return Vector3d(u(rng), u(rng), u(rng));
}


TEST(DmsTetrahedronBasis, MultiIndicesFollowTheDocumentedOrder) {
  for (int n = 0; n <= kMaxSimplexSplineDegree; ++n) {
    const auto betas = dms_multi_indices(n);
    ASSERT_EQ(static_cast<int>(betas.size()), (n + 1) * (n + 2) * (n + 3) / 6);
    EXPECT_EQ(betas.front(), (std::array<int, 4>{n, 0, 0, 0}));
    EXPECT_EQ(betas.back(), (std::array<int, 4>{0, 0, 0, n}));
    for (int p = 0; p < static_cast<int>(betas.size()); ++p) {
      EXPECT_EQ(betas[p][0] + betas[p][1] + betas[p][2] + betas[p][3], n);
      EXPECT_EQ(dms_multi_index_position(betas[p], n), p);
      // Lexicographically decreasing in (i, j, k).
      if (p > 0) {
        EXPECT_GT(betas[p - 1], betas[p]);
      }
    }
  }
  EXPECT_THROW(dms_multi_index_position({1, 0, 0, 0}, 2), InvalidInput);
  EXPECT_THROW(dms_multi_index_position({-1, 1, 1, 1}, 2), InvalidInput);
  EXPECT_THROW(DmsTetrahedronBasis(-1), InvalidInput);
  EXPECT_THROW(DmsTetrahedronBasis(kMaxSimplexSplineDegree + 1), InvalidInput);
}

TEST(DmsTetrahedronBasis, MemoisedBasisEqualsScaledReferenceSplines) {
  std::mt19937 rng(41);
  for (int n = 0; n <= kMaxSimplexSplineDegree; ++n) {
    const Clouds clouds = make_clouds(n, 0.12, rng);
    DmsTetrahedronBasis basis(n);
    DmsBasisValues out;
    for (int trial = 0; trial < (n <= 3 ? 6 : 1); ++trial) {
      const Vector3d x = random_point(rng);
      basis.evaluate(x, clouds.pointers(), 2, out);
      ASSERT_EQ(static_cast<int>(out.values.size()), basis.size());
      ASSERT_EQ(out.gradients.size(), out.values.size());
      ASSERT_EQ(out.hessians.size(), out.values.size());
      for (int b = 0; b < basis.size(); ++b) {
        const auto& beta = basis.multi_indices()[b];
        const auto knots = clouds.subset(beta);
        const double scale = clouds.scale(beta);
        const double reference = scale * simplex_spline_value(x, knots);
        EXPECT_NEAR(out.values[b], reference, 1e-12 * std::max(1.0, std::abs(reference))) << "degree " << n;
        const auto jet = simplex_spline_jet(x, knots, 2);
        EXPECT_LT((out.gradients[b] - scale * jet.gradient).norm(), 1e-11 * std::max(1.0, scale * jet.gradient.norm()));
        EXPECT_LT((out.hessians[b] - scale * jet.hessian).norm(), 1e-10 * std::max(1.0, scale * jet.hessian.norm()));
      }
    }
  }
}

// Sub-knots at exactly representable offsets and points on a grid: many points lie on knot planes,
// the domain tetrahedron's faces and edges, and the compiled recurrence (its own choice of W) must
// agree with the reference there too, by the half-open rule.
TEST(DmsTetrahedronBasis, AgreesWithTheReferenceOnKnotPlanes) {
  const std::array<Vector3d, 4> vertices = {Vector3d::Zero(), Vector3d(4, 0, 0), Vector3d(0, 4, 0),
                                            Vector3d(0, 0, 4)};
  const std::array<Vector3d, 4> offsets = {Vector3d(-1, 0, 0.5), Vector3d(0.5, -0.5, 0), Vector3d(0, 0.5, -0.5),
                                           Vector3d(0.5, 0, 0.5)};
  for (int n = 1; n <= 3; ++n) {
    Clouds clouds;
    for (int c = 0; c < 4; ++c) {
      clouds.knots[c].push_back(vertices[c]);
      for (int i = 1; i <= n; ++i) clouds.knots[c].push_back(vertices[c] + i * offsets[(c + i) % 4]);
    }
    DmsTetrahedronBasis basis(n);
    DmsBasisValues out;
    for (int i = -1; i <= 5; ++i) {
      for (int j = -1; j <= 5; ++j) {
        for (int k = -1; k <= 5; ++k) {
          const Vector3d x(i * 0.75, j * 0.75, k * 0.75);
          basis.evaluate(x, clouds.pointers(), 0, out);
          for (int b = 0; b < basis.size(); ++b) {
            const auto& beta = basis.multi_indices()[b];
            const double reference = clouds.scale(beta) * simplex_spline_value(x, clouds.subset(beta));
            ASSERT_NEAR(out.values[b], reference, 1e-12 * std::max(1.0, std::abs(reference))) << x.transpose();
          }
        }
      }
    }
  }
}

// Collapsed clouds (every sub-knot on its vertex) make the DMS basis the Bernstein basis of the
// tetrahedron, n!/β! λ^β (repeated knots: the coplanar subsets contribute 0). It sums to 1 on the
// half-open tetrahedron, faces, edges and vertices included, and to 0 outside.
TEST(DmsTetrahedronBasis, CollapsedCloudsGiveTheBernsteinBasis) {
  const std::array<Vector3d, 4> vertices = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                            Vector3d::UnitZ()};
  for (int n = 1; n <= 4; ++n) {
    Clouds clouds;
    for (int c = 0; c < 4; ++c) clouds.knots[c].assign(n + 1, vertices[c]);
    DmsTetrahedronBasis basis(n);
    DmsBasisValues out;
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        for (int k = 0; k <= 4; ++k) {
          const Vector3d x(i / 4.0, j / 4.0, k / 4.0);
          basis.evaluate(x, clouds.pointers(), 1, out);
          const std::array<double, 4> lambda = {1 - x.sum(), x.x(), x.y(), x.z()};
          const bool inside = in_half_open_tetrahedron(x, vertices[0], vertices[1], vertices[2], vertices[3]);
          double sum = 0;
          for (int b = 0; b < basis.size(); ++b) {
            const auto& beta = basis.multi_indices()[b];
            double bernstein = factorial(n);
            for (int c = 0; c < 4; ++c) bernstein *= std::pow(lambda[c], beta[c]) / factorial(beta[c]);
            EXPECT_NEAR(out.values[b], inside ? bernstein : 0.0, 1e-13) << x.transpose();
            sum += out.values[b];
          }
          EXPECT_NEAR(sum, inside ? 1.0 : 0.0, 1e-13) << x.transpose();
        }
      }
    }
  }
}

// With collapsed clouds the basis sums to the indicator of the tetrahedron, so the line integrals
// of all N_β sum to the chord length inside it. The splines jump on the faces (repeated knots):
// eq. 16 then needs the line integrals of the flat knot subsets, the measures on planes.
TEST(DmsTetrahedronBasis, LineIntegralsOfCollapsedCloudsSumToChordLengths) {
  const std::array<Vector3d, 4> vertices = {Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(),
                                            Vector3d::UnitZ()};
  std::mt19937 rng(59);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 0.5);
  for (int n = 1; n <= 3; ++n) {
    Clouds clouds;
    for (int c = 0; c < 4; ++c) clouds.knots[c].assign(n + 1, vertices[c]);
    DmsTetrahedronBasis basis(n);
    std::vector<double> out;
    for (int trial = 0; trial < 10; ++trial) {
      const Vector3d o(u(rng), u(rng), u(rng));
      const Vector3d d(normal(rng), normal(rng), normal(rng));
      // The chord: λ(o + t d) >= 0 for λ = (1 - x - y - z, x, y, z).
      double lo = -kInfinity;
      double hi = kInfinity;
      const std::array<double, 4> l = {1 - o.sum(), o.x(), o.y(), o.z()};
      const std::array<double, 4> m = {-d.sum(), d.x(), d.y(), d.z()};
      for (int j = 0; j < 4; ++j) {
        if (m[j] > 0) lo = std::max(lo, -l[j] / m[j]);
        if (m[j] < 0) hi = std::min(hi, -l[j] / m[j]);
      }
      for (const auto& [a, b] : {std::pair{-kInfinity, kInfinity}, std::pair{-0.1, 0.2}}) {
        basis.line_integrals(o, d, a, b, clouds.pointers(), out);
        double sum = 0;
        for (const double v : out) sum += v;
        EXPECT_NEAR(sum, std::max(0.0, std::min(hi, b) - std::max(lo, a)), 1e-12) << "degree " << n;
      }
    }
  }
}

TEST(DmsTetrahedronBasis, LineIntegralsEqualScaledSingleSplineIntegrals) {
  std::mt19937 rng(43);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int n = 0; n <= 4; ++n) {
    const Clouds clouds = make_clouds(n, 0.12, rng);
    DmsTetrahedronBasis basis(n);
    std::vector<double> out;
    for (int trial = 0; trial < 3; ++trial) {
      const Vector3d o = random_point(rng);
      const Vector3d d(normal(rng), normal(rng), normal(rng));
      for (const auto& [a, b] : {std::pair{-kInfinity, kInfinity}, std::pair{-0.2, 0.3}}) {
        basis.line_integrals(o, d, a, b, clouds.pointers(), out);
        ASSERT_EQ(static_cast<int>(out.size()), basis.size());
        for (int i = 0; i < basis.size(); ++i) {
          const auto& beta = basis.multi_indices()[i];
          const auto knots = clouds.subset(beta);
          const double reference = clouds.scale(beta) * simplex_spline_line_integral(o, d, a, b, knots);
          EXPECT_NEAR(out[i], reference, 1e-12 * std::max(1.0, std::abs(reference))) << "degree " << n;
          if (a == -kInfinity) {
            EXPECT_NEAR(out[i], clouds.scale(beta) * simplex_spline_full_line_integral_by_projection(o, d, knots),
                        1e-10 * std::max(1.0, std::abs(reference)));
          }
        }
      }
    }
  }
}

TEST(DmsTetrahedronBasis, ReusedObjectForgetsThePreviousTetrahedron) {
  std::mt19937 rng(47);
  const Clouds first = make_clouds(3, 0.1, rng);
  const Clouds second = make_clouds(3, 0.2, rng);
  DmsTetrahedronBasis basis(3);
  DmsBasisValues a;
  DmsBasisValues b;
  DmsBasisValues again;
  const Vector3d x(0.2, 0.3, 0.25);
  basis.evaluate(x, first.pointers(), 1, a);
  basis.evaluate(x, second.pointers(), 1, b);
  basis.evaluate(x, first.pointers(), 1, again);
  EXPECT_EQ(a.values, again.values);
  EXPECT_NE(a.values, b.values);
  // Far outside the knots: zeros at once.
  basis.evaluate(Vector3d(5, 5, 5), first.pointers(), 2, a);
  for (int i = 0; i < basis.size(); ++i) {
    EXPECT_EQ(a.values[i], 0.0);
    EXPECT_EQ(a.gradients[i], Vector3d::Zero());
  }
  EXPECT_THROW(basis.evaluate(x, first.pointers(), 3, a), InvalidInput);
  // More tetrahedra than the basis keeps compiled plans for, then the first again.
  for (int k = 0; k < 12; ++k) {
    const Clouds other = make_clouds(3, 0.1, rng);
    basis.evaluate(x, other.pointers(), 1, b);
  }
  basis.evaluate(x, first.pointers(), 1, again);
  basis.evaluate(Vector3d(0.2, 0.3, 0.25), first.pointers(), 1, a);
  EXPECT_EQ(a.values, again.values);
  std::vector<double> integrals;
  EXPECT_THROW(basis.line_integrals(x, Vector3d::UnitX(), 1, 0, first.pointers(), integrals), InvalidInput);
}

TEST(DmsTetrahedronBasis, PlansCompiledBeforehandGiveTheSameBasis) {
  std::mt19937 rng(53);
  const Clouds clouds = make_clouds(2, 0.1, rng);
  const DmsTetrahedronPlan plan(2, clouds.pointers());
  EXPECT_TRUE(plan.matches(clouds.pointers()));
  EXPECT_FALSE(plan.matches(make_clouds(2, 0.1, rng).pointers()));
  EXPECT_GT(plan.memory_bytes(), 0u);
  DmsTetrahedronBasis basis(2);
  DmsBasisValues from_plan;
  DmsBasisValues from_clouds;
  std::vector<double> integrals_from_plan;
  std::vector<double> integrals_from_clouds;
  for (int trial = 0; trial < 5; ++trial) {
    const Vector3d x = random_point(rng);
    basis.evaluate(x, plan, 2, from_plan);
    basis.evaluate(x, clouds.pointers(), 2, from_clouds);
    EXPECT_EQ(from_plan.values, from_clouds.values);
    EXPECT_EQ(from_plan.gradients, from_clouds.gradients);
    basis.line_integrals(x, Vector3d(0.3, 1, -0.2), -1, 1, plan, integrals_from_plan);
    basis.line_integrals(x, Vector3d(0.3, 1, -0.2), -1, 1, clouds.pointers(), integrals_from_clouds);
    EXPECT_EQ(integrals_from_plan, integrals_from_clouds);
  }
  DmsTetrahedronBasis cubic(3);
  EXPECT_THROW(cubic.evaluate(Vector3d::Zero(), plan, 0, from_plan), InvalidInput);
  EXPECT_THROW(basis.evaluate(Vector3d::Zero(), DmsTetrahedronPlan(), 0, from_plan), InvalidInput);
  EXPECT_THROW(DmsTetrahedronPlan(6, clouds.pointers()), InvalidInput);
  Clouds broken = clouds;
  broken.knots[2][1].x() = std::nan("");
  EXPECT_THROW(DmsTetrahedronPlan(2, broken.pointers()), InvalidInput);
  EXPECT_THROW(basis.evaluate(Vector3d(0.1, 0.1, 0.1), broken.pointers(), 0, from_plan), InvalidInput);
  EXPECT_THROW(basis.evaluate(Vector3d(std::nan(""), 0, 0), plan, 0, from_plan), InvalidInput);
}

}  // namespace
}  // namespace volspline
