#include "volspline/deform/ffd_example.h"

#include <cmath>
#include <numbers>

#include "volspline/construct/primitives.h"
#include "volspline/extract/face_tessellation.h"

namespace volspline {

FfdExample bent_bar_ffd_example() {
  TriangleMesh mesh = tessellate_faces(box(Eigen::Vector3d(4.0, 1.0, 1.0)), {.resolution = 40});
  const Lattice straight = undeformed_lattice(mesh, {3, 2, 2}, {3, 1, 1}, 0.02);
  const BSplineVolume& v = straight.volume;
  std::vector<double> points = v.points();
  const Eigen::Vector3d axis_point = straight.origin + 0.5 * (straight.axes.col(1) + straight.axes.col(2));
  for (std::size_t i = 0; i < points.size(); i += 3) {
    const Eigen::Vector3d p(points[i], points[i + 1], points[i + 2]);
    const double s = lattice_coordinates(straight, p)[0];
    const double angle = 0.9 * s, c = std::cos(angle), sn = std::sin(angle);
    const Eigen::Vector3d r = p - axis_point;
    // turn about the x axis through the bar's centre line, then lift
    const Eigen::Vector3d q = axis_point + Eigen::Vector3d(r.x(), c * r.y() - sn * r.z(), sn * r.y() + c * r.z()) +
                              Eigen::Vector3d(0.0, 0.0, 1.2 * std::sin(std::numbers::pi * s));
    points[i] = q.x();
    points[i + 1] = q.y();
    points[i + 2] = q.z();
  }
  return {std::move(mesh), Lattice{BSplineVolume(v.knot_vectors(), 3, std::move(points), v.weights()), straight.origin, straight.axes}};
}

}  // namespace volspline
