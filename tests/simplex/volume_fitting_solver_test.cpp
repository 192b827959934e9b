#include "simplex/volume_fitting_solver.h"

#include <random>

#include <gtest/gtest.h>

#include "simplex/control_fit.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/mesh/point_cloud_domain.h"
#include "volspline/simplex/knot_clouds.h"
#include "simplex/volume_fitting_assembly.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> solver_test_points(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> points(n);
  // One by one: a constructor's arguments are evaluated in an unspecified order (g++ and clang
  // differ); this is g++'s.
  for (auto& p : points) {
    const double z = u(random), y = u(random), x = u(random);
    p = Eigen::Vector3d(x, 0.7 * y, 0.9 * z);
  }
  return points;
}

DmsSplineVolume solver_test_volume(const std::vector<Eigen::Vector3d>& points, int degree, int knots) {
  PointCloudDomainOptions options;
  options.primary_knots = knots;
  PointCloudDomain domain = point_cloud_domain(points, options);
  KnotClouds clouds = generate_knot_clouds(domain.mesh, degree);
  return DmsSplineVolume(std::move(domain.mesh), std::move(clouds), DmsControlSharing::Shared);
}

TEST(VolumeFittingSolver, TheParallelBasisMatrixIsTheSerialOne) {
  const std::vector<Eigen::Vector3d> points = solver_test_points(1500, 4);
  const DmsSplineVolume volume = solver_test_volume(points, 2, 40);
  const Eigen::SparseMatrix<double> serial = basis_matrix(volume, points);
  const Eigen::SparseMatrix<double> parallel = parallel_basis_matrix(volume, points);
  ASSERT_EQ(serial.rows(), parallel.rows());
  ASSERT_EQ(serial.cols(), parallel.cols());
  EXPECT_LE((Eigen::MatrixXd(serial) - Eigen::MatrixXd(parallel)).cwiseAbs().maxCoeff(), 1e-15);
  // Partition of unity in Ω: every row of a point inside sums to 1 (0 outside).
  const Eigen::VectorXd sums = parallel * Eigen::VectorXd::Ones(parallel.cols());
  int inside = 0;
  for (Eigen::Index i = 0; i < sums.size(); ++i) {
    if (sums[i] == 0) continue;
    ++inside;
    // Rounding only; up to 2.7e-12 seen on another cloud (clang's order of the coordinates).
    EXPECT_NEAR(sums[i], 1, 1e-11);
  }
  EXPECT_GT(inside, 1000);
}

TEST(VolumeFittingSolver, ConjugateGradientsAndTheFactorisationAgree) {
  const std::vector<Eigen::Vector3d> points = solver_test_points(2500, 5);
  const DmsSplineVolume volume = solver_test_volume(points, 2, 60);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> a = parallel_basis_matrix(volume, points);
  Eigen::MatrixXd targets(a.rows(), 2), prior = Eigen::MatrixXd::Zero(a.cols(), 2);
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const Eigen::Vector3d& x = points[static_cast<std::size_t>(i)];
    targets(i, 0) = marschner_lobb(x);
    targets(i, 1) = std::sin(3 * x.x()) * x.y();
  }
  FittingSolverOptions direct, iterative;
  iterative.direct_limit = 0;
  FittingSolverReport direct_report, iterative_report;
  const Eigen::MatrixXd d = solve_fitting_least_squares(a, targets, prior, direct, &direct_report);
  const Eigen::MatrixXd c = solve_fitting_least_squares(a, targets, prior, iterative, &iterative_report);
  EXPECT_TRUE(direct_report.direct);
  EXPECT_FALSE(iterative_report.direct);
  EXPECT_GT(iterative_report.iterations, 0);
  // The same fit: the residuals at the data agree (the coefficients may differ along directions
  // the data barely see).
  const Eigen::MatrixXd rd = a * d - targets, rc = a * c - targets;
  EXPECT_LE((rd - rc).cwiseAbs().maxCoeff(), 1e-8 * targets.cwiseAbs().maxCoeff());
  // The normal equations hold: Aᵀ(A C − T) ≈ 0 relative to AᵀT.
  const Eigen::MatrixXd gradient = Eigen::SparseMatrix<double>(a.transpose()) * rc;
  const Eigen::MatrixXd scale = Eigen::SparseMatrix<double>(a.transpose()) * targets;
  EXPECT_LE(gradient.norm(), 1e-9 * scale.norm());
  // Deterministic: the same numbers again.
  EXPECT_EQ(solve_fitting_least_squares(a, targets, prior, iterative), c);
}

}  // namespace
}  // namespace volspline
