#include "volspline/construct/conic_arc.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

using Eigen::Vector3d;

BSplineCurve conic_arc(Vector3d start, double angle_deg, double s2, Vector3d axis_point, Vector3d axis_direction) {
  if (!start.allFinite() || !axis_point.allFinite() || !axis_direction.allFinite() || !std::isfinite(angle_deg) ||
      !std::isfinite(s2))
    throw InvalidInput("conic arc: every number must be finite");
  if (!(axis_direction.norm() > 0.0)) throw InvalidInput("conic arc: the axis direction is zero");
  if (!(angle_deg != 0.0 && std::abs(angle_deg) <= 180.0))
    throw InvalidInput("conic arc: the angle must satisfy 0 < |angle| <= 180 degrees (Lasser 1994, Theorem 2), got " +
                       format_double(angle_deg));
  if (!(s2 > 0.0)) throw InvalidInput("conic arc: s2 must be positive, got " + format_double(s2));
  const Vector3d axis = axis_direction.normalized();
  const Vector3d d = start - axis_point;
  const Vector3d along = d.dot(axis) * axis, radial = d - along;
  if (!(radial.norm() > 1e-14 * std::max(1.0, d.norm()))) throw InvalidInput("conic arc: the start point lies on the axis");
  const double alpha = angle_deg * std::numbers::pi / 180.0;
  const Vector3d side = axis.cross(radial);  // radial turned by +90 degrees about the axis
  const double half_cos = std::abs(angle_deg) == 180.0 ? 0.0 : std::cos(alpha / 2);
  const double half_sin = std::sin(alpha / 2);
  const double end_cos = std::abs(angle_deg) == 180.0 ? -1.0 : std::cos(alpha);
  const double end_sin = std::abs(angle_deg) == 180.0 ? 0.0 : std::sin(alpha);
  const Vector3d end = axis_point + along + end_cos * radial + end_sin * side;
  // Lasser's M_1 K_0 = (rot(alpha/2) radial + cos(alpha/2) (axis_point + along), cos(alpha/2))
  // homogeneously; scaled by s2 it keeps its Cartesian point (where the end tangents meet) and
  // gets the weight s2 cos(alpha/2), which alone decides the type of conic (eq. 9).
  const Vector3d turned = half_cos * radial + half_sin * side;
  std::vector<double> points{start.x(), start.y(), start.z()}, weights{1.0, s2 * half_cos, 1.0};
  Vector3d middle;
  if (half_cos == 0.0) middle = s2 * turned;  // a point at infinity: its direction (Lasser, after eq. 5)
  else middle = axis_point + along + turned / half_cos;
  points.insert(points.end(), {middle.x(), middle.y(), middle.z(), end.x(), end.y(), end.z()});
  return BSplineCurve({KnotVector::bezier(2)}, 3, std::move(points), std::move(weights));
}

}  // namespace volspline
