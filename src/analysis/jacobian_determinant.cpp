#include "volspline/analysis/jacobian_determinant.h"

#include <array>
#include <string>

#include "volspline/core/error.h"

namespace volspline {

namespace {

void check_in_r3(const BSplineVolume& volume) {
  if (volume.dimension() != 3) {
    throw InvalidInput("the Jacobian determinant needs control points in R^3, got " + std::to_string(volume.dimension()) +
                       " coordinates");
  }
}

}  // namespace

double jacobian_determinant(const BSplineVolume& volume, const BSplineVolume::Parameter& t) {
  check_in_r3(volume);
  std::array<double, 12> d;
  volume.evaluate_derivatives(t, 1, d.data());
  return jacobian_determinant(d.data());
}

JacobianWithGradient jacobian_with_gradient(const BSplineVolume& volume, const BSplineVolume::Parameter& t) {
  check_in_r3(volume);
  std::array<double, 30> d;
  volume.evaluate_derivatives(t, 2, d.data());
  return jacobian_with_gradient(d.data());
}

}  // namespace volspline
