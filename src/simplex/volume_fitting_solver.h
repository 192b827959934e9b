#pragma once
// The sparse least squares of eq. 10 for fitting volume data, built for large fits:
//   min |A C − T|² + λ |C − C_0|²,   then iterated Tikhonov steps (src/simplex/control_fit.h)
// on the normal equations (AᵀA + λI) C = AᵀT + λ C_0, all columns (geometry and attributes)
// at once. Small systems: SimplicialLDLT, one factorisation for every column and step. Large
// ones: preconditioned conjugate gradients (incomplete Cholesky) run on all columns together, so
// that each product with AᵀA (oneTBB, row blocks: the same sums whatever the threads) serves
// every column; each CG solve is loose (1e-6 of its right-hand side) and the Tikhonov steps
// double as iterative refinement until the normal equations' residual is tight
// (docs/fitting.md, "Speed").
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace volspline {

struct FittingSolverOptions {
  /// λ as a fraction of the mean diagonal of AᵀA.
  double regularisation = 1e-8;
  /// Iterated Tikhonov steps after the first solve, at most; they stop once a step changes no
  /// entry by more than `step_tolerance` of the largest.
  int refinement_steps = 40;
  double step_tolerance = 1e-15;
  /// Up to this many unknowns: SimplicialLDLT; above: conjugate gradients.
  long direct_limit = 8000;
  /// The conjugate-gradient path ends when every column of Aᵀ(T − A C) is below this fraction of
  /// the column of AᵀT + λ C_0; each CG solve runs to `inner_tolerance` of its own right-hand side.
  double iterative_tolerance = 1e-13;
  double inner_tolerance = 1e-6;
  int iterative_max_iterations = 5000;
};

struct FittingSolverReport {
  bool direct = true;
  int refinement_steps = 0;
  /// Conjugate-gradient iterations, all solves together (0 on the direct path).
  int iterations = 0;
  /// Seconds forming AᵀA, factoring (or the preconditioner), solving.
  double normal_seconds = 0, factor_seconds = 0, solve_seconds = 0;
};

/// The regularised least-squares columns (one per column of targets and prior).
/// \throw Error if the system cannot be factored.
Eigen::MatrixXd solve_fitting_least_squares(const Eigen::SparseMatrix<double, Eigen::RowMajor>& a, const Eigen::MatrixXd& targets,
                                            const Eigen::MatrixXd& prior, const FittingSolverOptions& options = {},
                                            FittingSolverReport* report = nullptr);

}  // namespace volspline
