#include "control_fit.h"

#include <algorithm>

#include <Eigen/Sparse>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

std::vector<Eigen::Vector3d> lattice_samples(const TetrahedralMesh& domain, int m) {
  std::vector<Eigen::Vector3d> samples;
  for (const auto& t : domain.tetrahedra) {
    std::array<Eigen::Vector3d, 4> p;
    for (int c = 0; c < 4; ++c) p[static_cast<std::size_t>(c)] = domain.points[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
    const Eigen::Vector3d centroid = (p[0] + p[1] + p[2] + p[3]) / 4;
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) {
          const int d = m - a - b - c;
          const Eigen::Vector3d x = (a * p[0] + b * p[1] + c * p[2] + d * p[3]) / m;
          samples.push_back(x + 1e-3 * (centroid - x));
        }
  }
  return samples;
}

Eigen::SparseMatrix<double> basis_matrix(const DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& samples) {
  DmsSplineEvaluator evaluator(volume);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t s = 0; s < samples.size(); ++s)
    evaluator.for_each_collocation_weight(samples[s], [&](int row, double value) {
      if (value != 0) entries.emplace_back(static_cast<int>(s), row, value);
    });
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(samples.size()), volume.control_vector_count());
  a.setFromTriplets(entries.begin(), entries.end());
  return a;
}

Eigen::MatrixXd solve_control_columns(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& targets, const Eigen::MatrixXd& prior,
                                      const ControlFitOptions& options) {
  const Eigen::Index rows = a.cols();
  Eigen::SparseMatrix<double> normal = a.transpose() * a;
  const double lambda = options.regularisation * std::max(normal.diagonal().mean(), 1e-300);
  Eigen::SparseMatrix<double> identity(rows, rows);
  identity.setIdentity();
  normal += lambda * identity;
  const auto refine = [&](auto& solver, Eigen::MatrixXd solution) {
    for (int step = 0; step < options.refinement_steps; ++step) {
      // argmin |A c - t|^2 + lambda |c - c_k|^2 = c_k + (AᵀA + lambda I)^-1 Aᵀ (t - A c_k).
      const Eigen::MatrixXd residual = targets - a * solution;
      const Eigen::MatrixXd update = solver.solve(a.transpose() * residual);
      solution += update;
      if (update.lpNorm<Eigen::Infinity>() <= 1e-15 * std::max(solution.lpNorm<Eigen::Infinity>(), 1e-300)) break;
    }
    return solution;
  };
  if (rows <= options.direct_limit) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) throw Error("the least-squares system of the control vectors could not be factored");
    return refine(solver, solver.solve(a.transpose() * targets + lambda * prior));
  }
  // Large systems: the simplicial factorisation fills in (3-D supports), conjugate gradients
  // with an incomplete Cholesky preconditioner do not.
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> solver;
  solver.setTolerance(options.iterative_tolerance);
  solver.setMaxIterations(options.iterative_max_iterations);
  solver.compute(normal);
  if (solver.info() != Eigen::Success) throw Error("the preconditioner of the control vectors' least-squares system could not be computed");
  Eigen::MatrixXd solution = prior;
  const Eigen::MatrixXd rhs = a.transpose() * targets + lambda * prior;
  for (Eigen::Index c = 0; c < rhs.cols(); ++c) solution.col(c) = solver.solveWithGuess(rhs.col(c), prior.col(c));
  return refine(solver, solution);
}

void fit_control_columns(DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& samples, const Eigen::MatrixXd& targets,
                         const std::vector<int>& columns, const Eigen::MatrixXd& prior) {
  const Eigen::MatrixXd solution = solve_control_columns(basis_matrix(volume, samples), targets, prior);
  for (std::size_t c = 0; c < columns.size(); ++c)
    volume.control_vectors().col(columns[c]) = solution.col(static_cast<Eigen::Index>(c));
}

}  // namespace volspline
