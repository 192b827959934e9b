#include "volspline/mesh/plane.h"

#include "volspline/core/error.h"

namespace volspline {

Plane plane_through(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  if (!point.allFinite() || !normal.allFinite() || normal.norm() == 0)
    throw InvalidInput("a plane needs a finite point and a finite nonzero normal");
  const Eigen::Vector3d unit = normal.normalized();
  return {unit, unit.dot(point)};
}

}  // namespace volspline
