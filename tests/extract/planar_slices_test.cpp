#include "volspline/extract/planar_slices.h"

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "support/jacobian_test_volumes.h"
#include "support/test_splines.h"
#include "volspline/construct/primitives.h"
#include "volspline/mesh/parts.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::on_domain_boundary;

using test_support::fold_s;
using test_support::fold_volume;
using test_support::interpolating_bezier;

double mesh_area(const TriangleMesh& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles)
    area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
  return area;
}


// Every slice vertex lies in its plane and is the image of its own parameters, which lie in the
// domain (the requirement, 1e-12).
void expect_exact_vertices(const BSplineVolume& v, const TriangleMesh& slice, const Plane& plane) {
  ASSERT_GT(slice.num_triangles(), 0u);
  for (std::size_t i = 0; i < slice.num_vertices(); ++i) {
    const Eigen::Vector3d& t = slice.parameters[i];
    for (int d = 0; d < 3; ++d) {
      ASSERT_GE(t[d], v.domain_min(d));
      ASSERT_LE(t[d], v.domain_max(d));
    }
    const Eigen::VectorXd image = v.evaluate({t[0], t[1], t[2]});
    EXPECT_LE(std::abs(plane.normal.dot(slice.positions[i]) - plane.offset), 1e-12);
    EXPECT_LE((image - slice.positions[i]).norm(), 1e-12);
  }
  for (const int part : slice.parts) EXPECT_EQ(part, static_cast<int>(Part::Slice));
}

BSplineVolume bent_volume() {
  return interpolating_bezier(
      [](const Eigen::Vector3d& p) {
        return Eigen::Vector3d(p[0] + 0.2 * p[1] * p[1], p[1] + 0.15 * std::sin(2 * p[0]) * p[2], p[2] + 0.1 * p[0] * p[1]);
      },
      {3, 3, 2}, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
}

TEST(PlanarSlice, VerticesLieInThePlaneAndMapFromTheDomain) {
  const BSplineVolume v = bent_volume();
  std::mt19937 rng(5);
  std::normal_distribution<double> gauss;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Vector3d normal(gauss(rng), gauss(rng), gauss(rng));
    const Plane plane = plane_through(Eigen::Vector3d(1.1, 0.5, 0.5), normal);
    expect_exact_vertices(v, planar_slice(v, plane, {.resolution = 12}), plane);
  }
}

TEST(PlanarSlice, RationalBallSliceIsTheDiskWithTheRightArea) {
  const BSplineVolume b = ball(1.5, Eigen::Vector3d(0.2, -0.1, 0.3));
  for (const double c : {0.0, 0.7, -1.1}) {
    const Plane plane{Eigen::Vector3d::UnitZ(), 0.3 + c};
    const TriangleMesh slice = planar_slice(b, plane, {.resolution = 48});
    expect_exact_vertices(b, slice, plane);
    const double r2 = 1.5 * 1.5 - c * c;
    for (const auto& p : slice.positions) EXPECT_LE((p - Eigen::Vector3d(0.2, -0.1, 0.3 + c)).squaredNorm(), r2 + 1e-9);
    // Chords of the outline cut off O(h^2) of the disk.
    EXPECT_NEAR(mesh_area(slice), std::numbers::pi * r2, 5e-3 * std::numbers::pi * r2);
  }
}

TEST(PlanarSlice, AffineSolidCutThroughSamplePointsIsExactAndWelded) {
  // A box's map is affine, so its slice is exact; x = 1 passes through grid samples, where g = 0
  // exactly at sample points: the slice must appear once, welded, with the exact area.
  const BSplineVolume box = interpolating_bezier([](const Eigen::Vector3d& p) { return p; }, {1, 1, 1},
                                                 Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 3, 4));
  const Plane plane{Eigen::Vector3d::UnitX(), 1.0};
  const TriangleMesh slice = planar_slice(box, plane, {.resolution = 8});
  expect_exact_vertices(box, slice, plane);
  EXPECT_NEAR(mesh_area(slice), 12.0, 1e-12);
  const auto stats = edge_statistics(slice);
  EXPECT_EQ(stats.nonmanifold_edges, 0u);
}

TEST(PlanarSlice, HasNoCracksItsBordersLieOnTheDomainBoundary) {
  const BSplineVolume v = bent_volume();
  const Plane plane = plane_through(Eigen::Vector3d(1.0, 0.4, 0.6), Eigen::Vector3d(1, 0.5, -0.3));
  const TriangleMesh slice = planar_slice(v, plane, {.resolution = 10});
  ASSERT_GT(slice.num_triangles(), 0u);
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : slice.triangles)
    for (int i = 0; i < 3; ++i) ++uses[{std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])}];
  int borders = 0;
  for (const auto& [edge, count] : uses) {
    EXPECT_LE(count, 2);
    if (count == 1) {
      ++borders;
      EXPECT_TRUE(on_domain_boundary(v, slice.parameters[static_cast<std::size_t>(edge.first)]) &&
                  on_domain_boundary(v, slice.parameters[static_cast<std::size_t>(edge.second)]))
          << "a border edge inside the domain is a crack";
    }
  }
  EXPECT_GT(borders, 0);
}

TEST(PlanarSlice, FollowsEverySheetWhereThePlaneCutsTheSolidSeveralTimes) {
  // x = u, y = v^3/3 - s v, z = w folds over itself: the plane y = 0 meets it on the sheets
  // v = 0 and v = ±sqrt(3 s(u, w)) (where |v| <= 1).
  const BSplineVolume v = fold_volume();
  const Plane plane{Eigen::Vector3d::UnitY(), 0.0};
  const TriangleMesh slice = planar_slice(v, plane, {.resolution = 24});
  expect_exact_vertices(v, slice, plane);
  int middle = 0, outer = 0;
  for (const auto& t : slice.parameters) {
    const double root = std::sqrt(3 * fold_s(t[0], t[2]));
    const double distance = std::min({std::abs(t[1]), std::abs(t[1] - root), std::abs(t[1] + root)});
    EXPECT_LE(distance, 1e-9) << "v = " << t[1];
    (std::abs(t[1]) < 1e-6 ? middle : outer)++;
  }
  EXPECT_GT(middle, 10);
  EXPECT_GT(outer, 10);
}

TEST(PlanarSlice, MissingPlaneGivesNothingAndSeveralPlanesShareOneSampling) {
  const BSplineVolume v = bent_volume();
  EXPECT_EQ(planar_slice(v, {Eigen::Vector3d::UnitZ(), 10.0}).num_triangles(), 0u);
  const auto planes = parallel_planes(0, 3, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
  ASSERT_EQ(planes.size(), 3u);
  TriangleMesh separate;
  for (const auto& p : planes) separate.append(planar_slice(v, p, {.resolution = 8}));
  const TriangleMesh together = planar_slices(v, planes, {.resolution = 8});
  EXPECT_EQ(together.num_triangles(), separate.num_triangles());
  EXPECT_EQ(together.positions, separate.positions);
}

TEST(PlaneFamilies, SeriesCoreAndPaddlewheelHaveTheirGeometry) {
  const auto series = parallel_planes(2, 3, Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(1, 1, 3));
  ASSERT_EQ(series.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(series[static_cast<std::size_t>(i)].normal, Eigen::Vector3d::UnitZ());
    EXPECT_DOUBLE_EQ(series[static_cast<std::size_t>(i)].offset, i);
  }
  const Eigen::Vector3d point(0.3, -0.2, 0.9);
  const auto core = core_planes(point);
  ASSERT_EQ(core.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(core[static_cast<std::size_t>(i)].normal.dot(point), core[static_cast<std::size_t>(i)].offset);
    for (int j = 0; j < i; ++j) EXPECT_EQ(core[static_cast<std::size_t>(i)].normal.dot(core[static_cast<std::size_t>(j)].normal), 0.0);
  }
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 2) / 3;
  const auto wheel = paddlewheel_planes(point, axis, 4);
  ASSERT_EQ(wheel.size(), 4u);
  for (std::size_t i = 0; i < wheel.size(); ++i) {
    EXPECT_NEAR(wheel[i].normal.norm(), 1.0, 1e-15);
    EXPECT_NEAR(wheel[i].normal.dot(point) - wheel[i].offset, 0.0, 1e-14);
    EXPECT_NEAR(wheel[i].normal.dot(point + 5 * axis) - wheel[i].offset, 0.0, 1e-14);  // contains the axis
    EXPECT_NEAR(std::acos(std::clamp(wheel[i].normal.dot(wheel[(i + 1) % 4].normal), -1.0, 1.0)),
                i == 3 ? std::numbers::pi / 4 * 3 : std::numbers::pi / 4, 1e-12);
  }
}

TEST(PlanarSlice, RejectsBadPlanesAndCounts) {
  const BSplineVolume v = bent_volume();
  EXPECT_THROW(planar_slice(v, {Eigen::Vector3d::Zero(), 1.0}), InvalidInput);
  EXPECT_THROW(planar_slice(v, {Eigen::Vector3d(1, std::nan(""), 0), 1.0}), InvalidInput);
  EXPECT_THROW(planar_slice(v, {Eigen::Vector3d::UnitX(), 1.0}, {.resolution = 0}), InvalidInput);
  EXPECT_THROW(plane_through(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), InvalidInput);
  EXPECT_THROW(parallel_planes(3, 2, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), InvalidInput);
  EXPECT_THROW(parallel_planes(0, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), InvalidInput);
  EXPECT_THROW(paddlewheel_planes(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 3), InvalidInput);
  EXPECT_THROW(paddlewheel_planes(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0), InvalidInput);
}

}  // namespace
}  // namespace volspline
