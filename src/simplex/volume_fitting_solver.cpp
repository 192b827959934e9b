#include "volume_fitting_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"

namespace volspline {
namespace {

double fitting_solver_seconds_since(std::chrono::steady_clock::time_point& start) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - start).count();
  start = now;
  return s;
}

// Q = N P for the symmetric N stored in full (column j of N is its row j), rows in parallel:
// each row's sum runs in the matrix's order, so the result does not depend on the threads.
void fitting_symmetric_product(const Eigen::SparseMatrix<double>& n, const Eigen::MatrixXd& p, Eigen::MatrixXd& q) {
  q.resize(p.rows(), p.cols());
  const Eigen::Index k = p.cols();
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n.outerSize(), 512), [&](const tbb::blocked_range<Eigen::Index>& range) {
    for (Eigen::Index j = range.begin(); j != range.end(); ++j)
      for (Eigen::Index c = 0; c < k; ++c) {
        double sum = 0;
        for (Eigen::SparseMatrix<double>::InnerIterator it(n, j); it; ++it) sum += it.value() * p(it.index(), c);
        q(j, c) = sum;
      }
  });
}

using FittingPreconditioner = Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>;

// Preconditioned conjugate gradients on every column of N X = B from X; column c stops when
// |r_c| <= tolerance · scale_c. Returns the iterations.
int fitting_block_cg(const Eigen::SparseMatrix<double>& n, const FittingPreconditioner* ic, const Eigen::VectorXd& jacobi,
                     const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const Eigen::VectorXd& scale, double tolerance, int max_iterations) {
  const Eigen::Index k = b.cols();
  Eigen::MatrixXd q;
  fitting_symmetric_product(n, x, q);
  Eigen::MatrixXd r = b - q, z(r.rows(), k);
  const auto precondition = [&] {
    if (ic != nullptr)
      tbb::parallel_for(Eigen::Index{0}, k, [&](Eigen::Index c) { z.col(c) = ic->solve(r.col(c)); });
    else
      z = jacobi.asDiagonal() * r;
  };
  std::vector<bool> done(static_cast<std::size_t>(k));
  int open = 0;
  for (Eigen::Index c = 0; c < k; ++c) open += !(done[static_cast<std::size_t>(c)] = r.col(c).norm() <= tolerance * scale[c]);
  if (open == 0) return 0;
  precondition();
  Eigen::MatrixXd p = z;
  Eigen::VectorXd rz(k);
  for (Eigen::Index c = 0; c < k; ++c) rz[c] = r.col(c).dot(z.col(c));
  int iteration = 0;
  while (open > 0 && iteration < max_iterations) {
    ++iteration;
    fitting_symmetric_product(n, p, q);
    for (Eigen::Index c = 0; c < k; ++c) {
      if (done[static_cast<std::size_t>(c)]) continue;
      const double curvature = p.col(c).dot(q.col(c));
      if (!(curvature > 0)) {  // exhausted (rounding): this column is as good as it gets
        done[static_cast<std::size_t>(c)] = true, --open;
        continue;
      }
      const double alpha = rz[c] / curvature;
      x.col(c) += alpha * p.col(c);
      r.col(c) -= alpha * q.col(c);
      if (r.col(c).norm() <= tolerance * scale[c]) done[static_cast<std::size_t>(c)] = true, --open;
    }
    if (open == 0) break;
    precondition();
    for (Eigen::Index c = 0; c < k; ++c) {
      if (done[static_cast<std::size_t>(c)]) continue;
      const double next = r.col(c).dot(z.col(c));
      p.col(c) = z.col(c) + (next / rz[c]) * p.col(c);
      rz[c] = next;
    }
  }
  return iteration;
}

}  // namespace

Eigen::MatrixXd solve_fitting_least_squares(const Eigen::SparseMatrix<double, Eigen::RowMajor>& a, const Eigen::MatrixXd& targets,
                                            const Eigen::MatrixXd& prior, const FittingSolverOptions& options, FittingSolverReport* report) {
  FittingSolverReport ignored;
  FittingSolverReport& out = report ? *report : ignored;
  out = {};
  auto clock = std::chrono::steady_clock::now();
  const Eigen::Index unknowns = a.cols();
  const Eigen::SparseMatrix<double> columns = a;  // column-major copy: AᵀA as a product of columns
  Eigen::SparseMatrix<double> normal = columns.transpose() * columns;
  const double lambda = options.regularisation * std::max(normal.diagonal().mean(), 1e-300);
  for (Eigen::Index i = 0; i < unknowns; ++i) normal.coeffRef(i, i) += lambda;
  normal.makeCompressed();
  const Eigen::MatrixXd rhs = columns.transpose() * targets + lambda * prior;
  out.normal_seconds = fitting_solver_seconds_since(clock);

  const auto refine = [&](auto&& solve_update, Eigen::MatrixXd solution) {
    for (int step = 0; step < options.refinement_steps; ++step) {
      // argmin |A c − t|² + λ |c − c_k|² = c_k + (AᵀA + λI)⁻¹ Aᵀ (t − A c_k).
      const Eigen::MatrixXd update = solve_update(Eigen::MatrixXd(columns.transpose() * (targets - a * solution)));
      solution += update;
      ++out.refinement_steps;
      if (update.lpNorm<Eigen::Infinity>() <= options.step_tolerance * std::max(solution.lpNorm<Eigen::Infinity>(), 1e-300)) break;
    }
    return solution;
  };

  if (unknowns <= options.direct_limit) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) throw Error("the least-squares system of the control vectors could not be factored");
    out.factor_seconds = fitting_solver_seconds_since(clock);
    Eigen::MatrixXd solution = refine([&](const Eigen::MatrixXd& b) -> Eigen::MatrixXd { return solver.solve(b); }, solver.solve(rhs));
    out.solve_seconds = fitting_solver_seconds_since(clock);
    return solution;
  }
  out.direct = false;
  FittingPreconditioner ic;
  ic.compute(normal);
  const bool use_ic = ic.info() == Eigen::Success;
  const Eigen::VectorXd jacobi = normal.diagonal().cwiseInverse();
  out.factor_seconds = fitting_solver_seconds_since(clock);
  // Iterative refinement in the outer loop: each conjugate-gradient solve runs only to
  // `inner_tolerance` of its own right-hand side, and the Tikhonov steps, which recompute the
  // residual from A, gain that many digits each, until Aᵀ(T − A C) is below
  // iterative_tolerance of AᵀT + λ C_0 (what a single tight solve would reach, at a fraction of
  // the iterations: a tight solve repeated per step made large fits slow).
  Eigen::VectorXd scale(rhs.cols());
  for (Eigen::Index c = 0; c < rhs.cols(); ++c) scale[c] = std::max(rhs.col(c).norm(), 1e-300);
  const auto inner = [&](const Eigen::MatrixXd& b, Eigen::MatrixXd& x) {
    Eigen::VectorXd own(b.cols());
    for (Eigen::Index c = 0; c < b.cols(); ++c) own[c] = std::max(b.col(c).norm(), 1e-300);
    out.iterations += fitting_block_cg(normal, use_ic ? &ic : nullptr, jacobi, b, x, own, options.inner_tolerance, options.iterative_max_iterations);
  };
  Eigen::MatrixXd solution = prior;
  inner(rhs, solution);
  double previous = INFINITY;
  for (int step = 0; step < options.refinement_steps; ++step) {
    const Eigen::MatrixXd gradient = columns.transpose() * (targets - a * solution);
    bool converged = true;
    double worst = 0;
    for (Eigen::Index c = 0; c < gradient.cols(); ++c) {
      converged = converged && gradient.col(c).norm() <= options.iterative_tolerance * scale[c];
      worst = std::max(worst, gradient.col(c).norm() / scale[c]);
    }
    // Stagnation: what is left is the regularisation's bias along directions the data barely
    // see (it shrinks by λ / (λ + σ) per step, σ tiny), not worth a full solve per step.
    if (converged || worst > 0.5 * previous) break;
    previous = worst;
    Eigen::MatrixXd update = Eigen::MatrixXd::Zero(gradient.rows(), gradient.cols());
    inner(gradient, update);
    solution += update;
    ++out.refinement_steps;
    if (update.lpNorm<Eigen::Infinity>() <= options.step_tolerance * std::max(solution.lpNorm<Eigen::Infinity>(), 1e-300)) break;
  }
  out.solve_seconds = fitting_solver_seconds_since(clock);
  return solution;
}

}  // namespace volspline
