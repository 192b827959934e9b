#pragma once
// Barycentric coordinates of the point of triangle (a, b, c) nearest to p's projection, clamped
// into the triangle; the centroid for a degenerate triangle. Shared by the superset trimming and
// the contouring trimmer, which both carry (u, v, w, t) from superset triangles to new vertices.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace volspline {

inline Eigen::Vector3d clamped_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(std::abs(den) > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1 - v - w, v, w};
}

}  // namespace volspline
