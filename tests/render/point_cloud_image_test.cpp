#include "volspline/render/point_cloud_image.h"

#include <cmath>

#include <gtest/gtest.h>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> lattice(int n) {
  std::vector<Eigen::Vector3d> p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.emplace_back(i, j, k);
  return p;
}

// One closed, outward octahedron per point drawn (volume 4/3 s^3 each), its vertices carrying
// the point's value; the cut leaves out one side, the thinning every k-th point.
TEST(PointCloudImage, MarkersAreOctahedraAtThePointsWithTheirValues) {
  const auto points = lattice(5);  // 125 points, spacing 1
  std::vector<double> values(points.size());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = points[i].x() + 10 * points[i].z();
  PointCloudPictureOptions options;
  options.marker_size = 0.2;
  const PointMarkers all = point_markers(points, values, options);
  EXPECT_EQ(all.points_drawn, 125u);
  EXPECT_EQ(all.mesh.num_triangles(), 8u * 125);
  EXPECT_TRUE(edge_statistics(all.mesh).closed_and_oriented());
  EXPECT_NEAR(enclosed_volume(all.mesh), 125 * 4.0 / 3 * 0.2 * 0.2 * 0.2, 1e-12);
  for (std::size_t v = 0; v < all.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d& x = all.mesh.positions[v];
    const Eigen::Vector3d centre = x.array().round();
    EXPECT_NEAR((x - centre).norm(), 0.2, 1e-12);
    EXPECT_EQ(all.vertex_values[v], centre.x() + 10 * centre.z());
  }
  options.cut = Plane{Eigen::Vector3d::UnitZ(), 1.5};  // z > 1.5 left out: two layers of 25 stay
  EXPECT_EQ(point_markers(points, values, options).points_drawn, 50u);
  options.cut.reset();
  options.max_points = 40;  // every 4th
  EXPECT_EQ(point_markers(points, values, options).points_drawn, 32u);
  // The automatic size: 0.35 of the spacing (the box 4^3 over 125 points: 0.8^(1/3)... spacing).
  options = {};
  const PointMarkers automatic = point_markers(points, values, options);
  const double expected = 0.35 * std::cbrt(64.0 / 125);
  EXPECT_NEAR((automatic.mesh.positions[0] - points[0]).norm(), expected, 1e-12);
}

TEST(PointCloudImage, DrawsAndRefusesBadInput) {
  const auto points = lattice(3);
  const std::vector<double> values(points.size(), 1.0);
  PointCloudPictureOptions options;
  options.render.width = 64;
  options.render.height = 48;
  const Image image = point_cloud_image(points, values, "f", options);
  EXPECT_EQ(image.width, 64);
  EXPECT_THROW(point_markers(points, std::vector<double>(3, 1.0)), InvalidInput);
  EXPECT_THROW(point_markers({Eigen::Vector3d(std::nan(""), 0, 0)}, {1.0}), InvalidInput);
  options.cut = Plane{Eigen::Vector3d::UnitX(), -1};  // every point on the positive side
  EXPECT_THROW(point_cloud_image(points, values, "f", options), InvalidInput);
  options.cut.reset();
  options.max_points = 0;
  EXPECT_THROW(point_markers(points, values, options), InvalidInput);
}

}  // namespace
}  // namespace volspline
