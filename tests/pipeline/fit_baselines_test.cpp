#include "volspline/pipeline/fit_baselines.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> scattered_points(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points(n);
  for (auto& p : points) p = Eigen::Vector3d(2 * u(random) - 1, u(random), 0.5 * u(random));
  return points;
}

// x² y − 3 x z² + y z + 0.25: in the tensor-product space of degree 2 in each variable.
double tensor_quadratic(const Eigen::Vector3d& x) { return x.x() * x.x() * x.y() - 3 * x.x() * x.z() * x.z() + x.y() * x.z() + 0.25; }

TEST(FitBaselines, TensorProductFitReproducesItsSpaceAndMapsTheBoxByTheIdentity) {
  const VolumeData data = sampled_volume_data(scattered_points(4000, 3), "f", tensor_quadratic);
  const TensorProductFit fit = fit_tensor_product_volume(data, 2, 300);
  EXPECT_LE(fit.coefficient_count(), 300u);
  EXPECT_GE(fit.coefficient_count(), 150u);
  std::mt19937 random(9);
  std::uniform_real_distribution<double> u(0, 1);
  const auto& k = fit.volume.knot_vector(0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d x(k.domain_min() + (k.domain_max() - k.domain_min()) * u(random),
                            fit.volume.knot_vector(1).domain_min() + (fit.volume.knot_vector(1).domain_max() - fit.volume.knot_vector(1).domain_min()) * u(random),
                            fit.volume.knot_vector(2).domain_min() + (fit.volume.knot_vector(2).domain_max() - fit.volume.knot_vector(2).domain_min()) * u(random));
    EXPECT_NEAR(fit(x)[0], tensor_quadratic(x), 1e-9);
    // Control points at the Greville abscissae: the geometry is the identity.
    const Eigen::VectorXd mapped = fit.volume.evaluate({x.x(), x.y(), x.z()});
    EXPECT_LT((mapped - x).norm(), 1e-13);
  }
}

TEST(FitBaselines, RegularGridsAreRecognisedAndInterpolated) {
  const VolumeData grid = marschner_lobb_data(5);
  const auto found = regular_grid_of(grid);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->axes[0].size(), 5u);
  // At the nodes both interpolants give the data; between them trilinear reproduces a trilinear
  // function exactly.
  for (std::size_t s = 0; s < grid.size(); ++s) {
    EXPECT_DOUBLE_EQ(found->nearest(grid.points[s])[0], grid.attributes(static_cast<Eigen::Index>(s), 0));
    EXPECT_NEAR(found->trilinear(grid.points[s])[0], grid.attributes(static_cast<Eigen::Index>(s), 0), 1e-15);
  }
  auto trilinear = [](const Eigen::Vector3d& x) { return 1 + x.x() - 2 * x.y() * x.z() + 0.5 * x.x() * x.y() * x.z(); };
  std::vector<Eigen::Vector3d> nodes = grid.points;
  const auto linear = regular_grid_of(sampled_volume_data(nodes, "t", trilinear));
  ASSERT_TRUE(linear.has_value());
  std::mt19937 random(4);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d x(u(random), u(random), u(random));
    EXPECT_NEAR(linear->trilinear(x)[0], trilinear(x), 1e-14);
  }
  EXPECT_FALSE(regular_grid_of(sampled_volume_data(scattered_points(125, 1), "f", tensor_quadratic)).has_value());
  VolumeData missing = grid;
  missing.points.pop_back();
  missing.attributes.conservativeResize(missing.attributes.rows() - 1, Eigen::NoChange);
  EXPECT_FALSE(regular_grid_of(missing).has_value());
}

TEST(FitBaselines, ComparisonMeasuresEveryMethodOnTheSamePoints) {
  // A linear field: every method but nearest reproduces it exactly, at the data and everywhere.
  auto field = [](const Eigen::Vector3d& x) { return 2 * x.x() - x.y() + 0.5 * x.z() + 3; };
  const VolumeData data = sampled_volume_data(marschner_lobb_data(9).points, "f", field);
  VolumeFitOptions options;
  options.degree = 2;
  const VolumeFit fit = fit_volume_data(data, options);
  FitComparisonOptions comparison;
  comparison.truth = [&](const Eigen::Vector3d& x) { return Eigen::VectorXd::Constant(1, field(x)); };
  comparison.truth_points = 2000;
  const std::vector<MethodError> errors = compare_volume_fits(data, fit.volume, comparison);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0].method, "dms simplex spline");
  EXPECT_EQ(errors[0].coefficients, static_cast<std::size_t>(fit.volume.control_vector_count()));
  EXPECT_EQ(errors[2].method, "trilinear interpolation");
  EXPECT_EQ(errors[3].method, "nearest node");
  for (int m = 0; m < 3; ++m) {
    EXPECT_LT(errors[static_cast<std::size_t>(m)].data_max_abs, 1e-9) << errors[static_cast<std::size_t>(m)].method;
    EXPECT_LT(errors[static_cast<std::size_t>(m)].truth_max_abs, 1e-9) << errors[static_cast<std::size_t>(m)].method;
  }
  // Nearest is exact at the nodes and off by at most half a cell's change elsewhere.
  EXPECT_EQ(errors[3].data_max_abs, 0.0);
  EXPECT_GT(errors[3].truth_max_abs, 0.01);
  EXPECT_LE(errors[3].truth_max_abs, 0.5 * 0.25 * (2 + 1 + 0.5) + 1e-12);
  // Without a truth the truth errors are NaN.
  const auto no_truth = compare_volume_fits(data, fit.volume);
  EXPECT_TRUE(std::isnan(no_truth[0].truth_mean_square));
}

TEST(FitBaselines, BadRequestsAreRefused) {
  const VolumeData data = sampled_volume_data(scattered_points(200, 2), "f", tensor_quadratic);
  EXPECT_THROW(fit_tensor_product_volume(data, 0, 100), InvalidInput);
  EXPECT_THROW(fit_tensor_product_volume(data, 2, 7), InvalidInput);
  std::vector<Eigen::Vector3d> flat = scattered_points(200, 2);
  for (auto& p : flat) p.z() = 0;
  EXPECT_THROW(fit_tensor_product_volume(sampled_volume_data(flat, "f", tensor_quadratic), 2, 100), InvalidInput);
}

}  // namespace
}  // namespace volspline
