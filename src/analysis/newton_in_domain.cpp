#include "newton_in_domain.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Cholesky>

#include "volspline/core/error.h"

namespace volspline::detail {

namespace {

// The value and the D first partial derivatives (derivative_multi_indices order: e_0 .. e_{D-1}).
template <int D>
struct Jet {
  Eigen::Vector3d value;
  Eigen::Matrix<double, 3, D> jacobian;
};

template <int D>
Jet<D> evaluate_jet(const TensorSpline<D>& s, const std::array<double, D>& p) {
  double numbers[3 * (D + 1)];
  s.evaluate_derivatives(p, 1, numbers);
  Jet<D> jet;
  jet.value = Eigen::Map<const Eigen::Vector3d>(numbers);
  jet.jacobian = Eigen::Map<const Eigen::Matrix<double, 3, D>>(numbers + 3);
  return jet;
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
  Jet<D> jet = evaluate_jet<D>(s, best.parameter);
  best.value = jet.value;
  best.residual = (x - jet.value).norm();
  int evaluations = 1;
  // Levenberg–Marquardt damping relative to the largest diagonal entry of J^T J: tiny, so that
  // a good step is the minimum-norm Gauss–Newton step; raised after each failed trial, which
  // turns the step towards the (projected) steepest descent direction, lowered after a success.
  double damping = 1e-12;
  while (best.residual > tolerance && evaluations < max_evaluations) {
    const Eigen::Vector3d r = x - jet.value;
    const Eigen::Matrix<double, D, 1> gradient = jet.jacobian.transpose() * r;  // descent direction of |r|^2 / 2
    // Coordinates at a bound whose descent direction leaves the domain stay where they are.
    std::array<bool, D> free{};
    Eigen::Matrix<double, 3, D> active = jet.jacobian;
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
      const double p = best.parameter[d];
      free[d] = !((p <= low[d] && gradient(static_cast<Eigen::Index>(d)) <= 0) || (p >= high[d] && gradient(static_cast<Eigen::Index>(d)) >= 0));
      if (!free[d]) active.col(static_cast<Eigen::Index>(d)).setZero();
    }
    Eigen::Matrix<double, D, D> normal = active.transpose() * active;
    const double scale = normal.diagonal().maxCoeff();
    if (!(scale > 0)) break;  // every free direction is stationary: a local minimum
    const Eigen::Matrix<double, D, 1> rhs = active.transpose() * r;
    bool improved = false;
    while (evaluations < max_evaluations && damping < 1e12) {
      Eigen::Matrix<double, D, D> damped = normal;
      // Held coordinates get a unit diagonal, so their step is 0 and the system stays regular.
      for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
        const auto i = static_cast<Eigen::Index>(d);
        damped(i, i) = free[d] ? damped(i, i) + damping * scale : 1.0;
      }
      const Eigen::Matrix<double, D, 1> step = damped.ldlt().solve(rhs);
      std::array<double, D> trial = best.parameter;
      bool moved = false;
      for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
        const double before = trial[d];
        trial[d] = std::clamp(trial[d] + step(static_cast<Eigen::Index>(d)), low[d], high[d]);
        moved = moved || trial[d] != before;
      }
      if (!moved) break;  // the step is below the resolution of the parameters
      const Jet<D> trial_jet = evaluate_jet<D>(s, trial);
      ++evaluations;
      const double trial_residual = (x - trial_jet.value).norm();
      if (trial_residual < best.residual) {
        best.parameter = trial;
        best.value = trial_jet.value;
        best.residual = trial_residual;
        jet = trial_jet;
        damping = std::max(1e-14, damping * 0.1);
        improved = true;
        break;
      }
      damping *= 100;
    }
    if (!improved) break;
  }
  best.converged = best.residual <= tolerance;
  return best;
}

template DomainNewtonResult<3> newton_in_domain<3>(const TensorSpline<3>&, const Eigen::Vector3d&, const std::array<double, 3>&, double, int);
template DomainNewtonResult<4> newton_in_domain<4>(const TensorSpline<4>&, const Eigen::Vector3d&, const std::array<double, 4>&, double, int);

}  // namespace volspline::detail
