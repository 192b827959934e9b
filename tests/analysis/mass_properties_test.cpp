// Mass properties: exactness for polynomial volumes (affine cubes, boxes, the divergence
// theorem as an independent computation), exact rational solids against their analytic volumes,
// centroids and inertia tensors, orientation, folds and the error estimate.
#include "volspline/analysis/mass_properties.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <string>
#include <numbers>
#include <random>
#include <vector>

#include "support/test_splines.h"
#include "volspline/construct/example_solids.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/iso_restriction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {
namespace {

constexpr double kPi = std::numbers::pi;

std::string sci(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3e", x);
  return buffer;
}

double relative(double got, double expected) { return std::abs(got - expected) / std::abs(expected); }

double max_relative(const Eigen::MatrixXd& got, const Eigen::MatrixXd& expected) {
  return (got - expected).cwiseAbs().maxCoeff() / std::max(expected.cwiseAbs().maxCoeff(), 1e-300);
}

/// The identity map of [0,1]^3 with the given degrees and spans: control points at the
/// Greville abscissae (the identity is reproduced exactly).
BSplineVolume identity_cube(std::array<int, 3> degrees = {1, 1, 1}, std::array<int, 3> spans = {1, 1, 1}) {
  std::array<KnotVector, 3> kv{KnotVector::uniform_clamped(degrees[0], spans[0]), KnotVector::uniform_clamped(degrees[1], spans[1]),
                               KnotVector::uniform_clamped(degrees[2], spans[2])};
  std::array<std::vector<double>, 3> greville;
  for (std::size_t d = 0; d < 3; ++d) {
    const auto& t = kv[d].knots();
    const int p = kv[d].degree();
    for (int i = 0; i < kv[d].num_basis(); ++i) {
      double s = 0.0;
      for (int k = 1; k <= p; ++k) s += t[static_cast<std::size_t>(i + k)];
      greville[d].push_back(s / p);
    }
  }
  std::vector<double> p;
  for (double z : greville[2])
    for (double y : greville[1])
      for (double x : greville[0]) p.insert(p.end(), {x, y, z});
  return BSplineVolume(kv, 3, std::move(p));
}

Eigen::Matrix3d rotation(double a, double b) {
  return (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b, Eigen::Vector3d(1, 1, 0).normalized())).toRotationMatrix();
}

// ---- The divergence theorem, computed on the six face surfaces only ----------------------
// volume = (1/3) sum over faces of the integral of x . N, first moments
// integral of x_i = sum over faces of the integral of (x_i^2 / 2) N_i, with N = x_s x x_t
// oriented outwards for a right-handed parameterisation (so these give the signed quantities).
struct Flux {
  double volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

Flux flux(const BSplineVolume& v, int points_per_direction, int subdivisions = 1) {
  std::vector<double> x(static_cast<std::size_t>(points_per_direction)), w(x.size());
  gauss_legendre(points_per_direction, x.data(), w.data());
  Flux f;
  for (int dir = 0; dir < 3; ++dir) {
    // restrict_to_iso keeps the other two directions in order: (v,w), (u,w), (u,v); the
    // (u,w) face's x_u x x_w is -(x_w x x_u).
    const double orientation = dir == 1 ? -1.0 : 1.0;
    for (int side = 0; side < 2; ++side) {
      const double value = side == 0 ? v.domain_min(dir) : v.domain_max(dir);
      const BSplineSurface face = restrict_to_iso(v, dir, value);
      const double sign = orientation * (side == 0 ? -1.0 : 1.0);
      const auto b0 = face.knot_vector(0).breakpoints(), b1 = face.knot_vector(1).breakpoints();
      for (std::size_t a = 0; a + 1 < b0.size(); ++a)
        for (std::size_t b = 0; b + 1 < b1.size(); ++b)
          for (int sa = 0; sa < subdivisions; ++sa)
            for (int sb = 0; sb < subdivisions; ++sb) {
              const double h0 = (b0[a + 1] - b0[a]) / subdivisions, h1 = (b1[b + 1] - b1[b]) / subdivisions;
              const double lo0 = b0[a] + sa * h0, lo1 = b1[b] + sb * h1;
              for (std::size_t i = 0; i < x.size(); ++i)
                for (std::size_t j = 0; j < x.size(); ++j) {
                  const double s = lo0 + 0.5 * h0 * (1 + x[i]), t = lo1 + 0.5 * h1 * (1 + x[j]);
                  const auto d = face.evaluate_derivatives({s, t}, 1);
                  const Eigen::Vector3d p(d[0], d[1], d[2]), ps(d[3], d[4], d[5]), pt(d[6], d[7], d[8]);
                  const Eigen::Vector3d N = sign * ps.cross(pt);
                  const double weight = 0.25 * h0 * h1 * w[i] * w[j];
                  f.volume += weight * p.dot(N) / 3.0;
                  f.moment += weight * 0.5 * p.cwiseProduct(p).cwiseProduct(N);
                }
            }
    }
  }
  return f;
}

// ---- Exact rational solids built here (independent of construct/) -------------------------

// The 9-point rational quadratic unit circle in 4 quarter arcs.
struct Circle {
  KnotVector knots{2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}};
  std::vector<std::array<double, 2>> points{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  std::vector<double> weights{1, std::sqrt(0.5), 1, std::sqrt(0.5), 1, std::sqrt(0.5), 1, std::sqrt(0.5), 1};
};

/// Solid cylinder of radius R, height h, axis z from 0 to h: (s, angle, z) -> (s R cos, s R sin, z).
BSplineVolume solid_cylinder(double R, double h) {
  const Circle c;
  std::vector<double> p, w;
  for (int k = 0; k < 2; ++k)
    for (std::size_t j = 0; j < c.points.size(); ++j)
      for (int i = 0; i < 2; ++i) {
        p.insert(p.end(), {i * R * c.points[j][0], i * R * c.points[j][1], k * h});
        w.push_back(c.weights[j]);
      }
  return BSplineVolume({KnotVector::bezier(1), c.knots, KnotVector::bezier(1)}, 3, std::move(p), std::move(w));
}

/// Solid ball of radius R about `center`: s times the sphere obtained by revolving the
/// half-circle profile (two quarter arcs) about z.
BSplineVolume solid_ball(double R, const Eigen::Vector3d& center) {
  const Circle c;
  const std::vector<std::array<double, 2>> profile{{0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}};  // (rho, z)
  const std::vector<double> profile_w{1, std::sqrt(0.5), 1, std::sqrt(0.5), 1};
  const KnotVector profile_knots(2, {0, 0, 0, 0.5, 0.5, 1, 1, 1});
  std::vector<double> p, w;
  for (std::size_t k = 0; k < c.points.size(); ++k)
    for (std::size_t j = 0; j < profile.size(); ++j)
      for (int i = 0; i < 2; ++i) {
        const double rho = i * R * profile[j][0], z = i * R * profile[j][1];
        p.insert(p.end(), {center.x() + rho * c.points[k][0], center.y() + rho * c.points[k][1], center.z() + z});
        w.push_back(profile_w[j] * c.weights[k]);
      }
  return BSplineVolume({KnotVector::bezier(1), profile_knots, c.knots}, 3, std::move(p), std::move(w));
}

/// Solid torus: the disk of radius r about (R, 0) in the (rho, z) plane, revolved about z.
BSplineVolume solid_torus(double R, double r) {
  const Circle c;
  std::vector<double> p, w;
  for (std::size_t k = 0; k < c.points.size(); ++k)
    for (std::size_t j = 0; j < c.points.size(); ++j)
      for (int i = 0; i < 2; ++i) {
        const double rho = R + i * r * c.points[j][0], z = i * r * c.points[j][1];
        p.insert(p.end(), {rho * c.points[k][0], rho * c.points[k][1], z});
        w.push_back(c.weights[j] * c.weights[k]);
      }
  return BSplineVolume({KnotVector::bezier(1), c.knots, c.knots}, 3, std::move(p), std::move(w));
}

// ---- Gauss-Legendre ------------------------------------------------------------------------

TEST(GaussLegendre, IntegratesEveryMonomialUpToDegree2nMinus1) {
  for (int n = 1; n <= 60; ++n) {
    std::vector<double> x(static_cast<std::size_t>(n)), w(x.size());
    gauss_legendre(n, x.data(), w.data());
    for (std::size_t i = 1; i < x.size(); ++i) ASSERT_LT(x[i - 1], x[i]) << n;
    for (int k = 0; k <= std::min(2 * n - 1, 40); ++k) {
      double s = 0.0;
      for (std::size_t i = 0; i < x.size(); ++i) s += w[i] * std::pow(x[i], k);
      const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
      EXPECT_NEAR(s, exact, 4e-15) << "n=" << n << " k=" << k;
    }
  }
}

// ---- Polynomial volumes: exact ----------------------------------------------------------------

TEST(MassProperties, AffineCubeHasVolumeDetAAndCentroidAHalfPlusB) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  double worst = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = u(rng);
    if (std::abs(A.determinant()) < 0.1) continue;
    const Eigen::Vector3d b(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    // degrees and spans vary: the identity is reproduced by every one of them
    const std::array<int, 3> degrees{1 + trial % 3, 1 + (trial / 3) % 3, 1 + trial % 2};
    const std::array<int, 3> spans{1 + trial % 2, 1 + trial % 3, 2};
    const auto v = transform_affine(identity_cube(degrees, spans), A, b);
    const auto m = mass_properties(v);
    const double det = A.determinant();
    EXPECT_LE(relative(m.volume, std::abs(det)), 1e-14) << trial;
    EXPECT_LE(relative(m.signed_volume, det), 1e-14) << trial;
    const Eigen::Vector3d c = A * Eigen::Vector3d::Constant(0.5) + b;
    EXPECT_LE((m.centroid - c).norm() / c.norm(), 1e-14) << trial;
    EXPECT_EQ(m.estimated_relative_error, 0.0);
    EXPECT_TRUE(m.converged);
    EXPECT_EQ(m.folded_cells, 0);
    EXPECT_EQ(m.knot_cells, spans[0] * spans[1] * spans[2]);
    // inertia of the unit cube about its centre is Id/6; under x -> A x the second moment
    // S = |det A| A (Id/12) A^T, I = tr(S) Id - S
    const Eigen::Matrix3d S = std::abs(det) * A * A.transpose() / 12.0;
    const Eigen::Matrix3d I = S.trace() * Eigen::Matrix3d::Identity() - S;
    EXPECT_LE(max_relative(m.inertia, I), 1e-13) << trial;
    worst = std::max({worst, relative(m.volume, std::abs(det)), (m.centroid - c).norm() / c.norm()});
  }
  RecordProperty("worst_relative_error", sci(worst));
}

TEST(MassProperties, LeftHandedCopiesHaveTheSamePositiveVolume) {
  const auto v = bent_tricubic_volume();
  const auto right = mass_properties(v);
  ASSERT_GT(right.signed_volume, 0.0);
  // a mirror image
  const auto mirrored = mass_properties(transform_affine(v, Eigen::Matrix3d(Eigen::Vector3d(-1, 1, 1).asDiagonal()), Eigen::Vector3d::Zero()));
  EXPECT_LE(relative(mirrored.volume, right.volume), 1e-14);
  EXPECT_LE(relative(mirrored.signed_volume, -right.volume), 1e-14);
  EXPECT_NEAR(mirrored.centroid.x(), -right.centroid.x(), 1e-14 * right.centroid.norm());
  // the same solid with u reversed (parameter direction flipped, geometry identical)
  const auto& ku = v.knot_vector(0);
  std::vector<double> reversed_knots;
  for (auto it = ku.knots().rbegin(); it != ku.knots().rend(); ++it) reversed_knots.push_back(ku.domain_max() + ku.domain_min() - *it);
  const auto n = v.num_control_points();
  std::vector<double> p;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = n[0] - 1; i >= 0; --i) {
        const auto* q = &v.points()[static_cast<std::size_t>(3 * v.linear_index({i, j, k}))];
        p.insert(p.end(), q, q + 3);
      }
  const BSplineVolume flipped({KnotVector(ku.degree(), reversed_knots), v.knot_vector(1), v.knot_vector(2)}, 3, p);
  const auto f = mass_properties(flipped);
  EXPECT_LT(f.signed_volume, 0.0);
  EXPECT_LE(relative(f.volume, right.volume), 1e-13);
  EXPECT_LE((f.centroid - right.centroid).norm() / right.centroid.norm(), 1e-13);
  EXPECT_LE(max_relative(f.inertia, right.inertia), 1e-13);
}

TEST(MassProperties, BoxInertiaIsAnalytic) {
  const double a = 3.0, b = 1.5, c = 0.25;
  const Eigen::Vector3d offset(100.0, -20.0, 7.0);  // far from the origin: no cancellation
  const auto box = transform_affine(identity_cube({2, 3, 1}, {2, 1, 3}), Eigen::Matrix3d(Eigen::Vector3d(a, b, c).asDiagonal()), offset);
  const auto m = mass_properties(box);
  const double mass = a * b * c;
  const Eigen::Matrix3d I = Eigen::Vector3d(mass / 12 * (b * b + c * c), mass / 12 * (a * a + c * c), mass / 12 * (a * a + b * b)).asDiagonal();
  EXPECT_LE(relative(m.volume, mass), 1e-14);
  EXPECT_LE((m.centroid - (offset + Eigen::Vector3d(a, b, c) / 2)).norm() / offset.norm(), 1e-15);
  EXPECT_LE(max_relative(m.inertia, I), 1e-13);
  // rotated: I -> R I R^T
  const Eigen::Matrix3d R = rotation(0.7, 1.1);
  const auto rotated = mass_properties(transform_affine(box, R, Eigen::Vector3d::Zero()));
  EXPECT_LE(max_relative(rotated.inertia, R * I * R.transpose()), 1e-12);
}

TEST(MassProperties, TricubicWithFixedBoundaryKeepsTheCubesVolumeAndMatchesTheDivergenceTheorem) {
  std::mt19937 rng(11);
  for (double amplitude : {0.05, 0.15}) {
    const auto cube = identity_cube({3, 3, 3}, {2, 3, 2});
    std::uniform_real_distribution<double> jitter(-amplitude, amplitude);
    std::vector<double> p = cube.points();
    const auto n = cube.num_control_points();
    for (int k = 1; k + 1 < n[2]; ++k)
      for (int j = 1; j + 1 < n[1]; ++j)
        for (int i = 1; i + 1 < n[0]; ++i)
          for (int c = 0; c < 3; ++c) p[static_cast<std::size_t>(3 * cube.linear_index({i, j, k}) + c)] += jitter(rng);
    const BSplineVolume v(cube.knot_vectors(), 3, p);
    const auto m = mass_properties(v);
    ASSERT_EQ(m.folded_cells, 0) << amplitude;
    // the boundary is the unit cube's, so the volume is 1 whatever the interior does
    EXPECT_NEAR(m.volume, 1.0, 1e-13) << amplitude;
    const Flux f = flux(v, 12);
    EXPECT_NEAR(m.volume, f.volume, 1e-12) << amplitude;
    EXPECT_LE((m.centroid * m.volume - f.moment).norm(), 1e-12) << amplitude;
    RecordProperty("volume_minus_1_at_" + sci(amplitude), sci(m.volume - 1.0));
    RecordProperty("volume_vs_flux_at_" + sci(amplitude), sci(m.volume - f.volume));
  }
}

TEST(MassProperties, FreeFormVolumesMatchTheDivergenceTheorem) {
  // Random tricubic (and mixed-degree) volumes with multiple interior knots: the signed
  // volume and first moments are exact even where the volume folds.
  std::mt19937 rng(3);
  for (int trial = 0; trial < 6; ++trial) {
    const std::array<int, 3> degrees{1 + trial % 3, 3, 2 + trial % 2};
    const auto v = test_support::random_spline<3>(rng, degrees, 2, 3, false, trial % 2 == 0);
    MassPropertiesOptions quick;
    quick.max_quadrature_points = 0;  // the exact pass only: signed quantities are exact anyway
    const auto m = mass_properties(v, quick);
    const Flux f = flux(v, 16);
    const double scale = std::abs(f.volume) + 1.0;
    EXPECT_NEAR(m.signed_volume, f.volume, 1e-12 * scale) << trial;
    // the bezier pieces add up to the whole
    double pieces = 0.0;
    for (const auto& piece : bezier_pieces(v)) pieces += mass_properties(piece, quick).signed_volume;
    EXPECT_NEAR(pieces, m.signed_volume, 1e-12 * scale) << trial;
  }
}

TEST(MassProperties, KnotInsertionAndDegreeElevationChangeNothing) {
  const auto v = bent_tricubic_volume();
  const auto m = mass_properties(v);
  for (const auto& w : {insert_knot(v, 0, 0.3, 2), elevate_degree(v, 1, 2)}) {
    const auto n = mass_properties(w);
    EXPECT_LE(relative(n.volume, m.volume), 1e-13);
    EXPECT_LE((n.centroid - m.centroid).norm() / m.centroid.norm(), 1e-13);
    EXPECT_LE(max_relative(n.inertia, m.inertia), 1e-12);
  }
}

// ---- Folded volumes ---------------------------------------------------------------------------

TEST(MassProperties, FoldedVolumeCountsTheOverlapTwiceAndConverges) {
  // x(u) = 4u - 3u^2 (control x: 0, 2, 1) rises to 4/3 at u = 2/3 and comes back to 1:
  // the integral of |J| is 4/3 + 1/3 = 5/3, of J is 1; the moment of x is 8/9 + 7/18 = 23/18.
  std::vector<double> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (double x : {0.0, 2.0, 1.0}) p.insert(p.end(), {x, 1.0 * j, 1.0 * k});
  const BSplineVolume v({KnotVector::bezier(2), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, p);
  const auto m = mass_properties(v);
  EXPECT_EQ(m.folded_cells, 1);
  EXPECT_NEAR(m.signed_volume, 1.0, 1e-14);
  EXPECT_TRUE(m.converged) << m.estimated_relative_error;
  EXPECT_LE(m.estimated_relative_error, 1e-13);
  EXPECT_NEAR(m.volume, 5.0 / 3.0, 1e-12);
  EXPECT_NEAR(m.centroid.x(), 23.0 / 30.0, 1e-12);
  EXPECT_NEAR(m.centroid.y(), 0.5, 1e-13);
  RecordProperty("volume_error", sci(std::abs(m.volume - 5.0 / 3.0)));
  RecordProperty("quadrature_points", std::to_string(m.quadrature_points));

  // with no budget for refinement the estimate says so
  MassPropertiesOptions none;
  none.max_quadrature_points = 0;
  const auto rough = mass_properties(v, none);
  EXPECT_FALSE(rough.converged);
  EXPECT_GT(rough.estimated_relative_error, 1e-13);
  EXPECT_GE(rough.estimated_relative_error * rough.volume * 10, std::abs(rough.volume - 5.0 / 3.0));
}

// ---- Rational volumes -------------------------------------------------------------------------

TEST(MassProperties, ExactRationalSolidsHaveTheirAnalyticVolumes) {
  struct Case {
    const char* name;
    BSplineVolume v;
    double volume;
    Eigen::Vector3d centroid;
    Eigen::Matrix3d inertia;
  };
  const double R = 1.3, h = 2.5, r = 0.4, T = 2.0;
  const Eigen::Vector3d center(1.0, -2.0, 0.5);
  const double mc = kPi * R * R * h, mb = 4.0 / 3.0 * kPi * R * R * R, mt = 2 * kPi * kPi * T * r * r;
  std::vector<Case> cases{
      {"cylinder", solid_cylinder(R, h), mc, {0, 0, h / 2},
       Eigen::Vector3d(mc * (3 * R * R + h * h) / 12, mc * (3 * R * R + h * h) / 12, mc * R * R / 2).asDiagonal()},
      {"ball", solid_ball(R, center), mb, center, Eigen::Matrix3d::Identity() * 0.4 * mb * R * R},
      // torus (major T, minor r): I_zz = m (T^2 + 3/4 r^2), I_xx = m (T^2/2 + 5/8 r^2)
      {"torus", solid_torus(T, r), mt, {0, 0, 0},
       Eigen::Vector3d(mt * (T * T / 2 + 5.0 / 8 * r * r), mt * (T * T / 2 + 5.0 / 8 * r * r), mt * (T * T + 0.75 * r * r)).asDiagonal()},
  };
  for (const auto& c : cases) {
    const auto m = mass_properties(c.v);
    EXPECT_TRUE(m.converged) << c.name << " " << m.estimated_relative_error;
    EXPECT_LE(relative(m.volume, c.volume), 1e-12) << c.name;
    EXPECT_LE((m.centroid - c.centroid).norm() / std::max(1.0, c.centroid.norm()), 1e-12) << c.name;
    EXPECT_LE(max_relative(m.inertia, c.inertia), 1e-12) << c.name;
    EXPECT_EQ(m.folded_cells, 0) << c.name;
    RecordProperty(std::string(c.name) + "_volume_relative_error", sci(relative(m.volume, c.volume)));
    RecordProperty(std::string(c.name) + "_estimate", sci(m.estimated_relative_error));
    RecordProperty(std::string(c.name) + "_inertia_relative_error", sci(max_relative(m.inertia, c.inertia)));
    RecordProperty(std::string(c.name) + "_points", std::to_string(m.quadrature_points));
  }
}

/// Expected mass properties of half_cylinder_shell(ri, ro, h): r in [ri, ro], angle in [0, pi].
struct ShellExpectation {
  double volume;
  Eigen::Vector3d centroid;
  Eigen::Matrix3d inertia;
};
ShellExpectation shell_expectation(double ri, double ro, double h) {
  const double area = kPi / 2 * (ro * ro - ri * ri), m = area * h;
  const double cy = 4 * (ro * ro * ro - ri * ri * ri) / (3 * kPi * (ro * ro - ri * ri));
  // about the origin: int y^2 = int x^2 = h pi (ro^4 - ri^4) / 8, int z^2 = area h^3 / 3
  const double x2 = h * kPi * (std::pow(ro, 4) - std::pow(ri, 4)) / 8, z2 = area * h * h * h / 3;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  I(0, 0) = x2 + z2 - m * (cy * cy + h * h / 4);
  I(1, 1) = x2 + z2 - m * (h * h / 4);
  I(2, 2) = 2 * x2 - m * cy * cy;
  return {m, {0, cy, h / 2}, I};
}

TEST(MassProperties, HalfCylinderShellWithPointsAtInfinity) {
  for (auto [ri, ro, h] : {std::array<double, 3>{1, 2, 1}, {0.0, 1.0, 3.0}, {0.9, 1.0, 0.1}}) {
    const auto e = shell_expectation(ri, ro, h);
    const auto m = mass_properties(half_cylinder_shell(ri, ro, h));
    EXPECT_TRUE(m.converged) << m.estimated_relative_error;
    EXPECT_LE(relative(m.volume, e.volume), 1e-12);
    EXPECT_LE((m.centroid - e.centroid).norm() / e.centroid.norm(), 1e-12);
    EXPECT_LE(max_relative(m.inertia, e.inertia), 1e-12);
    RecordProperty("shell_" + sci(ri) + "_volume_error", sci(relative(m.volume, e.volume)));
    RecordProperty("shell_" + sci(ri) + "_centroid_error", sci((m.centroid - e.centroid).norm() / e.centroid.norm()));
    RecordProperty("shell_" + sci(ri) + "_estimate", sci(m.estimated_relative_error));
  }
}

TEST(MassProperties, RationalWithConstantWeightsEqualsPolynomial) {
  std::mt19937 rng(5);
  const auto poly = test_support::random_spline<3>(rng, {2, 3, 2}, 2, 3, false);
  std::vector<double> w(static_cast<std::size_t>(poly.num_control_points_total()), 2.0);
  const BSplineVolume rational(poly.knot_vectors(), 3, poly.points(), w);
  MassPropertiesOptions quick;
  quick.max_quadrature_points = 0;
  const auto a = mass_properties(poly, quick), b = mass_properties(rational, quick);
  EXPECT_NEAR(a.signed_volume, b.signed_volume, 1e-13 * std::abs(a.signed_volume) + 1e-14);
}

TEST(MassProperties, RandomRationalVolumeMatchesTheDivergenceTheorem) {
  std::mt19937 rng(9);
  // near the identity so it does not fold: the identity cube with perturbed points and weights
  const auto cube = identity_cube({2, 2, 2}, {2, 1, 2});
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), weight(0.6, 1.6);
  std::vector<double> p = cube.points(), w(static_cast<std::size_t>(cube.num_control_points_total()));
  for (auto& x : p) x += jitter(rng);
  for (auto& x : w) x = weight(rng);
  const BSplineVolume v(cube.knot_vectors(), 3, p, w);
  const auto m = mass_properties(v);
  EXPECT_TRUE(m.converged) << m.estimated_relative_error;
  EXPECT_EQ(m.folded_cells, 0);
  const Flux f = flux(v, 30, 4);  // far more points than the integrand needs to settle
  EXPECT_LE(relative(m.volume, f.volume), 1e-12);
  EXPECT_LE((m.centroid * m.volume - f.moment).norm() / f.moment.norm(), 1e-12);
  RecordProperty("volume_vs_flux", sci(relative(m.volume, f.volume)));
  RecordProperty("estimate", sci(m.estimated_relative_error));
}

// ---- Edge cases -------------------------------------------------------------------------------

TEST(MassProperties, FlatVolumeHasZeroVolumeAndNoCentroid) {
  std::vector<double> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) p.insert(p.end(), {1.0 * i, 1.0 * j, 0.0});
  const BSplineVolume flat({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, p);
  const auto m = mass_properties(flat);
  EXPECT_EQ(m.volume, 0.0);
  EXPECT_TRUE(std::isnan(m.centroid.x()));
}

TEST(MassProperties, OnlyVolumesInR3) {
  std::vector<double> p(8 * 2, 0.0);
  const BSplineVolume planar({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 2, p);
  EXPECT_THROW(mass_properties(planar), InvalidInput);
}

TEST(MassProperties, SerialAndParallelAgreeBitForBit) {
  const auto v = transform_affine(identity_cube({3, 2, 3}, {4, 3, 5}), rotation(0.3, 0.2), Eigen::Vector3d(1, 2, 3));
  MassPropertiesOptions serial;
  serial.parallel = false;
  const auto a = mass_properties(v), b = mass_properties(v, serial);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.centroid, b.centroid);
  EXPECT_EQ(a.inertia, b.inertia);
  EXPECT_EQ(a.quadrature_points, b.quadrature_points);
}

}  // namespace
}  // namespace volspline
