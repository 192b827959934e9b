#include "newton_in_domain.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "volspline/core/error.h"

namespace volspline::detail {

// The value, the first partial derivatives (columns) and, for order 2, the Hessian of every
// component, from evaluate_derivatives (derivative_multi_indices order). Outside the anonymous
// namespace: the lambdas of newton_in_domain (external linkage) capture one.
template <int D>
struct DomainNewtonJet {
  Eigen::Vector3d value;
  Eigen::Matrix<double, 3, D> jacobian;
  std::array<Eigen::Matrix<double, D, D>, 3> hessian;
};

namespace {

template <int D>
DomainNewtonJet<D> evaluate_jet(const TensorSpline<D>& s, const std::array<double, D>& p, int order = 1) {
  double numbers[3 * (1 + D + D * (D + 1) / 2)];
  s.evaluate_derivatives(p, order, numbers);
  DomainNewtonJet<D> jet;
  jet.value = Eigen::Map<const Eigen::Vector3d>(numbers);
  jet.jacobian = Eigen::Map<const Eigen::Matrix<double, 3, D>>(numbers + 3);
  if (order < 2) return jet;
  static const std::vector<std::array<int, D>> indices = derivative_multi_indices<D>(2);
  for (std::size_t m = 1 + D; m < indices.size(); ++m) {
    int first = -1, second = -1;
    for (int d = 0; d < D; ++d) {
      for (int k = 0; k < indices[m][static_cast<std::size_t>(d)]; ++k) (first < 0 ? first : second) = d;
    }
    for (std::size_t c = 0; c < 3; ++c) jet.hessian[c](first, second) = jet.hessian[c](second, first) = numbers[3 * m + c];
  }
  return jet;
}

// Coordinates held at a bound: those at a bound whose descent direction (the gradient of
// -|r|^2 / 2, J^T r) leaves the domain.
template <int D>
std::array<bool, D> free_coordinates(const std::array<double, D>& p, const std::array<double, D>& low, const std::array<double, D>& high,
                                     const Eigen::Matrix<double, D, 1>& descent) {
  std::array<bool, D> free{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    const double g = descent(static_cast<Eigen::Index>(d));
    free[d] = !((p[d] <= low[d] && g <= 0) || (p[d] >= high[d] && g >= 0));
  }
  return free;
}

// Solves (A + damping * max diag(A) I) step = rhs over the free coordinates, 0 for the others.
// Returns false if the damped matrix is not positive definite.
template <int D>
bool damped_step(Eigen::Matrix<double, D, D> A, Eigen::Matrix<double, D, 1> rhs, const std::array<bool, D>& free, double damping,
                 Eigen::Matrix<double, D, 1>& step) {
  double scale = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    if (free[d]) scale = std::max(scale, A(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(d)));
  }
  if (!(scale > 0)) return false;
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    const auto i = static_cast<Eigen::Index>(d);
    if (free[d]) {
      A(i, i) += damping * scale;
      continue;
    }
    A.row(i).setZero();
    A.col(i).setZero();
    A(i, i) = 1;
    rhs(i) = 0;
  }
  const Eigen::LDLT<Eigen::Matrix<double, D, D>> ldlt(A);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().minCoeff() > 0)) return false;
  step = ldlt.solve(rhs);
  return step.allFinite();
}

}  // namespace

template <int D>
DomainNewtonResult<D> newton_in_domain(const TensorSpline<D>& s, const Eigen::Vector3d& x, const std::array<double, D>& start,
                                       double tolerance, int max_evaluations) {
  if (s.dimension() != 3) {
    throw InvalidInput("s(p) = x needs a map into R^3, got control points of dimension " + std::to_string(s.dimension()));
  }
  std::array<double, D> low{}, high{};
  for (int d = 0; d < D; ++d) {
    low[static_cast<std::size_t>(d)] = s.domain_min(d);
    high[static_cast<std::size_t>(d)] = s.domain_max(d);
  }
  auto clamp_into_domain = [&](std::array<double, D> p) {
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) p[d] = std::clamp(p[d], low[d], high[d]);
    return p;
  };

  DomainNewtonResult<D> best;
  best.parameter = clamp_into_domain(start);
  DomainNewtonJet<D> jet = evaluate_jet<D>(s, best.parameter);
  best.value = jet.value;
  best.residual = (x - jet.value).norm();
  int evaluations = 1;
  // The trial point p + step clamped into the domain; false if it did not move. Accepted (and
  // `jet` updated) when the residual decreases.
  auto try_step = [&](const Eigen::Matrix<double, D, 1>& step, bool& moved) {
    std::array<double, D> trial = best.parameter;
    moved = false;
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
      const double before = trial[d];
      trial[d] = std::clamp(trial[d] + step(static_cast<Eigen::Index>(d)), low[d], high[d]);
      moved = moved || trial[d] != before;
    }
    if (!moved) return false;
    const DomainNewtonJet<D> trial_jet = evaluate_jet<D>(s, trial);
    ++evaluations;
    const double trial_residual = (x - trial_jet.value).norm();
    if (!(trial_residual < best.residual)) return false;
    best.parameter = trial;
    best.value = trial_jet.value;
    best.residual = trial_residual;
    jet = trial_jet;
    return true;
  };

  // Gauss–Newton with Levenberg–Marquardt damping relative to the largest diagonal entry of
  // J^T J: tiny, so that a good step is the minimum-norm Gauss–Newton step J^+ r; raised after
  // each failed trial, which turns the step towards the projected steepest descent direction;
  // lowered after a success.
  double damping = 1e-12;
  // Steps that gain less than a thousandth of the residual twice running: a local minimum with
  // a positive residual (x outside the image), approached only linearly from here on.
  int stagnant = 0;
  while (best.residual > tolerance && evaluations < max_evaluations && stagnant < 2) {
    const Eigen::Vector3d r = x - jet.value;
    const Eigen::Matrix<double, D, 1> descent = jet.jacobian.transpose() * r;
    const std::array<bool, D> free = free_coordinates<D>(best.parameter, low, high, descent);
    const Eigen::Matrix<double, D, D> normal = jet.jacobian.transpose() * jet.jacobian;
    bool improved = false;
    while (evaluations < max_evaluations && damping < 1e12) {
      Eigen::Matrix<double, D, 1> step;
      if (!damped_step<D>(normal, descent, free, damping, step)) break;
      const double before = best.residual;
      bool moved = false;
      if (try_step(step, moved)) {
        stagnant = best.residual > (1 - 1e-3) * before ? stagnant + 1 : 0;
        damping = std::max(1e-14, damping * 0.1);
        improved = true;
        break;
      }
      if (!moved) break;  // the step is below the resolution of the parameters
      damping *= 100;
    }
    if (!improved) break;
  }

  // Gauss–Newton ignores the curvature of s, which decides the minimum where J is singular
  // along the minimum's valley: at a fold of the map (the envelope of a sweep, Conkey–Joy
  // 2000; J = 0 of a folded volume) the minimum-norm step never moves along the null vector of
  // J, so it stops beside the closest point and its residual direction is tilted. Newton's
  // method on |s - x|^2 / 2 with the full Hessian J^T J - sum_c r_c Hess(s_c), which is positive
  // along that valley, finishes the approach in a few steps.
  for (int polish = 0; polish < 8 && best.residual > tolerance; ++polish) {
    const DomainNewtonJet<D> second = evaluate_jet<D>(s, best.parameter, 2);
    ++evaluations;
    const Eigen::Vector3d r = x - second.value;
    const Eigen::Matrix<double, D, 1> descent = second.jacobian.transpose() * r;
    const std::array<bool, D> free = free_coordinates<D>(best.parameter, low, high, descent);
    Eigen::Matrix<double, D, D> hessian = second.jacobian.transpose() * second.jacobian;
    for (std::size_t c = 0; c < 3; ++c) hessian -= r(static_cast<Eigen::Index>(c)) * second.hessian[c];
    Eigen::Matrix<double, D, 1> step;
    bool moved = false;
    if (!damped_step<D>(hessian, descent, free, 1e-12, step) || !try_step(step, moved)) break;
  }
  best.converged = best.residual <= tolerance;
  const Eigen::Vector3d r = x - jet.value;
  const Eigen::Matrix<double, D, 1> descent = jet.jacobian.transpose() * r;
  const std::array<bool, D> free = free_coordinates<D>(best.parameter, low, high, descent);
  double projected = 0;
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    if (free[d]) projected += descent(static_cast<Eigen::Index>(d)) * descent(static_cast<Eigen::Index>(d));
  }
  best.stationary = best.converged || std::sqrt(projected) <= 1e-6 * jet.jacobian.norm() * r.norm();
  return best;
}

template DomainNewtonResult<3> newton_in_domain<3>(const TensorSpline<3>&, const Eigen::Vector3d&, const std::array<double, 3>&, double, int);
template DomainNewtonResult<4> newton_in_domain<4>(const TensorSpline<4>&, const Eigen::Vector3d&, const std::array<double, 4>&, double, int);

}  // namespace volspline::detail
