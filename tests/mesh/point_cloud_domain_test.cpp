#include "volspline/mesh/point_cloud_domain.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "volspline/core/error.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> grid(int n, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const std::function<bool(const Eigen::Vector3d&)>& keep) {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d t(i, j, k);
        const Eigen::Vector3d x = lo + (hi - lo).cwiseProduct(t / (n - 1));
        if (keep(x)) points.push_back(x);
      }
  return points;
}

double min_distance(const Eigen::Vector3d& x, const std::vector<Eigen::Vector3d>& points, const std::vector<int>& chosen) {
  double d = INFINITY;
  for (int c : chosen) d = std::min(d, (x - points[static_cast<std::size_t>(c)]).norm());
  return d;
}

TEST(PointCloudDomain, FarthestPointSamplesAreGreedyCoveringChoices) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points(400);
  for (auto& p : points) p = Eigen::Vector3d(u(random), u(random), u(random));
  points.push_back(points[17]);  // a duplicate is never chosen twice
  const std::vector<int> chosen = farthest_point_subsample(points, 40);
  ASSERT_EQ(chosen.size(), 40u);
  // Each choice is the point farthest from those before it (brute force), so the distances at
  // which points are chosen do not increase, and the last bounds the covering radius.
  double previous = INFINITY;
  for (std::size_t k = 1; k < chosen.size(); ++k) {
    const std::vector<int> before(chosen.begin(), chosen.begin() + static_cast<std::ptrdiff_t>(k));
    double farthest = 0;
    for (const auto& p : points) farthest = std::max(farthest, min_distance(p, points, before));
    const double d = min_distance(points[static_cast<std::size_t>(chosen[k])], points, before);
    EXPECT_EQ(d, farthest);
    EXPECT_LE(d, previous);
    previous = d;
  }
  double covering = 0;
  for (const auto& p : points) covering = std::max(covering, min_distance(p, points, chosen));
  EXPECT_LE(covering, previous);
  EXPECT_EQ(farthest_point_subsample(points, 40), chosen);  // deterministic
  EXPECT_EQ(farthest_point_subsample(std::vector<Eigen::Vector3d>(5, Eigen::Vector3d::Ones()), 3).size(), 1u);
}

TEST(PointCloudDomain, FarthestPointSamplesFollowASizingField) {
  std::mt19937 random(6);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points(3000);
  for (auto& p : points) p = Eigen::Vector3d(u(random), u(random), u(random));
  // Half the spacing where x < 1/2: about 2³ = 8 times as many samples per volume there.
  std::vector<double> spacing(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) spacing[i] = points[i].x() < 0.5 ? 0.5 : 1.0;
  const std::vector<int> chosen = farthest_point_subsample(points, 180, {}, spacing);
  ASSERT_EQ(chosen.size(), 180u);
  int fine = 0;
  for (int c : chosen) fine += points[static_cast<std::size_t>(c)].x() < 0.5;
  EXPECT_GT(fine, 4 * (180 - fine));
  // Each choice maximises the distance to those before it in units of its own spacing.
  for (std::size_t k = 1; k < 30; ++k) {
    double farthest = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      double d = INFINITY;
      for (std::size_t j = 0; j < k; ++j) d = std::min(d, (points[i] - points[static_cast<std::size_t>(chosen[j])]).norm());
      farthest = std::max(farthest, d / spacing[i]);
    }
    const auto c = static_cast<std::size_t>(chosen[k]);
    double d = INFINITY;
    for (std::size_t j = 0; j < k; ++j) d = std::min(d, (points[c] - points[static_cast<std::size_t>(chosen[j])]).norm());
    EXPECT_NEAR(d / spacing[c], farthest, 1e-12 * farthest);
  }
  // A constant spacing changes nothing.
  EXPECT_EQ(farthest_point_subsample(points, 50, {}, std::vector<double>(points.size(), 3.0)), farthest_point_subsample(points, 50));
  EXPECT_THROW(farthest_point_subsample(points, 10, {}, std::vector<double>(5, 1.0)), InvalidInput);
  spacing[7] = 0;
  EXPECT_THROW(farthest_point_subsample(points, 10, {}, spacing), InvalidInput);
  spacing[7] = NAN;
  EXPECT_THROW(farthest_point_subsample(points, 10, {}, spacing), InvalidInput);
}

TEST(PointCloudDomain, OccupancyBallsHaveTheEighthNearestNeighbourRadius) {
  std::mt19937 random(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> points(300);
  for (auto& p : points) p = Eigen::Vector3d(u(random), u(random), 0.2 * u(random));
  const OccupancyMap map(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::vector<double> distances;
    for (std::size_t j = 0; j < points.size(); ++j)
      if (j != i) distances.push_back((points[i] - points[j]).norm());
    std::sort(distances.begin(), distances.end());
    EXPECT_EQ(map.radius(i), distances[kOccupancyNeighbour - 1]);
  }
  for (int s = 0; s < 2000; ++s) {
    const Eigen::Vector3d x(1.2 * u(random), 1.2 * u(random), 0.5 * u(random));
    bool inside = false;
    for (std::size_t j = 0; j < points.size(); ++j) inside = inside || (x - points[j]).norm() <= map.radius(j);
    EXPECT_EQ(map.contains(x), inside) << x.transpose();
  }
}

TEST(PointCloudDomain, CubeOfPointsGivesTheCubeWithItsCornersEdgesAndFaces) {
  const auto points = grid(9, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), [](const Eigen::Vector3d&) { return true; });
  PointCloudDomainOptions options;
  options.primary_knots = 120;
  const PointCloudDomain domain = point_cloud_domain(points, options);
  EXPECT_NEAR(tetrahedral_mesh_volume(domain.mesh), 1.0, 1e-12);
  EXPECT_EQ(domain.mesh.tetrahedra.size(), domain.delaunay_tetrahedra);  // nothing of a full cube is clipped
  ASSERT_EQ(domain.data_index.size(), domain.mesh.points.size());
  // The solid angle is 4π inside, 2π on a face, π on an edge, π/2 at a corner.
  const std::vector<double> angles = vertex_solid_angles(domain.mesh);
  int corners = 0;
  for (std::size_t v = 0; v < domain.mesh.points.size(); ++v) {
    const Eigen::Vector3d& x = domain.mesh.points[v];
    // The jitter moves interior knots by 1 % of an edge; the hull's stay where the data are.
    const Eigen::Vector3d& data_point = points[static_cast<std::size_t>(domain.data_index[v])];
    if (domain.kinds[v] == VertexKind::Interior) EXPECT_LE((x - data_point).norm(), 0.01 * std::sqrt(3.0));
    else EXPECT_EQ(x, data_point);
    int on = 0;
    for (int a = 0; a < 3; ++a) on += x[a] == 0 || x[a] == 1;
    const double expected[] = {4 * std::numbers::pi, 2 * std::numbers::pi, std::numbers::pi, std::numbers::pi / 2};
    const VertexKind kinds[] = {VertexKind::Interior, VertexKind::General, VertexKind::Curve, VertexKind::Corner};
    EXPECT_NEAR(angles[v], expected[on], 1e-12) << x.transpose();
    EXPECT_EQ(domain.kinds[v], kinds[on]) << x.transpose();
    corners += on == 3;
  }
  EXPECT_EQ(corners, 8);
}

TEST(PointCloudDomain, LShapedPointsDoNotFillTheConcavity) {
  // [0,2]³ without the quadrant x > 1, y > 1: volume 6; the hull's is 7.
  const auto points = grid(17, Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 2, 2),
                           [](const Eigen::Vector3d& x) { return x.x() <= 1 || x.y() <= 1; });
  PointCloudDomainOptions options;
  options.primary_knots = 300;
  const PointCloudDomain domain = point_cloud_domain(points, options);
  PointCloudDomainOptions unclipped = options;
  unclipped.clip_to_occupancy = false;
  EXPECT_NEAR(tetrahedral_mesh_volume(point_cloud_domain(points, unclipped).mesh), 7.0, 1e-12);
  const double volume = tetrahedral_mesh_volume(domain.mesh);
  EXPECT_LT(volume, 6.25);
  EXPECT_GT(volume, 5.9);
  // No tetrahedron reaches deeper into the concavity than two data spacings (1/4).
  for (const auto& t : domain.mesh.tetrahedra) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : t) c += domain.mesh.points[static_cast<std::size_t>(v)] / 4;
    EXPECT_FALSE(c.x() > 1.25 && c.y() > 1.25) << c.transpose();
  }
}

TEST(PointCloudDomain, CoplanarOrTooFewPointsAreRefused) {
  std::vector<Eigen::Vector3d> flat;
  for (int i = 0; i < 10; ++i) flat.emplace_back(i, i * i, 0);
  EXPECT_THROW(point_cloud_domain(flat), InvalidInput);
  EXPECT_THROW(point_cloud_domain(std::vector<Eigen::Vector3d>(3, Eigen::Vector3d::Zero())), InvalidInput);
  std::vector<Eigen::Vector3d> bad = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}};
  try {
    point_cloud_domain(bad);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "points[3]");
  }
}

TEST(PointCloudDomain, ALatticeLayoutCoversTheBoxWithAboutTheAskedNumberOfKnots) {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) points.emplace_back(2.0 * i / 11, 1.0 * j / 11, 1.0 * k / 11);
  PointCloudDomainOptions options;
  options.primary_knots = 60;
  options.lattice = true;
  const PointCloudDomain domain = point_cloud_domain(points, options);
  ASSERT_NO_THROW(validate_tetrahedral_mesh(domain.mesh));
  EXPECT_NEAR(tetrahedral_mesh_volume(domain.mesh), 2.0, 1e-12);  // the box, corners kept
  // cbrt(2 · 2 / 60) = 0.405, so 4.94 x 2.47 x 2.47 cells: of the candidates, 4 x 2 x 2
  // cells of side 0.5 come nearest 60 knots, 5 x 3 x 3 corners and 4 x 2 x 2 centres (rounding
  // each axis, 5 x 2 x 2 cells, gave 74).
  EXPECT_EQ(domain.mesh.points.size(), 45u + 16u);
  for (int v : domain.data_index) EXPECT_EQ(v, -1);
}

}  // namespace
}  // namespace volspline
