// Free-form deformation: the undeformed lattice is the identity, batches equal single points bit
// for bit, control points act only on their support, and functional composition is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "support/test_splines.h"
#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/lattice.h"

namespace volspline {
namespace {

// Skew edge directions (Lasser's eq. 10 allows any non-coplanar U, V, W).
Eigen::Matrix3d skew_directions() {
  Eigen::Matrix3d d;
  d.col(0) = Eigen::Vector3d(1.0, 0.2, -0.1);
  d.col(1) = Eigen::Vector3d(0.4, 1.0, 0.3);
  d.col(2) = Eigen::Vector3d(-0.3, 0.5, 2.0);
  return d;
}

std::vector<Eigen::Vector3d> random_points(std::mt19937& rng, int n, double extent) {
  std::uniform_real_distribution<double> x(-extent, extent);
  std::vector<Eigen::Vector3d> p(static_cast<std::size_t>(n));
  for (auto& q : p) q = Eigen::Vector3d(x(rng), x(rng), x(rng)) + Eigen::Vector3d(3, -1, 2);
  return p;
}

// Moves every control point by a random offset of size `amount` relative to the box.
Lattice perturbed(const Lattice& lattice, std::mt19937& rng, double amount, bool rational = false) {
  std::uniform_real_distribution<double> x(-amount, amount), w(0.5, 2.0);
  std::vector<double> points = lattice.volume.points();
  for (auto& c : points) c += x(rng);
  std::vector<double> weights;
  if (rational) {
    weights.resize(static_cast<std::size_t>(lattice.volume.num_control_points_total()));
    for (auto& v : weights) v = w(rng);
  }
  return Lattice{BSplineVolume(lattice.volume.knot_vectors(), 3, points, weights), lattice.origin, lattice.axes};
}

TEST(Ffd, UndeformedLatticeIsTheIdentity) {
  std::mt19937 rng(1);
  const auto points = random_points(rng, 400, 2.0);
  struct Case {
    std::array<int, 3> degree, divisions;
    Eigen::Matrix3d directions;
  };
  const Case cases[] = {
      {{1, 1, 1}, {1, 1, 1}, Eigen::Matrix3d::Identity()},
      {{3, 2, 1}, {1, 1, 1}, skew_directions()},
      {{3, 3, 2}, {4, 3, 2}, skew_directions()},  // segmented: interior knots, Greville points
      {{2, 4, 3}, {5, 1, 7}, Eigen::Matrix3d::Identity()},
  };
  for (const auto& c : cases) {
    const Lattice lattice = undeformed_lattice(points, c.degree, c.divisions, 0.1, c.directions);
    for (const auto& p : points) {
      const Eigen::Vector3d q = deform_point(lattice, p);
      EXPECT_LE((q - p).norm(), 1e-12 * (1 + p.norm()));
    }
    // Points outside the box move by the (zero) displacement of the nearest box point.
    for (const auto& p : random_points(rng, 50, 6.0)) EXPECT_LE((deform_point(lattice, p) - p).norm(), 1e-12 * (1 + p.norm()));
  }
}

TEST(Ffd, LatticeCoordinatesSolveEquation10) {
  std::mt19937 rng(2);
  const auto points = random_points(rng, 100, 1.0);
  const Lattice lattice = undeformed_lattice(points, {2, 2, 2}, {1, 1, 1}, 0.0, skew_directions());
  for (const auto& p : points) {
    const Eigen::Vector3d c = lattice_coordinates(lattice, p);
    EXPECT_LE((lattice_box_point(lattice, c) - p).norm(), 1e-13 * (1 + p.norm()));
    EXPECT_GE(c.minCoeff(), -1e-14);
    EXPECT_LE(c.maxCoeff(), 1 + 1e-14);
  }
  // margin 0: the box touches the extreme points in every direction.
  for (int d = 0; d < 3; ++d) {
    double lo = 1, hi = 0;
    for (const auto& p : points) {
      lo = std::min(lo, lattice_coordinates(lattice, p)[d]);
      hi = std::max(hi, lattice_coordinates(lattice, p)[d]);
    }
    EXPECT_NEAR(lo, 0, 1e-14);
    EXPECT_NEAR(hi, 1, 1e-14);
  }
}

TEST(Ffd, DeformMeshEqualsPointwiseDeformation) {
  std::mt19937 rng(3);
  const TriangleMesh sphere = test_support::icosphere(3);
  const Lattice lattice = perturbed(undeformed_lattice(sphere, {3, 2, 3}, {2, 3, 1}, 0.05, skew_directions()), rng, 0.2, true);
  // Some vertices outside the lattice box too.
  TriangleMesh mesh = sphere;
  for (std::size_t i = 0; i < mesh.positions.size(); i += 7) mesh.positions[i] *= 1.5;
  const TriangleMesh deformed = deform_mesh(lattice, mesh);
  ASSERT_EQ(deformed.positions.size(), mesh.positions.size());
  EXPECT_EQ(deformed.triangles, mesh.triangles);
  EXPECT_EQ(deformed.parts, mesh.parts);
  EXPECT_EQ(deformed.parameters, mesh.parameters);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Eigen::Vector3d expected = deform_point(lattice, mesh.positions[i]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(deformed.positions[i][c], expected[c]) << i;
    moved += (deformed.positions[i] - mesh.positions[i]).norm() > 1e-3;
  }
  EXPECT_GT(moved, mesh.positions.size() / 2);
}

TEST(Ffd, MovingOneControlPointMovesOnlyItsSupport) {
  std::mt19937 rng(4);
  const auto points = random_points(rng, 3000, 1.0);
  const Lattice lattice = undeformed_lattice(points, {2, 3, 2}, {3, 2, 4}, 0.05, skew_directions());
  const std::array<int, 3> moved_index{2, 1, 3};
  std::vector<double> control = lattice.volume.points();
  const auto index = static_cast<std::size_t>(lattice.volume.linear_index(moved_index));
  control[3 * index] += 0.3;
  control[3 * index + 2] -= 0.2;
  const Lattice changed{BSplineVolume(lattice.volume.knot_vectors(), 3, control), lattice.origin, lattice.axes};
  const auto before = deform_points(lattice, points);
  const auto after = deform_points(changed, points);
  std::size_t inside = 0, outside = 0;
  for (std::size_t n = 0; n < points.size(); ++n) {
    const Eigen::Vector3d c = lattice_coordinates(lattice, points[n]);
    bool in_support = true;
    for (int d = 0; d < 3; ++d) {
      const auto& t = lattice.volume.knot_vector(d).knots();
      const int i = moved_index[static_cast<std::size_t>(d)], p = lattice.volume.knot_vector(d).degree();
      in_support = in_support && c[d] > t[static_cast<std::size_t>(i)] && c[d] < t[static_cast<std::size_t>(i + p + 1)];
    }
    if (in_support) {
      ++inside;
      EXPECT_GT((after[n] - before[n]).norm(), 0.0) << n;
    } else {
      ++outside;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(after[n][k], before[n][k]) << n;  // bit-identical
    }
  }
  EXPECT_GT(inside, 100u);
  EXPECT_GT(outside, 100u);
}

// Points along the object, composed vs. deformed pointwise.
template <int D>
void expect_exact_composition(const Lattice& lattice, const TensorSpline<D>& object, std::mt19937& rng) {
  const TensorSpline<D> composed = compose(lattice, object);
  const auto d = object.degrees();
  const auto p = lattice.volume.degrees();
  for (int m = 0; m < D; ++m) EXPECT_EQ(composed.degrees()[m], (p[0] + p[1] + p[2]) * d[m]);
  EXPECT_EQ(composed.is_rational(), object.is_rational() || lattice.volume.is_rational());
  const double scale = test_support::coefficient_scale(lattice.volume);
  for (int n = 0; n < 200; ++n) {
    const auto t = test_support::random_parameter(rng, object);
    const Eigen::VectorXd x = object.evaluate(t);
    const Eigen::Vector3d expected = deform_point(lattice, Eigen::Vector3d(x[0], x[1], x[2]));
    const Eigen::VectorXd got = composed.evaluate(t);
    EXPECT_LE((got - expected).norm(), 1e-12 * scale) << n;
  }
}

std::vector<Eigen::Vector3d> control_points(const std::vector<double>& flat) {
  std::vector<Eigen::Vector3d> p;
  for (std::size_t i = 0; i + 2 < flat.size(); i += 3) p.emplace_back(flat[i], flat[i + 1], flat[i + 2]);
  return p;
}

TEST(Ffd, CompositionOfACurveThroughABezierLatticeIsExact) {
  std::mt19937 rng(5);
  for (const bool rational_curve : {false, true}) {
    for (const bool rational_lattice : {false, true}) {
      const auto curve = test_support::random_spline<1>(rng, {3}, 4, 3, rational_curve);
      const Lattice box = undeformed_lattice(control_points(curve.points()), {2, 3, 2}, {1, 1, 1}, 0.05, skew_directions());
      const Lattice lattice = perturbed(box, rng, 0.5, rational_lattice);
      expect_exact_composition(lattice, curve, rng);
    }
  }
}

TEST(Ffd, CompositionOfASurfaceIsExact) {
  std::mt19937 rng(6);
  for (const bool rational : {false, true}) {
    const auto surface = test_support::random_spline<2>(rng, {2, 1}, 3, 3, rational);
    const Lattice box = undeformed_lattice(control_points(surface.points()), {2, 1, 2}, {1, 1, 1}, 0.1, skew_directions());
    expect_exact_composition(perturbed(box, rng, 0.4, rational), surface, rng);
  }
}

TEST(Ffd, CompositionWithTheUndeformedLatticeReproducesTheCurve) {
  std::mt19937 rng(7);
  const auto curve = test_support::random_spline<1>(rng, {2}, 3, 3, false);
  const Lattice lattice = undeformed_lattice(control_points(curve.points()), {1, 2, 1}, {1, 1, 1}, 0.05);
  const auto composed = compose(lattice, curve);
  for (int n = 0; n < 100; ++n) {
    const auto t = test_support::random_parameter(rng, curve);
    EXPECT_LE((composed.evaluate(t) - curve.evaluate(t)).norm(), 1e-12 * test_support::coefficient_scale(curve));
  }
}

TEST(Ffd, SegmentedLatticeComposesExactlyInsideOneCellAndRefusesCrossings) {
  std::mt19937 rng(8);
  const auto curve = test_support::random_spline<1>(rng, {2}, 2, 3, false);
  const auto pts = control_points(curve.points());
  // A lattice around the curve, then a segmented one twice as large in every direction whose
  // first cell (of 2 x 2 x 2) is the same box: the curve lies in that cell.
  const Lattice tight = undeformed_lattice(pts, {2, 2, 2}, {1, 1, 1}, 0.05);
  std::vector<Eigen::Vector3d> corners{tight.origin, tight.origin + 2 * tight.axes * Eigen::Vector3d::Ones()};
  const Lattice big = perturbed(undeformed_lattice(corners, {2, 2, 2}, {2, 2, 2}, 0.0), rng, 0.3);
  expect_exact_composition(big, curve, rng);

  const Lattice crossing = undeformed_lattice(pts, {2, 2, 2}, {2, 1, 1}, 0.05);
  try {
    compose(crossing, curve);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("crosses the knot planes"), std::string::npos) << e.what();
  }
}

TEST(Ffd, CompositionRejectsObjectsOutsideTheDomainAndHugeDegrees) {
  std::mt19937 rng(9);
  const auto curve = test_support::random_spline<1>(rng, {3}, 2, 3, false);
  std::vector<Eigen::Vector3d> half{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.5, 0.5)};
  EXPECT_THROW(compose(undeformed_lattice(half, {1, 1, 1}, {1, 1, 1}, 0.0), curve), InvalidInput);
  const auto big = test_support::random_spline<1>(rng, {9}, 1, 3, false);
  EXPECT_THROW(compose(undeformed_lattice(control_points(big.points()), {3, 3, 3}), big), InvalidInput);  // 81 > 64
  const auto planar = test_support::random_spline<1>(rng, {2}, 1, 2, false);
  EXPECT_THROW(compose(undeformed_lattice(half, {1, 1, 1}), planar), InvalidInput);
}

TEST(Ffd, NonFinitePointsAreBadInput) {
  const Lattice lattice = undeformed_lattice(test_support::unit_cube(), {1, 1, 1});
  EXPECT_THROW(deform_point(lattice, Eigen::Vector3d(NAN, 0, 0)), InvalidInput);
  EXPECT_THROW(deform_points(lattice, {Eigen::Vector3d(0, INFINITY, 0)}), InvalidInput);
}

// Far from the origin (issue 16): a lattice and the points it deforms, both offset by 1e6, 1e12
// or 1e15, move as the same lattice and points at 0 do. The lattice at 0 is the offset one moved
// back, exactly (Sterbenz: x + o and o are within a factor 2), so the two are the same
// deformation; the volume is evaluated relative to its local origin (TensorSpline::local_origin)
// and the frame of eq. 10 works on X - P0, so the results differ by the rounding of positions
// near the offset only, a few ulp of it. Points outside the box exercise the displacement rule.
TEST(Ffd, FarFromTheOriginDeformsAsAtTheOrigin) {
  std::mt19937 rng(16);
  auto points = random_points(rng, 400, 1.0);
  for (int k = 0; k < 40; ++k) points.push_back(points[static_cast<std::size_t>(k)] + Eigen::Vector3d(2.5, -3.0, 1.5) * (k % 2 ? 1 : -1));
  const Lattice base = undeformed_lattice(std::vector<Eigen::Vector3d>(points.begin(), points.begin() + 400), {2, 3, 2}, {3, 2, 4}, 0.05,
                                          skew_directions());
  for (const bool rational : {false, true}) {
    const Lattice bent = perturbed(base, rng, 0.2, rational);
    for (const double offset : {1e6, 1e12, 1e15}) {
      for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, -1, 1), Eigen::Vector3d(0, 0, -1)}) {
        const Eigen::Vector3d o = offset * direction;
        std::vector<double> far_control = bent.volume.points(), near_control(far_control.size());
        for (std::size_t i = 0; i < far_control.size(); ++i) {
          far_control[i] += o[static_cast<int>(i % 3)];
          near_control[i] = far_control[i] - o[static_cast<int>(i % 3)];
        }
        const Lattice far{BSplineVolume(bent.volume.knot_vectors(), 3, far_control, bent.volume.weights()), bent.origin + o, bent.axes};
        const Lattice near{BSplineVolume(bent.volume.knot_vectors(), 3, near_control, bent.volume.weights()), far.origin - o, bent.axes};
        std::vector<Eigen::Vector3d> far_points(points.size()), near_points(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) {
          far_points[i] = points[i] + o;
          near_points[i] = far_points[i] - o;
        }
        const auto far_moved = deform_points(far, far_points);
        const auto near_moved = deform_points(near, near_points);
        // Measured: half an ulp of the offset (the rounding of the result); allowed: one to two ulp.
        const double tolerance = offset * std::numeric_limits<double>::epsilon() + 1e-12;
        double worst = 0;
        for (std::size_t i = 0; i < points.size(); ++i) worst = std::max(worst, (far_moved[i] - o - near_moved[i]).cwiseAbs().maxCoeff());
        EXPECT_LE(worst, tolerance) << "offset " << offset << " direction " << direction.transpose() << " rational " << rational;
        // The deformation is not the identity there (the test would be empty otherwise).
        EXPECT_GT((near_moved[3] - near_points[3]).norm(), 1e-3);
      }
    }
  }
}

}  // namespace
}  // namespace volspline
