// Builds an exact ball and a box with the installed volspline, evaluates the ball on its sphere
// face and certifies the box's Jacobian. Exit 0 when every check holds, 1 otherwise.
#include <cmath>
#include <cstdio>

#include "volspline/analysis/jacobian_validity.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/version.h"

int main() {
  const double radius = 2.0;
  const Eigen::Vector3d center(1.0, -0.5, 3.0);
  const volspline::BSplineVolume ball = volspline::ball(radius, center);
  // u = 1 is the sphere: exact rational arcs put every point on it to rounding.
  double worst = 0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const Eigen::VectorXd x = ball.evaluate({1.0, i / 10.0, j / 10.0});
      worst = std::max(worst, std::abs((x - center).norm() - radius));
    }
  // A box of size a x b x c has the constant Jacobian abc, certified with one sign.
  const volspline::BSplineVolume box = volspline::box(Eigen::Vector3d(1.0, 2.0, 3.0));
  const volspline::JacobianValidity validity = volspline::check_jacobian(box);
  std::printf("volspline %s: sphere distance %.2e, box Jacobian %s in [%g, %g]\n", volspline::kVersion, worst,
              volspline::verdict_name(validity.verdict), validity.lower, validity.upper);
  const bool ok = worst < 1e-12 && validity.verdict == volspline::JacobianVerdict::Valid && validity.orientation == 1 &&
                  std::abs(validity.lower - 6.0) < 1e-9 && std::abs(validity.upper - 6.0) < 1e-9;
  return ok ? 0 : 1;
}
