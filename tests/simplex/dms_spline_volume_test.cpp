// DMS spline volumes (Hua–He–Qin §3.2): partition of unity everywhere on the closed domain,
// reproduction of polynomials of degree <= n from blossoms, gradients against finite
// differences, shared control vectors agreeing with per-tetrahedron ones, zero outside Ω.
#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {
namespace {

TetrahedralMesh cube_domain() { return test_support::jittered_cube_domain(); }

DmsSplineVolume cube_volume(int degree, DmsControlSharing sharing = DmsControlSharing::Shared) {
  return test_support::cube_simplex_volume(degree, sharing);
}

// A polynomial of degree d as a product of d linear forms a_m·x + b_m, and its blossom as a
// polynomial of degree n >= d: the mean over all orders of the n arguments of the product of
// the forms at the first d of them (symmetric, multi-affine, equal to P on the diagonal).
struct ProductPolynomial {
  std::vector<Eigen::Vector4d> forms;  // (a, b)
  double operator()(const Eigen::Vector3d& x) const {
    double v = 1;
    for (const Eigen::Vector4d& f : forms) v *= f.head<3>().dot(x) + f[3];
    return v;
  }
  double blossom(std::span<const Eigen::Vector3d> arguments) const {
    std::vector<int> order(arguments.size());
    std::iota(order.begin(), order.end(), 0);
    double sum = 0;
    int count = 0;
    do {
      double v = 1;
      for (std::size_t m = 0; m < forms.size(); ++m) v *= forms[m].head<3>().dot(arguments[static_cast<std::size_t>(order[m])]) + forms[m][3];
      sum += v;
      ++count;
    } while (std::next_permutation(order.begin(), order.end()));
    return sum / count;
  }
};

ProductPolynomial random_polynomial(int degree, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  ProductPolynomial p;
  for (int m = 0; m < degree; ++m) p.forms.emplace_back(u(rng), u(rng), u(rng), u(rng) + 1.5);
  return p;
}

// Points where the half-open rule decides: random interior points, the domain's vertices, edge
// midpoints, face centroids (interior and boundary faces), and knots.
std::vector<Eigen::Vector3d> test_points(const DmsSplineVolume& v, std::mt19937& rng) {
  std::vector<Eigen::Vector3d> points;
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 60; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  for (const Eigen::Vector3d& p : v.domain().points) points.push_back(p);
  for (std::size_t t = 0; t < v.domain().tetrahedra.size(); t += 3) {
    const auto& tet = v.domain().tetrahedra[t];
    const auto P = [&](int c) { return v.domain().points[static_cast<std::size_t>(tet[static_cast<std::size_t>(c)])]; };
    points.push_back((P(0) + P(1)) / 2);
    points.push_back((P(1) + P(2) + P(3)) / 3);
    points.push_back((P(0) + P(2) + P(3)) / 3);
  }
  for (const Eigen::Vector3d& k : v.knots().knots)
    if ((k.array() >= 0).all() && (k.array() <= 1).all()) points.push_back(k);
  return points;
}

TEST(DmsSplineVolume, BasisSumsToOneEverywhereOnTheClosedDomain) {
  std::mt19937 rng(11);
  for (int degree = 0; degree <= 3; ++degree) {
    const DmsSplineVolume v = cube_volume(degree, degree == 0 ? DmsControlSharing::PerTetrahedron : DmsControlSharing::Shared);
    DmsSplineEvaluator evaluator(v);
    std::set<std::array<double, 3>> knots;
    for (const Eigen::Vector3d& k : v.knots().knots) knots.insert({k.x(), k.y(), k.z()});
    for (const Eigen::Vector3d& x : test_points(v, rng)) {
      // Issue 13 asks for 1e-12 everywhere. Measured: up to 4.3e-13 at knots (domain vertices and
      // sub-knots, where the knot tetrahedra are small), 3.4e-14 at edge midpoints and face
      // centroids (on knot planes) and random points. Barycentric coordinates from faces taken
      // relative to one of their knots gave this; g·(x - a) with λ_0 = 1 - λ_1 - λ_2 - λ_3 lost
      // digits: 9e-12 at knots, 3.2e-12 on knot planes.
      const double tolerance = 1e-12;
      double sum = 0;
      bool negative = false;
      evaluator.for_each_basis_function(x, [&](int, double value) {
        sum += value;
        // The basis is nonnegative; rounding reaches about 1e-12 on ∂Ω, where four or more knots
        // are coplanar.
        negative = negative || value < -1e-11;
      });
      ASSERT_NEAR(sum, 1.0, tolerance) << "degree " << degree << " at " << x.transpose();
      ASSERT_FALSE(negative);
    }
  }
}

TEST(DmsSplineVolume, ReproducesEveryPolynomialOfDegreeAtMostNFromItsBlossom) {
  std::mt19937 rng(5);
  for (int degree = 1; degree <= 3; ++degree) {
    for (const DmsControlSharing sharing : {DmsControlSharing::Shared, DmsControlSharing::PerTetrahedron}) {
      DmsSplineVolume v = cube_volume(degree, sharing);
      const ProductPolynomial p = random_polynomial(degree, rng), q = random_polynomial(degree - 1, rng);
      set_column_from_blossom(v, v.attribute_column("density"), [&](std::span<const Eigen::Vector3d> a) { return p.blossom(a); });
      set_column_from_blossom(v, 1, [&](std::span<const Eigen::Vector3d> a) { return q.blossom(a); });
      DmsSplineEvaluator evaluator(v);
      for (const Eigen::Vector3d& x : test_points(v, rng)) {
        const DmsSplinePoint s = evaluator.evaluate(x);
        ASSERT_TRUE(s.inside);
        // At points in general position the error is below 1e-12; at the domain's vertices (knots of
        // every cloud around them, and four or more coplanar knots on the cube's faces) it
        // reaches 4e-11 for the identity.
        EXPECT_NEAR(s.value[0], x.x(), 1e-10);  // the identity geometry, from the blossom of x
        EXPECT_NEAR(s.value[2], x.z(), 1e-10);
        EXPECT_NEAR(s.value[1], q(x), 1e-10) << "degree " << degree;
        EXPECT_NEAR(s.value[3], p(x), 1e-10) << "degree " << degree;
      }
    }
  }
}

TEST(DmsSplineVolume, GradientMatchesCentralDifferences) {
  std::mt19937 rng(3);
  for (int degree = 1; degree <= 3; ++degree) {
    DmsSplineVolume v = cube_volume(degree);
    std::uniform_real_distribution<double> u(-1, 1);
    for (Eigen::Index r = 0; r < v.control_vectors().rows(); ++r) v.control_vectors()(r, 3) = u(rng);  // a generic attribute
    DmsSplineEvaluator evaluator(v);
    std::uniform_real_distribution<double> inside(0.1, 0.9);
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector3d x(inside(rng), inside(rng), inside(rng));
      const DmsSplinePoint s = evaluator.evaluate(x, 1);
      for (int d = 0; d < 3; ++d) {
        const double h = 1e-6;
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(d) * h;
        const double fd = (evaluator.evaluate(x + e).value[3] - evaluator.evaluate(x - e).value[3]) / (2 * h);
        EXPECT_NEAR(s.gradient(3, d), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "degree " << degree;
        EXPECT_NEAR(s.gradient(d, d), 1.0, 1e-11);
      }
    }
  }
}

TEST(DmsSplineVolume, SharedControlVectorsAreOnePerDomainPoint) {
  const DmsSplineVolume shared = cube_volume(2, DmsControlSharing::Shared);
  const DmsSplineVolume separate = cube_volume(2, DmsControlSharing::PerTetrahedron);
  // Degree 2: the domain points are the vertices and the edge midpoints of Ω.
  std::set<std::pair<int, int>> edges;
  for (const auto& t : shared.domain().tetrahedra)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.insert(std::minmax(t[static_cast<std::size_t>(a)], t[static_cast<std::size_t>(b)]));
  EXPECT_EQ(shared.control_vector_count(), static_cast<int>(shared.domain().points.size() + edges.size()));
  EXPECT_EQ(separate.control_vector_count(), static_cast<int>(10 * separate.domain().tetrahedra.size()));
  DmsSplineEvaluator a(shared), b(separate);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    EXPECT_LT((a.evaluate(x).value - b.evaluate(x).value).norm(), 1e-13);
  }
  for (int row = 0; row < shared.control_vector_count(); ++row) {
    const auto& uses = shared.control_row_uses()[static_cast<std::size_t>(row)];
    for (const auto& [t, beta] : uses) EXPECT_EQ(shared.control_row(t, beta), row);
  }
}

// The evaluator takes shared volumes through the DMS step from degree n − 1 (§3.2:
// s = Σ_{|γ| = n−1} N_γ Σ_m λ_m(x | W_γ) c_{γ+e^m}); the same spline with its control vectors
// copied per tetrahedron goes through all degree-n basis functions. Both must agree everywhere
// on the closed domain, knot planes and knots included, values and gradients. And the step
// never reads the last knots t_{v,n}: moving them (validly) leaves a shared spline unchanged.
TEST(DmsSplineVolume, SharedVolumesByTheDegreeLoweringStepEqualTheFullBasis) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int degree = 1; degree <= 3; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    DmsSplineVolume shared = cube_volume(degree, DmsControlSharing::Shared);
    for (Eigen::Index r = 0; r < shared.control_vectors().rows(); ++r) shared.control_vectors()(r, 3) = u(rng);
    DmsSplineVolume separate = cube_volume(degree, DmsControlSharing::PerTetrahedron);
    const int tetrahedra = static_cast<int>(shared.domain().tetrahedra.size());
    for (int t = 0; t < tetrahedra; ++t)
      for (int b = 0; b < shared.basis_per_tetrahedron(); ++b)
        separate.control_vectors().row(separate.control_row(t, b)) = shared.control_vectors().row(shared.control_row(t, b));
    DmsSplineEvaluator lowered(shared), full(separate);
    double largest_value = 0, largest_gradient = 0;
    for (const Eigen::Vector3d& x : test_points(shared, rng)) {
      const DmsSplinePoint a = lowered.evaluate(x, 1), b = full.evaluate(x, 1);
      ASSERT_EQ(a.tetrahedron, b.tetrahedron);
      largest_value = std::max(largest_value, (a.value - b.value).cwiseAbs().maxCoeff());
      const double scale = std::max(1.0, b.gradient.cwiseAbs().maxCoeff());
      largest_gradient = std::max(largest_gradient, (a.gradient - b.gradient).cwiseAbs().maxCoeff() / scale);
    }
    // Measured on these and on 2,000 random points: values within 2.3e-13, gradients within
    // 2.9e-9 of the largest gradient (degree 2, next to a cloud's small sub-tetrahedra, whose ∇λ
    // are large: both computations round there).
    EXPECT_LT(largest_value, 1e-12);
    EXPECT_LT(largest_gradient, 2e-8);

    // The last knot of every cloud moved halfway towards its vertex: still valid clouds (the
    // sub-knots stay where generate_knot_clouds may put them), the same shared spline.
    KnotClouds moved = shared.knots();
    for (int vertex = 0; vertex < static_cast<int>(shared.domain().points.size()); ++vertex) {
      Eigen::Vector3d* cloud = &moved.knots[static_cast<std::size_t>(vertex * (degree + 1))];
      cloud[degree] = 0.5 * (cloud[degree] + cloud[0]);
    }
    ASSERT_NO_THROW(validate_knot_clouds(shared.domain(), moved));
    DmsSplineVolume moved_volume(shared.domain(), moved, DmsControlSharing::Shared, {"density"});
    moved_volume.control_vectors() = shared.control_vectors();
    DmsSplineEvaluator moved_evaluator(moved_volume);
    std::uniform_real_distribution<double> inside(0, 1);
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d x(inside(rng), inside(rng), inside(rng));
      EXPECT_EQ(moved_evaluator.evaluate(x, 1).value, lowered.evaluate(x, 1).value);
    }
  }
}

// The batch evaluation reorders the points by index cell, nothing else: the same results bit for
// bit, in the order given, for points inside, on the boundary and outside, shared and not.
TEST(DmsSplineVolume, BatchEvaluationEqualsPointByPoint) {
  std::mt19937 rng(23);
  for (const DmsControlSharing sharing : {DmsControlSharing::Shared, DmsControlSharing::PerTetrahedron}) {
    DmsSplineVolume v = cube_volume(2, sharing);
    std::uniform_real_distribution<double> u(-1, 1);
    for (Eigen::Index r = 0; r < v.control_vectors().rows(); ++r) v.control_vectors()(r, 3) = u(rng);
    std::vector<Eigen::Vector3d> points = test_points(v, rng);
    std::uniform_real_distribution<double> around(-0.2, 1.2);
    for (int i = 0; i < 100; ++i) points.emplace_back(around(rng), around(rng), around(rng));
    std::shuffle(points.begin(), points.end(), rng);
    DmsSplineEvaluator batch(v), single(v);
    std::vector<DmsSplinePoint> out;
    batch.evaluate(points, 1, out);
    ASSERT_EQ(out.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const DmsSplinePoint expected = single.evaluate(points[i], 1);
      EXPECT_EQ(out[i].tetrahedron, expected.tetrahedron);
      EXPECT_EQ(out[i].value, expected.value) << points[i].transpose();
      EXPECT_EQ(out[i].gradient, expected.gradient) << points[i].transpose();
    }
  }
}

TEST(DmsSplineVolume, IsZeroOutsideTheDomain) {
  DmsSplineVolume v = cube_volume(2);
  v.control_vectors().col(3).setOnes();
  DmsSplineEvaluator evaluator(v);
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.01, 0.5, 0.5), Eigen::Vector3d(-1e-9, 0.2, 0.3), Eigen::Vector3d(5, 5, 5)}) {
    const DmsSplinePoint s = evaluator.evaluate(x, 1);
    EXPECT_FALSE(s.inside);
    EXPECT_EQ(s.tetrahedron, -1);
    EXPECT_EQ(s.value.norm(), 0.0);
    EXPECT_EQ(s.gradient.norm(), 0.0);
  }
  const DmsSplinePoint corner = evaluator.evaluate(Eigen::Vector3d(1, 1, 1));
  EXPECT_TRUE(corner.inside);
  EXPECT_NEAR(corner.value[3], 1.0, 1e-12);
}

TEST(DmsSplineVolume, RefusesWhatItCannotRepresent) {
  TetrahedralMesh domain = cube_domain();
  KnotClouds zero = generate_knot_clouds(domain, 0);
  EXPECT_THROW(DmsSplineVolume(domain, zero, DmsControlSharing::Shared), InvalidInput);
  KnotClouds two = generate_knot_clouds(domain, 2);
  for (const std::vector<std::string>& names : std::vector<std::vector<std::string>>{{"x"}, {""}, {"a", "a"}}) {
    try {
      DmsSplineVolume(domain, two, DmsControlSharing::Shared, names);
      ADD_FAILURE() << "accepted bad attribute names";
    } catch (const InvalidInput& e) {
      EXPECT_NE(e.where().find("attributes"), std::string::npos) << e.what();
    }
  }
  KnotClouds short_clouds = two;
  short_clouds.knots.pop_back();
  EXPECT_THROW(DmsSplineVolume(domain, short_clouds, DmsControlSharing::Shared), InvalidInput);
  DmsSplineVolume v(domain, two, DmsControlSharing::Shared, {"a"});
  EXPECT_THROW(v.attribute_column("b"), InvalidInput);
  EXPECT_THROW(DmsSplineEvaluator(v).evaluate(Eigen::Vector3d(0.5, 0.5, 0.5), 2), InvalidInput);
}

// A domain of two parts that touch along the plane x = 0.5 without sharing points (its points
// there duplicated, as interface_split makes them): each part is its own spline, so a volume
// with the blossoms of two different linear functions on the two parts takes each exactly on its
// side, right up to the plane (§4.2: the jump is kept).
TEST(DmsSplineVolume, PartsTouchingWithoutSharedPointsAreSeparateSplinesThatJumpAtTheirInterface) {
  TetrahedralMesh domain;
  const TetrahedralMesh half = test_support::jittered_cube_domain(3);
  for (int side = 0; side < 2; ++side) {
    const int offset = static_cast<int>(domain.points.size());
    for (const Eigen::Vector3d& p : half.points) domain.points.emplace_back(0.5 * p.x() + 0.5 * side, p.y(), p.z());
    for (std::array<int, 4> t : half.tetrahedra) {
      for (int& v : t) v += offset;
      domain.tetrahedra.push_back(t);
    }
  }
  for (int degree = 1; degree <= 3; ++degree) {
    KnotClouds clouds = generate_knot_clouds(domain, degree);  // boundary sub-knots outside their own part
    ASSERT_NO_THROW(validate_knot_clouds(domain, clouds));
    DmsSplineVolume volume(domain, clouds, DmsControlSharing::Shared, {"g"});
    const std::vector<int> parts = tetrahedron_parts(volume.domain());
    // g = 1 + y on the part x <= 0.5, 3 − z on the other: the blossom of a linear function is its
    // value at the mean of the arguments.
    for (int row = 0; row < volume.control_vector_count(); ++row) {
      const auto [tet, beta] = volume.control_row_uses()[static_cast<std::size_t>(row)].front();
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      const std::vector<Eigen::Vector3d> arguments = dms_blossom_arguments(volume, tet, beta);
      for (const Eigen::Vector3d& a : arguments) mean += a / static_cast<double>(arguments.size());
      volume.control_vectors()(row, 3) = parts[static_cast<std::size_t>(tet)] == 0 ? 1 + mean.y() : 3 - mean.z();
    }
    DmsSplineEvaluator evaluator(volume);
    for (double d : {0.2, 1e-3, 1e-7}) {
      for (const Eigen::Vector3d& yz : {Eigen::Vector3d(0, 0.3, 0.6), Eigen::Vector3d(0, 0.81, 0.17)}) {
        const DmsSplinePoint left = evaluator.evaluate(Eigen::Vector3d(0.5 - d, yz.y(), yz.z()), 1);
        const DmsSplinePoint right = evaluator.evaluate(Eigen::Vector3d(0.5 + d, yz.y(), yz.z()), 1);
        ASSERT_TRUE(left.inside && right.inside);
        EXPECT_NEAR(left.value[3], 1 + yz.y(), 1e-10) << "degree " << degree << ", d " << d;
        EXPECT_NEAR(right.value[3], 3 - yz.z(), 1e-10) << "degree " << degree << ", d " << d;
        EXPECT_NEAR(left.gradient(3, 1), 1, 1e-8);
        EXPECT_NEAR(right.gradient(3, 2), -1, 1e-8);
        EXPECT_NEAR(left.value[0], 0.5 - d, 1e-12);  // the identity geometry on both parts
        EXPECT_NEAR(right.value[0], 0.5 + d, 1e-12);
      }
    }
  }
}

}  // namespace
}  // namespace volspline
