#include "volspline/mesh/material_interface.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

TEST(MaterialInterface, AJumpSplitsTwoMaterialDataIntoItsTwoSides) {
  const double tilt = 0.37;
  const VolumeData data = two_material_data(13, tilt);
  // Normalised: the jump is 1 / 1.2 of the range, neighbours on one side differ by 0.1 h / 1.2.
  const Eigen::MatrixXd values = (data.attributes.array() - 1.0) / 1.2;
  const JumpRegions regions = jump_regions(data.points, values, 0.3);
  ASSERT_EQ(regions.sizes.size(), 2u);
  EXPECT_GT(regions.jump_edges, 0u);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const Eigen::Vector3d& p = data.points[i];
    const bool first_material = p.x() + tilt * p.y() < 0.5;
    EXPECT_EQ(regions.label[i] == regions.label[0], first_material) << i;
  }
  // No threshold below the within-material differences keeps them apart: one region per point
  // would need a jump below 0.1 h / 1.2; at 2 everything is one region.
  EXPECT_EQ(jump_regions(data.points, values, 2.0).sizes.size(), 1u);
  EXPECT_THROW(jump_regions(data.points, values, 0.0), InvalidInput);
}

TEST(MaterialInterface, TheLocalPlaneOfTheMidpointsFindsATiltedInterfaceWithinAFractionOfTheSpacing) {
  // Scattered points (no grid: the midpoints' offsets from the plane are not periodic).
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points(6000);
  for (auto& p : points) p = Eigen::Vector3d(u(random), u(random), u(random));
  const Eigen::Vector3d normal = Eigen::Vector3d(1, 0.4, -0.2).normalized();
  const auto distance = [&](const Eigen::Vector3d& x) { return normal.dot(x - Eigen::Vector3d(0.5, 0.5, 0.5)); };
  std::vector<int> label(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) label[i] = distance(points[i]) < 0 ? 0 : 1;
  const MaterialInterface interface(points, label);
  EXPECT_GT(interface.sample_count(), 100u);
  const double spacing = std::cbrt(1.0 / 6000);  // the mean distance between the points
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.45, 0.6, 0.4), Eigen::Vector3d(0.2, 0.5, 0.5),
                                   Eigen::Vector3d(0.9, 0.3, 0.6)}) {
    Eigen::Vector3d n;
    const double level = interface.level(x, &n);
    EXPECT_NEAR(level, distance(x), 0.25 * spacing) << x.transpose();
    EXPECT_GT(n.dot(normal), 0.95);
  }
  EXPECT_THROW(MaterialInterface(points, std::vector<int>(points.size(), 0)), InvalidInput);
}

}  // namespace
}  // namespace volspline
