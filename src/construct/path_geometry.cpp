#include "path_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "volspline/core/error.h"

namespace volspline::detail {

using Eigen::Matrix3d;
using Eigen::Vector3d;

void require_dimension(int dimension, const std::string& what) {
  if (dimension != 3) throw InvalidInput(what + " must be 3-dimensional, got dimension " + std::to_string(dimension));
}

double path_scale(const BSplineCurve& path) {
  double m = 0.0;
  const int n = path.num_control_points_total();
  for (int i = 0; i < n; ++i) {
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) continue;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(path.points()[static_cast<std::size_t>(3 * i + c)]));
  }
  return std::max(m, 1.0);
}

double length_scale(const BSplineCurve& path) {
  const int n = path.num_control_points_total();
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int i = 0; i < n; ++i) {
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) continue;
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const double d = (hi - lo).norm();
  return d > 0.0 ? d : 1.0;
}

// Speeds below this are a vanishing tangent: relative to the average speed over the domain.
double speed_floor(const BSplineCurve& path) {
  return 1e-10 * path_scale(path) / (path.domain_max(0) - path.domain_min(0));
}

Vector3d point_at(const BSplineCurve& curve, double t) {
  const auto x = curve.evaluate({t});
  return {x[0], x[1], x[2]};
}

// Position and first two derivatives.
std::array<Vector3d, 3> derivatives_at(const BSplineCurve& curve, double t, int order) {
  const auto d = curve.evaluate_derivatives({t}, order);
  std::array<Vector3d, 3> r{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
  for (int k = 0; k <= order; ++k) r[static_cast<std::size_t>(k)] = Eigen::Map<const Vector3d>(&d[static_cast<std::size_t>(3 * k)]);
  return r;
}

Matrix3d evaluate_frame(const std::array<BSplineCurve, 3>& curves, double t) {
  Matrix3d r;
  for (int a = 0; a < 3; ++a) r.col(a) = point_at(curves[static_cast<std::size_t>(a)], t);
  return r;
}

}  // namespace volspline::detail
