// The half-open rule of simplex splines (docs/simplex-splines.md): membership of the symbolically
// perturbed point x + ε e_x + ε² e_y + ε³ e_z, decided by CGAL's filtered exact predicates.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>

#include "simplex_recurrence.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

int orientation3(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                 const Eigen::Vector3d& s) {
  return static_cast<int>(CGAL::orientation(Kernel::Point_3(p.x(), p.y(), p.z()), Kernel::Point_3(q.x(), q.y(), q.z()),
                                            Kernel::Point_3(r.x(), r.y(), r.z()),
                                            Kernel::Point_3(s.x(), s.y(), s.z())));
}

int orientation2(double px, double py, double qx, double qy, double rx, double ry) {
  return static_cast<int>(
      CGAL::orientation(Kernel::Point_2(px, py), Kernel::Point_2(qx, qy), Kernel::Point_2(rx, ry)));
}

// The sign of det[q - p, r - p, x + ε e_x + ε² e_y + ε³ e_z - p] for small ε > 0: the exact
// orientation, then the components of the normal n = (q - p) × (r - p) in the order x, y, z.
// n_x = orientation of (p, q, r) projected to (y, z), n_y to (z, x), n_z to (x, y).
int perturbed_orientation3(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                           const Eigen::Vector3d& x) {
  if (const int s = orientation3(p, q, r, x); s != 0) return s;
  if (const int s = orientation2(p.y(), p.z(), q.y(), q.z(), r.y(), r.z()); s != 0) return s;
  if (const int s = orientation2(p.z(), p.x(), q.z(), q.x(), r.z(), r.x()); s != 0) return s;
  return orientation2(p.x(), p.y(), q.x(), q.y(), r.x(), r.y());
}

// The sign of det[q - p, x + ε e_x + ε² e_y - p]: the exact orientation, then the components of
// the edge normal (-(q - p)_y, (q - p)_x), whose signs are comparisons of coordinates.
int perturbed_orientation2(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& x) {
  if (const int s = orientation2(p.x(), p.y(), q.x(), q.y(), x.x(), x.y()); s != 0) return s;
  if (p.y() != q.y()) return p.y() > q.y() ? 1 : -1;
  if (p.x() != q.x()) return q.x() > p.x() ? 1 : -1;
  return 0;
}

}  // namespace

bool in_half_open_tetrahedron(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const int sign = orientation3(a, b, c, d);
  if (sign == 0) return false;
  // x replaces each vertex in turn and must keep the orientation; the determinants are permuted
  // so that x comes last: (a,b,x,d) -> -(a,b,d,x), (a,x,c,d) -> +(a,c,d,x), (x,b,c,d) -> -(b,c,d,x).
  return perturbed_orientation3(a, b, c, x) == sign && -perturbed_orientation3(a, b, d, x) == sign &&
         perturbed_orientation3(a, c, d, x) == sign && -perturbed_orientation3(b, c, d, x) == sign;
}

bool in_half_open_triangle(const Eigen::Vector2d& x, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                           const Eigen::Vector2d& c) {
  const int sign = orientation2(a.x(), a.y(), b.x(), b.y(), c.x(), c.y());
  if (sign == 0) return false;
  return perturbed_orientation2(a, b, x) == sign && perturbed_orientation2(b, c, x) == sign &&
         perturbed_orientation2(c, a, x) == sign;
}

namespace simplex_detail {

bool exactly_coplanar(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d) {
  return orientation3(a, b, c, d) == 0;
}

bool exactly_collinear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return orientation2(a.x(), a.y(), b.x(), b.y(), c.x(), c.y()) == 0;
}

bool make_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d, BarycentricFrame& frame) {
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const Eigen::Vector3d e3 = d - a;
  const Eigen::Vector3d n1 = e2.cross(e3);
  const double det = e1.dot(n1);
  // Rounding can turn an exactly coplanar four into a tiny nonzero determinant; the exact
  // predicate decides whenever |det| is within a generous multiple of that rounding.
  const double scale = e1.squaredNorm() * e2.squaredNorm() * e3.squaredNorm();
  if (!(det * det > 1e-20 * scale) && (det == 0 || exactly_coplanar(a, b, c, d))) return false;
  const double inverse = 1.0 / det;
  frame.origin = a;
  frame.det = det;
  frame.g[1] = n1 * inverse;
  frame.g[2] = e3.cross(e1) * inverse;
  frame.g[3] = e1.cross(e2) * inverse;
  frame.g[0] = -(frame.g[1] + frame.g[2] + frame.g[3]);
  return true;
}

}  // namespace simplex_detail
}  // namespace volspline
