#pragma once
// The exact orientation predicate on double coordinates (CGAL's filtered orient3d), shared by
// the tetrahedral-mesh checks and the knot-cloud checks so that both decide degeneracy alike.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>

namespace volspline::exact {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

inline Point to_cgal(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

/// The sign (-1, 0, 1) of det[b-a, c-a, d-a], exactly.
inline int orientation(const Point& a, const Point& b, const Point& c, const Point& d) {
  return static_cast<int>(CGAL::orientation(a, b, c, d));
}
inline int orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& d) {
  return orientation(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d));
}

}  // namespace volspline::exact
