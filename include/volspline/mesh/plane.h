#pragma once
// A plane in space, for slicing solids and cutting meshes.
#include <Eigen/Core>

namespace volspline {

/// The plane of points x with normal·x = offset; `normal` is a unit vector. Its positive side
/// is normal·x > offset.
struct Plane {
  Eigen::Vector3d normal;
  double offset = 0;
};

/// The plane through `point` with normal direction `normal` (normalised here).
/// \throw InvalidInput if normal is zero or either is not finite.
Plane plane_through(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);

}  // namespace volspline
