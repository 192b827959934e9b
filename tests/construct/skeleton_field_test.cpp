#include "volspline/construct/skeleton_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "support/test_splines.h"
#include "volspline/construct/conic_arc.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using Kind = SkeletonElement::Kind;

SkeletonElement point_element(const Eigen::Vector3d& p) {
  SkeletonElement e;
  e.kind = Kind::Point;
  e.points = {p};
  return e;
}

SkeletonElement polyline_element(std::vector<Eigen::Vector3d> points) {
  SkeletonElement e;
  e.kind = points.size() == 2 ? Kind::Segment : Kind::Polyline;
  e.points = std::move(points);
  return e;
}

SkeletonElement curve_element(const BSplineCurve& curve) {
  SkeletonElement e;
  e.kind = Kind::Curve;
  e.curve = curve;
  return e;
}

SkeletonElement ellipsoid_element(const Eigen::Vector3d& centre, const Eigen::Vector3d& semi_axes, const Eigen::Matrix3d& rotation) {
  SkeletonElement e;
  e.kind = Kind::Ellipsoid;
  e.centre = centre;
  e.semi_axes = semi_axes;
  e.rotation = rotation;
  return e;
}

Eigen::Vector3d random_point(std::mt19937& rng, double range) {
  std::uniform_real_distribution<double> u(-range, range);
  return {u(rng), u(rng), u(rng)};
}

Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// The invalid element's message names its JSON path below "elements[i]".
void expect_invalid_at(std::vector<SkeletonElement> elements, const std::string& where) {
  try {
    SkeletonField field(std::move(elements));
    ADD_FAILURE() << "no error, expected one at " << where;
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), where) << e.what();
  }
}

TEST(SkeletonDistance, PointIsTheEuclideanDistance) {
  const SkeletonElement e = point_element({1, 2, 3});
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {1, 2, 3}), 0.0);
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {4, 6, 3}), 5.0);
}

TEST(SkeletonDistance, SegmentWithTheFootInsideAndOutside) {
  const SkeletonElement e = polyline_element({{0, 0, 0}, {4, 0, 0}});
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {1.5, 3, 4}), 5.0);   // foot (1.5, 0, 0) inside
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {7, 4, 0}), 5.0);     // beyond the end (4, 0, 0)
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {-3, 0, -4}), 5.0);   // before the start
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {2, 0, 0}), 0.0);
  // A segment of length 0 is its point.
  EXPECT_DOUBLE_EQ(skeleton_distance(polyline_element({{1, 1, 1}, {1, 1, 1}}), {1, 1, 3}), 2.0);
}

TEST(SkeletonDistance, PolylineCornerIsTheVertexDistance) {
  const SkeletonElement e = polyline_element({{-2, 0, 0}, {0, 0, 0}, {0, 2, 0}, {3, 2, 0}});
  // Outside the corner at the origin both segments' feet are the vertex itself.
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {1, -1, 0}), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {0.5, -0.5, 1}), std::sqrt(1.5));
  // Inside the corner the nearest segment wins.
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {-1, 0.25, 0}), 0.25);
  EXPECT_DOUBLE_EQ(skeleton_distance(e, {1, 1.5, 0}), 0.5);
}

// The circle of radius r about c in the plane spanned by the columns u, v of `frame`: the
// standard 9-point quadratic NURBS (weights 1, √2/2), an exact rational curve.
BSplineCurve nurbs_circle(const Eigen::Vector3d& c, double r, const Eigen::Matrix3d& frame) {
  const double h = std::sqrt(0.5);
  const double square[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  std::vector<double> points, weights;
  for (int i = 0; i < 9; ++i) {
    const Eigen::Vector3d p = c + r * (square[i][0] * frame.col(0) + square[i][1] * frame.col(1));
    points.insert(points.end(), {p[0], p[1], p[2]});
    weights.push_back(i % 2 == 0 ? 1.0 : h);
  }
  return BSplineCurve({KnotVector(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1})}, 3, std::move(points), std::move(weights));
}

TEST(SkeletonDistance, RationalCircleIsExact) {
  std::mt19937 rng(13);
  const Eigen::Matrix3d frame = random_rotation(rng);
  const Eigen::Vector3d c(0.3, -0.7, 1.1);
  const double r = 1.7;
  const SkeletonField field({curve_element(nurbs_circle(c, r, frame))});
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int i = 0; i < 200; ++i) {
    // In the plane the distance is | |x - c| - r |; off it, sqrt((ρ - r)² + h²) with ρ the distance
    // from the axis and h the height above the plane.
    const Eigen::Vector2d planar(u(rng), u(rng));
    const double height = i % 2 == 0 ? 0.0 : u(rng);
    const Eigen::Vector3d x = c + planar[0] * frame.col(0) + planar[1] * frame.col(1) + height * frame.col(2);
    const double expected = std::hypot(planar.norm() - r, height);
    if (height == 0.0) {
      EXPECT_NEAR(expected, std::abs((x - c).norm() - r), 1e-14);
    }
    EXPECT_NEAR(field.distance(0, x), expected, 1e-12 * std::max(1.0, expected)) << i;
  }
  // On the axis every point of the circle is nearest: (c - x)·c' vanishes identically.
  for (const double height : {0.0, 0.5, -3.0}) {
    EXPECT_NEAR(field.distance(0, c + height * frame.col(2)), std::hypot(r, height), 1e-12);
  }
}

TEST(SkeletonDistance, HalfCircleWithAPointAtInfinity) {
  // Lasser's arc of 180 degrees: the middle control point has weight 0 (a direction).
  const BSplineCurve arc = conic_arc({2, 0, 0}, 180.0, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  ASSERT_TRUE(arc.is_rational());
  const SkeletonElement e = curve_element(arc);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    // The arc is y >= 0 of the circle of radius 2: the circle's distance where x's angle lies
    // in [0, π], else the nearer end (2, 0, 0) or (-2, 0, 0).
    const double rho = std::hypot(x[0], x[1]);
    const double expected = x[1] >= 0 ? std::hypot(rho - 2.0, x[2])
                                      : std::min((x - Eigen::Vector3d(2, 0, 0)).norm(), (x - Eigen::Vector3d(-2, 0, 0)).norm());
    EXPECT_NEAR(skeleton_distance(e, x), expected, 1e-12 * std::max(1.0, expected)) << i;
  }
}

// Independent reference: the best of dense samples, then golden-section minimisation of
// |c(t) - x|² between the neighbouring samples (the robust half of Brent's minimiser).
double sampled_distance(const BSplineCurve& curve, const Eigen::Vector3d& x) {
  const double a = curve.domain_min(0), b = curve.domain_max(0);
  const int n = 2000;
  auto squared = [&](double t) { return (curve.evaluate({t}) - x).squaredNorm(); };
  int best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    const double value = squared(a + (b - a) * i / n);
    if (value < best_value) {
      best_value = value;
      best = i;
    }
  }
  double lo = a + (b - a) * std::max(0, best - 1) / n, hi = a + (b - a) * std::min(n, best + 1) / n;
  const double g = (std::sqrt(5.0) - 1) / 2;
  double t1 = hi - g * (hi - lo), t2 = lo + g * (hi - lo), f1 = squared(t1), f2 = squared(t2);
  for (int i = 0; i < 80; ++i) {
    if (f1 < f2) {
      hi = t2;
      t2 = t1;
      f2 = f1;
      t1 = hi - g * (hi - lo);
      f1 = squared(t1);
    } else {
      lo = t1;
      t1 = t2;
      f1 = f2;
      t2 = lo + g * (hi - lo);
      f2 = squared(t2);
    }
  }
  return std::sqrt(std::min({best_value, f1, f2, squared(a), squared(b)}));
}

TEST(SkeletonDistance, CubicAndRationalCurvesMatchSamplingAndMinimisation) {
  std::mt19937 rng(42);
  for (const bool rational : {false, true}) {
    for (const bool clamped : {true, false}) {
      const BSplineCurve curve = test_support::random_spline<1>(rng, {3}, 5, 3, rational, clamped, 3);
      const SkeletonField field({curve_element(curve)});
      for (int i = 0; i < 25; ++i) {
        const Eigen::Vector3d x = random_point(rng, 3.0);
        const double reference = sampled_distance(curve, x);
        EXPECT_NEAR(field.distance(0, x), reference, 1e-12 * std::max(1.0, reference)) << rational << clamped << i;
      }
      // Points on the curve, at and between knots, are at distance 0.
      for (const double t : curve.knot_vector(0).breakpoints()) EXPECT_NEAR(field.distance(0, curve.evaluate({t})), 0.0, 1e-13);
      const double mid = 0.5 * (curve.domain_min(0) + curve.domain_max(0)) + 0.0123;
      EXPECT_NEAR(field.distance(0, curve.evaluate({mid})), 0.0, 1e-13);
      // Off the curve by δ along a normal, c(t) stays nearest (δ is far below the radius of
      // curvature); beyond an end along the tangent, the end is nearest.
      std::uniform_real_distribution<double> parameter(curve.domain_min(0), curve.domain_max(0));
      for (int i = 0; i < 10; ++i) {
        const std::vector<double> d = curve.evaluate_derivatives({parameter(rng)}, 1);
        const Eigen::Vector3d p(d[0], d[1], d[2]), tangent = Eigen::Vector3d(d[3], d[4], d[5]).normalized();
        const Eigen::Vector3d normal = tangent.cross(random_point(rng, 1.0)).normalized();
        for (const double delta : {1e-9, 1e-5}) EXPECT_NEAR(field.distance(0, p + delta * normal), delta, 1e-14) << i;
      }
      for (const auto& [t, outward] : {std::pair{curve.domain_min(0), -1.0}, std::pair{curve.domain_max(0), 1.0}}) {
        const std::vector<double> d = curve.evaluate_derivatives({t}, 1);
        const Eigen::Vector3d p(d[0], d[1], d[2]), tangent = Eigen::Vector3d(d[3], d[4], d[5]).normalized();
        EXPECT_NEAR(field.distance(0, p + 1e-4 * outward * tangent), 1e-4, 1e-14);
      }
    }
  }
}

TEST(SkeletonDistance, RationalCurveWithAPointAtInfinity) {
  std::mt19937 rng(7);
  const BSplineCurve curve = test_support::random_spline<1>(rng, {3}, 4, 3, true, true, 2, true);
  const SkeletonElement e = curve_element(curve);
  for (int i = 0; i < 15; ++i) {
    const Eigen::Vector3d x = random_point(rng, 3.0);
    const double reference = sampled_distance(curve, x);
    EXPECT_NEAR(skeleton_distance(e, x), reference, 1e-12 * std::max(1.0, reference)) << i;
  }
}

TEST(SkeletonDistance, SphereIsAnalytic) {
  std::mt19937 rng(3);
  const Eigen::Vector3d c(1, -2, 0.5);
  const SkeletonElement e = ellipsoid_element(c, Eigen::Vector3d::Constant(1.5), random_rotation(rng));
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d x = c + random_point(rng, 4.0);
    EXPECT_NEAR(skeleton_distance(e, x), std::max(0.0, (x - c).norm() - 1.5), 1e-14 * (1 + (x - c).norm())) << i;
  }
}

TEST(SkeletonDistance, EllipsoidAxesInsideAndNormals) {
  std::mt19937 rng(11);
  const Eigen::Matrix3d rotation = random_rotation(rng);
  const Eigen::Vector3d c(0.2, 0.1, -0.3), a(3.0, 1.0, 0.4);
  const SkeletonElement e = ellipsoid_element(c, a, rotation);
  auto world = [&](const Eigen::Vector3d& y) -> Eigen::Vector3d { return c + rotation * y; };
  // On a semi-axis line beyond the tip the tip is nearest, for the longest and the shortest alike.
  for (int k = 0; k < 3; ++k) {
    for (const double t : {1e-9, 0.01, 0.7, 25.0}) {
      for (const double side : {1.0, -1.0}) {
        Eigen::Vector3d y = Eigen::Vector3d::Zero();
        y[k] = side * (a[k] + t);
        EXPECT_NEAR(skeleton_distance(e, world(y)), t, 1e-14 * (a[k] + t)) << k << " " << t;
      }
    }
  }
  // Inside (centre, near the surface, on an axis) the distance is 0.
  EXPECT_EQ(skeleton_distance(e, c), 0.0);
  EXPECT_EQ(skeleton_distance(e, world({2.999, 0, 0})), 0.0);
  EXPECT_EQ(skeleton_distance(e, world({0.5, 0.5, 0.2})), 0.0);
  // From a surface point p along the outward normal by δ, p stays nearest (the solid is convex):
  // the distance is δ, including surface points on the principal planes and near the axes.
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  for (int i = 0; i < 60; ++i) {
    double theta = angle(rng), phi = angle(rng) / 2;
    if (i % 6 == 0) phi = 0;                  // the plane of the two longer axes
    if (i % 6 == 1) theta = 0;                // the plane of the longest and the shortest
    if (i % 6 == 2) phi = 1e-7;               // next to a principal plane
    if (i % 6 == 3) phi = std::numbers::pi / 2 - 1e-6;  // next to the shortest axis
    const Eigen::Vector3d y(a[0] * std::cos(theta) * std::cos(phi), a[1] * std::sin(theta) * std::cos(phi), a[2] * std::sin(phi));
    const Eigen::Vector3d normal = y.cwiseQuotient(a.cwiseAbs2()).normalized();
    for (const double delta : {1e-7, 0.05, 2.0, 40.0}) {
      EXPECT_NEAR(skeleton_distance(e, world(y + delta * normal)), delta, 2e-15 * (4 + delta)) << i << " " << delta;
    }
  }
}

// Brute force: the best point of a grid over the surface's angles, then a pattern search.
double brute_force_ellipsoid_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& y) {
  auto squared = [&](double theta, double phi) {
    const Eigen::Vector3d p(a[0] * std::cos(theta) * std::cos(phi), a[1] * std::sin(theta) * std::cos(phi), a[2] * std::sin(phi));
    return (p - y).squaredNorm();
  };
  const double pi = std::numbers::pi;
  double best = std::numeric_limits<double>::infinity(), theta = 0, phi = 0;
  for (int i = 0; i < 180; ++i) {
    for (int j = 0; j <= 90; ++j) {
      const double t = -pi + 2 * pi * i / 180, f = -pi / 2 + pi * j / 90, value = squared(t, f);
      if (value < best) {
        best = value;
        theta = t;
        phi = f;
      }
    }
  }
  for (double step = 2 * pi / 180; step > 1e-14;) {
    bool moved = false;
    for (const auto& [dt, df] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}}) {
      const double value = squared(theta + dt * step, phi + df * step);
      if (value < best) {
        best = value;
        theta += dt * step;
        phi += df * step;
        moved = true;
      }
    }
    if (!moved) step /= 2;
  }
  return std::sqrt(best);
}

TEST(SkeletonDistance, EllipsoidMatchesBruteForceMinimisation) {
  std::mt19937 rng(17);
  const Eigen::Matrix3d rotation = random_rotation(rng);
  const Eigen::Vector3d c(-1, 0.5, 2), a(2.0, 0.5, 1.2);
  const SkeletonElement e = ellipsoid_element(c, a, rotation);
  int outside = 0;
  for (int i = 0; i < 30; ++i) {
    const Eigen::Vector3d y = random_point(rng, 3.5);
    const double d = skeleton_distance(e, c + rotation * y);
    if (y.cwiseQuotient(a).squaredNorm() <= 1.0) {
      EXPECT_EQ(d, 0.0);
      continue;
    }
    ++outside;
    EXPECT_NEAR(d, brute_force_ellipsoid_distance(a, y), 1e-11 * (1 + d)) << i;
  }
  EXPECT_GT(outside, 20);
}

TEST(SkeletonFalloff, InverseSquareAndPolynomialValues) {
  SkeletonFalloff inverse;
  inverse.scale = 0.5;
  EXPECT_DOUBLE_EQ(inverse(0.0), 1.0);
  EXPECT_DOUBLE_EQ(inverse(0.5), 0.5);
  EXPECT_DOUBLE_EQ(inverse(1.0), 0.2);
  EXPECT_DOUBLE_EQ(SkeletonFalloff{}(1.0), 0.5);  // the paper's 1 / (1 + d²)
  // (1 - (d / R)²)² = 1 - 2 d² / R² + d⁴ / R⁴ with R = 2.
  SkeletonFalloff bump;
  bump.kind = SkeletonFalloff::Kind::Polynomial;
  bump.coefficients = {1.0, 0.0, -0.5, 0.0, 0.0625};
  bump.radius = 2.0;
  EXPECT_DOUBLE_EQ(bump(0.0), 1.0);
  EXPECT_DOUBLE_EQ(bump(1.0), 0.5625);
  EXPECT_NEAR(bump(1.999), std::pow(1 - 1.999 * 1.999 / 4, 2), 1e-15);
  EXPECT_EQ(bump(2.0), 0.0);
  EXPECT_EQ(bump(5.0), 0.0);
}

TEST(SkeletonFalloff, PolynomialMustBeNonnegativeUpToTheRadius) {
  auto with_polynomial = [](std::vector<double> coefficients, double radius) {
    SkeletonElement e = point_element({0, 0, 0});
    e.falloff.kind = SkeletonFalloff::Kind::Polynomial;
    e.falloff.coefficients = std::move(coefficients);
    e.falloff.radius = radius;
    return e;
  };
  // Touching 0: (1 - d)², and the bump of the previous test (a double root at the radius).
  EXPECT_NO_THROW(SkeletonField({with_polynomial({1, -2, 1}, 1.0)}));
  EXPECT_NO_THROW(SkeletonField({with_polynomial({1.0, 0.0, -0.5, 0.0, 0.0625}, 2.0)}));
  EXPECT_NO_THROW(SkeletonField({with_polynomial({0.5}, 1.0)}));
  // Negative at the radius, and negative only inside (1 - 3d + 2.2 d², minimum -0.0227 at d = 0.68).
  expect_invalid_at({with_polynomial({1, -3}, 1.0)}, "elements[0].falloff.coefficients");
  expect_invalid_at({with_polynomial({1, -3, 2.2}, 1.0)}, "elements[0].falloff.coefficients");
  // But 1 - 3d + 2.2 d² is fine up to d = 0.5.
  EXPECT_NO_THROW(SkeletonField({with_polynomial({1, -3, 2.2}, 0.5)}));
  expect_invalid_at({with_polynomial({}, 1.0)}, "elements[0].falloff.coefficients");
  expect_invalid_at({with_polynomial({1}, 0.0)}, "elements[0].falloff.radius");
  expect_invalid_at({with_polynomial(std::vector<double>(kMaxFalloffDegree + 2, 1.0), 1.0)}, "elements[0].falloff.coefficients");
}

TEST(SkeletonField, SumsWeightedContributions) {
  SkeletonElement a = point_element({0, 0, 0});
  a.weight = 2.0;
  SkeletonElement b = polyline_element({{3, -1, 0}, {3, 1, 0}});
  b.weight = -0.5;
  b.falloff.scale = 2.0;
  SkeletonElement c = ellipsoid_element({0, 5, 0}, {1, 2, 1}, Eigen::Matrix3d::Identity());
  c.falloff.kind = SkeletonFalloff::Kind::Polynomial;
  c.falloff.coefficients = {1.0, -0.25};
  c.falloff.radius = 4.0;
  const SkeletonField field({a, b, c});
  const Eigen::Vector3d x(0, 0, 0);  // d_a = 0, d_b = 3, d_c = 3 (along the ellipsoid's y axis)
  EXPECT_NEAR(field(x), 2.0 - 0.5 / (1 + 9.0 / 4) + 0.25, 1e-15);
  EXPECT_DOUBLE_EQ(field({0, -10, 0}), 2.0 / 101 - 0.5 / (1 + (9 + 81) / 4.0));  // d_c = 13, beyond the radius
  const Eigen::Vector3d y(0, 2, 0);  // d_a = 2, d_b = √10, d_c = 1
  EXPECT_NEAR(field(y), 2.0 / 5.0 - 0.5 / (1 + 10.0 / 4) + 0.75, 1e-15);
  EXPECT_EQ(SkeletonField({})(x), 0.0);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(field.distance(i, y), skeleton_distance(field.elements()[i], y));
}

TEST(SkeletonField, InvalidElementsAreLocated) {
  const SkeletonElement good = point_element({0, 0, 0});
  SkeletonElement two_points = point_element({0, 0, 0});
  two_points.points.push_back({1, 0, 0});
  expect_invalid_at({good, two_points}, "elements[1].points");
  SkeletonElement one_point_polyline = polyline_element({{0, 0, 0}, {1, 0, 0}});
  one_point_polyline.kind = Kind::Polyline;
  one_point_polyline.points.pop_back();
  expect_invalid_at({one_point_polyline}, "elements[0].points");
  expect_invalid_at({good, good, polyline_element({{0, 0, 0}, {1, 0, std::nan("")}, {2, 0, 0}})}, "elements[2].points[1][2]");
  SkeletonElement no_curve;
  no_curve.kind = Kind::Curve;
  expect_invalid_at({no_curve}, "elements[0].curve");
  std::mt19937 rng(1);
  expect_invalid_at({curve_element(test_support::random_spline<1>(rng, {2}, 3, 2, false))}, "elements[0].curve.control_points");
  expect_invalid_at({ellipsoid_element({0, 0, 0}, {1, 0, 1}, Eigen::Matrix3d::Identity())}, "elements[0].semi_axes[1]");
  expect_invalid_at({ellipsoid_element({0, 0, 0}, {1, 1, 1}, 1.01 * Eigen::Matrix3d::Identity())}, "elements[0].rotation");
  expect_invalid_at({ellipsoid_element({0, 0, 0}, {1, 1, 1}, -Eigen::Matrix3d::Identity())}, "elements[0].rotation");
  expect_invalid_at({ellipsoid_element({0, std::numeric_limits<double>::infinity(), 0}, {1, 1, 1}, Eigen::Matrix3d::Identity())},
                    "elements[0].centre[1]");
  SkeletonElement bad_weight = good;
  bad_weight.weight = std::nan("");
  expect_invalid_at({bad_weight}, "elements[0].weight");
  SkeletonElement bad_scale = good;
  bad_scale.falloff.scale = 0.0;
  expect_invalid_at({good, bad_scale}, "elements[1].falloff.scale");
  EXPECT_THROW(skeleton_distance(two_points, {0, 0, 0}), InvalidInput);
}

}  // namespace
}  // namespace volspline
