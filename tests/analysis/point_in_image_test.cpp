#include "volspline/analysis/point_in_image.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include <tbb/parallel_for.h>

#include "support/swept_solids.h"
#include "support/test_splines.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {
namespace {

using Predicate = std::function<bool(const Eigen::Vector3d&)>;

using test_support::translated_along;

// The unit cube [0, 1]^3 as a degree (2, 2, 2) B-spline with interior knots at 1/3 and 1/2:
// several Bézier pieces, so that queries meet knot planes.
BSplineVolume unit_cube_spline() {
  BSplineVolume cube = box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5));
  for (int d = 0; d < 3; ++d) cube = refine_knots(elevate_degree(cube, d, 1), d, {1.0 / 3, 0.5});
  return cube;
}

// Joy–Duchaineau's folding in one Bézier volume of degree (3, 2, 2): the identity map
// (u, v, w) with its interior control point P_111 pulled by `pull` along +x. Then
// x(u, v, w) = u + 3 k u (1 - u)^2 with k = pull * B_1^2(v) B_1^2(w) = pull * 4 v (1 - v) w (1 - w),
// y = v, z = w. For k > 1, x(u) has a local maximum at
// u* = (2 - sqrt(1 - 1/k)) / 3, so the image is {0 <= x <= M(v, w), 0 <= v, w <= 1} with
// M = max(1, x(u*)): it bulges beyond the face x = 1 where the volume folds (J < 0 between the
// two roots of x'(u)).
BSplineVolume folded_volume(double pull) {
  std::vector<double> points;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        points.push_back(i / 3.0 + (i == 1 && j == 1 && k == 1 ? pull : 0.0));
        points.push_back(j / 2.0);
        points.push_back(k / 2.0);
      }
  return BSplineVolume({KnotVector(3, {0, 0, 0, 0, 1, 1, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1}), KnotVector(2, {0, 0, 0, 1, 1, 1})},
                       3, std::move(points));
}

double folded_bulge(double pull, double v, double w) {
  const double k = pull * (2 * v * (1 - v)) * (2 * w * (1 - w));  // B_1^2(s) = 2 s (1 - s)
  if (k <= 1) return 1;  // x' >= 1 - k > 0: monotone in u
  const double u = (2 - std::sqrt(1 - 1 / k)) / 3;
  return std::max(1.0, u + 3 * k * u * (1 - u) * (1 - u));
}

bool in_folded(double pull, const Eigen::Vector3d& x) {
  return x.y() >= 0 && x.y() <= 1 && x.z() >= 0 && x.z() <= 1 && x.x() >= 0 && x.x() <= folded_bulge(pull, x.y(), x.z());
}

double segment_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (x - (a + t * (b - a))).norm();
}

// x in [0, 1]^3 + [0, 1] offset: some t in [0, 1] has 0 <= x_a - t offset_a <= 1 on every axis.
bool in_translated_unit_box(const Eigen::Vector3d& x, const Eigen::Vector3d& offset) {
  double low = 0, high = 1;
  for (int a = 0; a < 3; ++a) {
    if (offset[a] == 0) {
      if (x[a] < 0 || x[a] > 1) return false;
      continue;
    }
    double t0 = x[a] / offset[a], t1 = (x[a] - 1) / offset[a];
    if (t0 > t1) std::swap(t0, t1);
    low = std::max(low, t0);
    high = std::min(high, t1);
  }
  return low <= high;
}

Eigen::Vector3d random_direction(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
  return d.normalized();
}

// Points at distance about `offset` on both sides of the boundary of a set that is star-shaped
// about `centre`: the crossing of a random ray is found by bisection of the analytic predicate,
// then moved by +- offset along the ray (so by at least offset * cos(angle to the normal)).
struct BoundaryPair {
  Eigen::Vector3d inside, outside;
};
std::vector<BoundaryPair> boundary_pairs(std::mt19937& rng, const Predicate& contains, const Eigen::Vector3d& centre, double reach,
                                         double offset, int count) {
  std::vector<BoundaryPair> pairs;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d d = random_direction(rng);
    double in = 0, out = reach;
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (in + out);
      (contains(centre + mid * d) ? in : out) = mid;
    }
    pairs.push_back({centre + (in - offset) * d, centre + (out + offset) * d});
  }
  return pairs;
}

struct Tally {
  int checked = 0, undecided = 0;
};

// The classification agrees with the analytic predicate wherever it decides; Inside comes with
// a parameter in the domain whose image is within the tolerance.
template <int D>
void expect_classified(const SplineImage<D>& image, const Eigen::Vector3d& x, bool inside, Tally& tally) {
  const auto q = image.query(x);
  ++tally.checked;
  if (q.membership == ImageMembership::Undecided) {
    ++tally.undecided;
    EXPECT_LE(q.distance_bound, 1e-6 * image.size()) << x.transpose();
    return;
  }
  ASSERT_EQ(q.membership == ImageMembership::Inside, inside) << "x = " << x.transpose() << " cells " << q.cells_tested;
  if (inside) {
    ASSERT_TRUE(q.preimage.has_value());
    const TensorSpline<D>& patch = image.patches()[q.preimage->patch];
    ASSERT_TRUE(patch.contains(q.preimage->parameter));
    const Eigen::VectorXd value = patch.evaluate(q.preimage->parameter);
    EXPECT_LE((value - x).norm(), image.tolerance());
    EXPECT_NEAR(q.residual, (value - x).norm(), 1e-3 * image.tolerance());
  } else {
    EXPECT_FALSE(q.preimage.has_value());
  }
}

template <int D>
Tally expect_boundary_classified(const SplineImage<D>& image, const Predicate& contains, const Eigen::Vector3d& centre, int pairs,
                                 std::mt19937& rng) {
  Tally tally;
  const double offset = 1e-6 * image.size();
  for (const auto& pair : boundary_pairs(rng, contains, centre, image.size(), offset, pairs)) {
    EXPECT_TRUE(contains(pair.inside));
    EXPECT_FALSE(contains(pair.outside));
    expect_classified(image, pair.inside, true, tally);
    expect_classified(image, pair.outside, false, tally);
  }
  return tally;
}

template <int D>
void expect_random_points_classified(const SplineImage<D>& image, const Predicate& contains, int count, std::mt19937& rng) {
  const Eigen::AlignedBox3d& box = image.bounding_box();
  const Eigen::Vector3d pad = 0.2 * box.diagonal();
  Tally tally;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d x;
    for (int a = 0; a < 3; ++a) {
      std::uniform_real_distribution<double> coordinate(box.min()[a] - pad[a], box.max()[a] + pad[a]);
      x[a] = coordinate(rng);
    }
    expect_classified(image, x, contains(x), tally);
  }
  EXPECT_EQ(tally.undecided, 0);
}

void report_undecided(const char* model, const Tally& tally) {
  std::printf("[ %s: %d of %d points within 1e-6 of the boundary undecided ]\n", model, tally.undecided, tally.checked);
  EXPECT_LE(tally.undecided, tally.checked / 50) << model;
}

TEST(PointInImage, UnitCubeOnBothSidesOfEveryFace) {
  std::mt19937 rng(11);
  const SplineImage<3> image({unit_cube_spline()});
  const Predicate contains = [](const Eigen::Vector3d& x) { return (x.array() >= 0).all() && (x.array() <= 1).all(); };
  report_undecided("cube", expect_boundary_classified(image, contains, Eigen::Vector3d(0.5, 0.5, 0.5), 60, rng));
  expect_random_points_classified(image, contains, 200, rng);
}

TEST(PointInImage, KnotPlanesCellBoundariesAndTheClosedBoundaryAreInside) {
  const BSplineVolume cube = unit_cube_spline();
  const SplineImage<3> image({cube});
  Tally tally;
  // Knot planes at 1/3 and 1/2 (the spline is the identity map), the cube's faces, edges and
  // corners: the image is closed, so all are Inside.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1.0 / 3, 0.5, 0.25), Eigen::Vector3d(1, 0.5, 0.5),
                                   Eigen::Vector3d(1, 1.0 / 3, 0.5), Eigen::Vector3d(0, 0, 0.7), Eigen::Vector3d(1, 1, 1)}) {
    expect_classified(image, x, true, tally);
  }
  // Far away in every direction: rejected by the top of the hierarchy.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1e6, 0, 0), Eigen::Vector3d(-1e6, -1e6, 1e6), Eigen::Vector3d(0.5, 0.5, -1e6)}) {
    const auto q = image.query(x);
    EXPECT_EQ(q.membership, ImageMembership::Outside);
    EXPECT_LE(q.cells_tested, 1);
  }
  EXPECT_EQ(tally.undecided, 0);
  EXPECT_THROW(image.classify(Eigen::Vector3d(NAN, 0, 0)), InvalidInput);
}

TEST(PointInImage, ExactRationalBallWithPolesAndCentre) {
  std::mt19937 rng(12);
  const double radius = 1.5;
  const Eigen::Vector3d centre(0.3, -0.2, 0.1);
  const SplineImage<3> image({ball(radius, centre)});
  const Predicate contains = [&](const Eigen::Vector3d& x) { return (x - centre).norm() <= radius; };
  report_undecided("ball", expect_boundary_classified(image, contains, centre, 60, rng));
  expect_random_points_classified(image, contains, 200, rng);
  // The centre (the face u = 0), the poles and the axis (faces v = 0, 1: J = 0 on them), and
  // the seam w = 0 = w = 1: degenerate parameterisations, still Inside.
  Tally tally;
  for (const Eigen::Vector3d& x : std::vector<Eigen::Vector3d>{centre, centre + Eigen::Vector3d(0, 0, radius),
                                                                centre - Eigen::Vector3d(0, 0, 0.5 * radius),
                                                                centre + Eigen::Vector3d(0.7 * radius, 0, 0.1)}) {
    expect_classified(image, x, true, tally);
  }
  for (const Eigen::Vector3d& x : std::vector<Eigen::Vector3d>{centre + Eigen::Vector3d(0, 0, radius * (1 + 1e-6)),
                                                                centre - Eigen::Vector3d(0, 0, radius * (1 + 1e-6))}) {
    expect_classified(image, x, false, tally);
  }
  EXPECT_EQ(tally.undecided, 0);
}

TEST(PointInImage, AHintFromANeighbourGivesTheSameAnswersAndSkipsTheSearchInside) {
  // A ball: points along a line through it and out again, each query started from the
  // preimage of the one before (as the trimmers' grid corners are).
  const double radius = 1.5;
  const Eigen::Vector3d centre(0.3, -0.2, 0.1);
  const SplineImage<3> image({ball(radius, centre)});
  std::optional<SplineImage<3>::Preimage> last;
  int skipped = 0, inside = 0;
  for (int i = 0; i <= 400; ++i) {
    const Eigen::Vector3d x = centre + Eigen::Vector3d(-2.0 + 0.01 * i, 0.31, -0.17);
    const auto plain = image.query(x);
    const auto hinted = last ? image.query(x, *last) : image.query(x);
    ASSERT_EQ(hinted.membership, plain.membership) << x.transpose();
    EXPECT_EQ(hinted.membership == ImageMembership::Inside, (x - centre).norm() <= radius) << x.transpose();
    if (hinted.membership == ImageMembership::Inside) {
      ++inside;
      ASSERT_TRUE(hinted.preimage);
      const Eigen::VectorXd p = image.patches()[hinted.preimage->patch].evaluate(hinted.preimage->parameter);
      EXPECT_LE((Eigen::Vector3d(p[0], p[1], p[2]) - x).norm(), image.tolerance());
      skipped += hinted.cells_tested == 0;
    }
    if (hinted.preimage) last = hinted.preimage;
  }
  // Every inside point but the first is found from its neighbour's preimage.
  EXPECT_GE(skipped, inside - 2);
  EXPECT_GT(inside, 100);
  // A hint naming no patch is ignored.
  const SplineImage<3>::Preimage nowhere{7, {0.5, 0.5, 0.5}};
  EXPECT_EQ(image.query(centre, nowhere).membership, ImageMembership::Inside);
  EXPECT_EQ(image.query(centre + Eigen::Vector3d(2, 0, 0), nowhere).membership, ImageMembership::Outside);
}

TEST(PointInImage, FoldedVolumeBulgesBeyondItsFaces) {
  std::mt19937 rng(13);
  const double pull = 8;
  const SplineImage<3> image({folded_volume(pull)});
  const Predicate contains = [&](const Eigen::Vector3d& x) { return in_folded(pull, x); };
  EXPECT_GT(folded_bulge(pull, 0.5, 0.5), 1.25);
  // Just below and above the bulge x = M(v, w), which the faces u = 0, 1 do not reach: its
  // points are images of the fold (x'(u) = 0 inside the domain).
  Tally tally;
  const double offset = 1e-6 * image.size();
  std::uniform_real_distribution<double> unit(0.05, 0.95);
  for (int i = 0; i < 60; ++i) {
    const double v = unit(rng), w = unit(rng);
    const double top = folded_bulge(pull, v, w);
    expect_classified(image, Eigen::Vector3d(top - offset, v, w), true, tally);
    expect_classified(image, Eigen::Vector3d(top + offset, v, w), false, tally);
  }
  report_undecided("folded bulge", tally);
  report_undecided("folded volume", expect_boundary_classified(image, contains, Eigen::Vector3d(0.5, 0.5, 0.5), 40, rng));
  expect_random_points_classified(image, contains, 200, rng);
}

TEST(PointInImage, TranslatedBoxIsTheHullOfItsEnds) {
  std::mt19937 rng(14);
  const Eigen::Vector3d offset(1.5, 0.8, -0.6);
  const BSplineHypervolume sweep = translated_along(box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5)), offset);
  const SplineImage<4> image({sweep});
  const Predicate contains = [&](const Eigen::Vector3d& x) { return in_translated_unit_box(x, offset); };
  report_undecided("translated box",
                   expect_boundary_classified(image, contains, Eigen::Vector3d(0.5, 0.5, 0.5) + 0.5 * offset, 60, rng));
  expect_random_points_classified(image, contains, 200, rng);
}

TEST(PointInImage, FaceMovingInItsOwnPlaneGivesRankTwoPieces) {
  // Translating the unit cube along +x: the faces y = 0, 1 and z = 0, 1 move in their own
  // planes, so s restricted to them has rank 2 (the image of the face v = 0 over (u, w, t) is
  // planar). The swept volume is the box [0, 1 + a] x [0, 1]^2.
  std::mt19937 rng(15);
  const Eigen::Vector3d offset(0.75, 0, 0);
  const SplineImage<4> image({translated_along(box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5)), offset)});
  const Predicate contains = [&](const Eigen::Vector3d& x) { return in_translated_unit_box(x, offset); };
  report_undecided("box sliding in its faces' planes",
                   expect_boundary_classified(image, contains, Eigen::Vector3d(0.875, 0.5, 0.5), 40, rng));
  Tally tally;
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.2, 0, 0.5), Eigen::Vector3d(1.75, 1, 1), Eigen::Vector3d(0.3, 0.5, 1)}) {
    expect_classified(image, x, true, tally);
  }
  EXPECT_EQ(tally.undecided, 0);
}

TEST(PointInImage, BallAlongASegmentIsACapsule) {
  std::mt19937 rng(16);
  const double radius = 0.6;
  const Eigen::Vector3d start(0.1, 0.2, -0.3), offset(1.2, -0.7, 0.9);
  const SplineImage<4> image({translated_along(ball(radius, start), offset)});
  const Predicate contains = [&](const Eigen::Vector3d& x) { return segment_distance(x, start, start + offset) <= radius; };
  report_undecided("capsule", expect_boundary_classified(image, contains, start + 0.5 * offset, 60, rng));
  expect_random_points_classified(image, contains, 200, rng);
  // The preimage of an interior point is a curve (4 unknowns, 3 equations); any point of it will
  // do. Far points are rejected at once.
  const auto far = image.query(Eigen::Vector3d(0, 1e6, 0));
  EXPECT_EQ(far.membership, ImageMembership::Outside);
  EXPECT_EQ(image.classify(start + offset), ImageMembership::Inside);
}

TEST(PointInImage, UnionOfFourQuarterTorusPatches) {
  std::mt19937 rng(17);
  const double major = 2, minor = 0.5;
  std::vector<BSplineVolume> quarters;
  for (int q = 0; q < 4; ++q) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(q * std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    quarters.push_back(transform_affine(torus(major, minor, 90.0), turn, Eigen::Vector3d::Zero()));
  }
  const SplineImage<3> image(std::move(quarters));
  const Predicate contains = [&](const Eigen::Vector3d& x) { return std::hypot(std::hypot(x.x(), x.y()) - major, x.z()) <= minor; };
  Tally tally;
  const double offset = 1e-6 * image.size();
  for (int i = 0; i < 40; ++i) {
    std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
    const double phi = angle(rng), theta = angle(rng);
    const Eigen::Vector3d around(std::cos(phi), std::sin(phi), 0);
    const Eigen::Vector3d normal = std::cos(theta) * around + std::sin(theta) * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d surface = major * around + minor * normal;
    expect_classified(image, surface - offset * normal, true, tally);
    expect_classified(image, surface + offset * normal, false, tally);
  }
  report_undecided("four quarter tori", tally);
  expect_random_points_classified(image, contains, 200, rng);
}

TEST(PointInImage, PointsAtInfinityAreElevatedAway) {
  // Lasser's half torus has weight-0 control points; the oracle elevates them away.
  std::mt19937 rng(18);
  const double major = 2, minor = 1;
  const SplineImage<3> image({half_torus(major, minor)});
  const Predicate contains = [&](const Eigen::Vector3d& x) {
    return x.y() >= 0 && std::hypot(std::hypot(x.x(), x.y()) - major, x.z()) <= minor;
  };
  expect_random_points_classified(image, contains, 150, rng);
}

TEST(PointInImage, RejectsWhatItCannotBound) {
  EXPECT_THROW(SplineImage<3>({}), InvalidInput);
  const BSplineVolume cube = box(Eigen::Vector3d(1, 1, 1));
  PointInImageOptions negative;
  negative.max_depth = -1;
  EXPECT_THROW(SplineImage<3>({cube}, negative), InvalidInput);
  PointInImageOptions zero_tolerance;
  zero_tolerance.tolerance = 0;
  EXPECT_THROW(SplineImage<3>({cube}, zero_tolerance), InvalidInput);
  PointInImageOptions no_cells;
  no_cells.max_cells = 0;
  EXPECT_THROW(SplineImage<3>({cube}, no_cells), InvalidInput);
  const BSplineVolume planar({KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1}), KnotVector(1, {0, 0, 1, 1})}, 2,
                             std::vector<double>(16, 0.0));
  EXPECT_THROW(SplineImage<3>({planar}), InvalidInput);
}

TEST(PointInImage, MemoryOfThePrecomputedCellsIsBounded) {
  const BSplineHypervolume sweep = translated_along(ball(1.0), Eigen::Vector3d(2, 0, 0));
  PointInImageOptions small;
  small.precomputed_bytes = 64 << 10;
  const SplineImage<4> image({sweep}, small);
  // Each cell of degree (1, 2, 2, 1) holds 2 * 3 * 3 * 2 homogeneous points of 4 numbers.
  const std::size_t cell_bytes = 36 * 4 * sizeof(double);
  EXPECT_LE(image.precomputed_cells() * cell_bytes, small.precomputed_bytes + cell_bytes);
  EXPECT_EQ(image.classify(Eigen::Vector3d(1, 0, 0)), ImageMembership::Inside);
  EXPECT_EQ(image.classify(Eigen::Vector3d(1, 0, 1 + 1e-6)), ImageMembership::Outside);
}


TEST(PointInImage, UndecidedOnlyWithinItsDistanceBoundOfTheImage) {
  // A tolerance below the distance and a shallow depth limit: points 1e-10 of the radius
  // outside the ball are never Inside; where the depth runs out, the bound reported is at least
  // the true distance (it bounds the distance from x to the image).
  PointInImageOptions shallow;
  shallow.tolerance = 1e-15;
  shallow.max_depth = 15;
  const double radius = 1;
  const SplineImage<3> image({ball(radius)}, shallow);
  std::mt19937 rng(19);
  int undecided = 0;
  for (int i = 0; i < 40; ++i) {
    const double distance = 1e-10 * radius;
    const Eigen::Vector3d x = (radius + distance) * random_direction(rng);
    const auto q = image.query(x);
    ASSERT_NE(q.membership, ImageMembership::Inside);
    if (q.membership == ImageMembership::Undecided) {
      ++undecided;
      EXPECT_GE(q.distance_bound, distance * (1 - 1e-4));
      EXPECT_LE(q.distance_bound, 1e-2 * image.size());
    }
  }
  std::printf("[ 1e-10 outside with max_depth 15: %d of 40 undecided ]\n", undecided);
}

TEST(PointInImage, ParallelQueriesAgreeWithSerialOnes) {
  const SplineImage<4> image({translated_along(ball(0.6), Eigen::Vector3d(1.2, -0.7, 0.9))});
  std::mt19937 rng(20);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 200; ++i) points.push_back(Eigen::Vector3d(0.6, -0.35, 0.45) + 1.2 * random_direction(rng) * std::cbrt(i / 200.0));
  std::vector<ImageMembership> serial, parallel(points.size());
  for (const auto& x : points) serial.push_back(image.classify(x));
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { parallel[i] = image.classify(points[i]); });
  EXPECT_EQ(serial, parallel);
}


template <int D>
void expect_image_points_never_outside(std::uint32_t seed, std::array<int, D> degrees, bool rational) {
  // Random B-splines fold over themselves everywhere; a point s(p) is in the image, so the
  // certificate must never call it Outside, and Newton should find a preimage.
  std::mt19937 rng(seed);
  const TensorSpline<D> s = test_support::random_spline<D>(rng, degrees, 2, 3, rational);
  const SplineImage<D> image({s});
  int inside = 0;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d x = s.evaluate(test_support::random_parameter(rng, s));
    const auto q = image.query(x);
    ASSERT_NE(q.membership, ImageMembership::Outside) << x.transpose();
    inside += q.membership == ImageMembership::Inside;
  }
  EXPECT_EQ(inside, 60);
}

TEST(PointInImage, ImagePointsOfRandomFoldedSplinesAreNeverOutside) {
  expect_image_points_never_outside<3>(21, {2, 3, 2}, false);
  expect_image_points_never_outside<3>(22, {3, 2, 2}, true);
  expect_image_points_never_outside<4>(23, {2, 2, 1, 2}, true);
}

}  // namespace
}  // namespace volspline
