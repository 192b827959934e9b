// The half-open rule of simplex splines (docs/simplex-splines.md): membership of the symbolically
// perturbed point x + ε e_x + ε² e_y + ε³ e_z, decided by CGAL's filtered exact predicates.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
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

// The orientation of (p, q, r, s), 0 where the four points are coplanar within the rounding of
// their coordinates (simplex_detail::coplanar_within_rounding), as make_frame decides flat fours.
int rounded_orientation3(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                         const Eigen::Vector3d& s) {
  return simplex_detail::coplanar_within_rounding(p, q, r, s) ? 0 : orientation3(p, q, r, s);
}

// The sign of det[q - p, r - p, x + ε e_x + ε² e_y + ε³ e_z - p] for small ε > 0: the
// orientation (exact, or 0 within rounding), then the components of the normal
// n = (q - p) × (r - p) in the order x, y, z.
// n_x = orientation of (p, q, r) projected to (y, z), n_y to (z, x), n_z to (x, y).
template <bool kWithinRounding>
int perturbed_orientation3(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r,
                           const Eigen::Vector3d& x) {
  if (const int s = kWithinRounding ? rounded_orientation3(p, q, r, x) : orientation3(p, q, r, x); s != 0) return s;
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

// x replaces each vertex in turn and must keep the orientation; the determinants are permuted
// so that x comes last: (a,b,x,d) -> -(a,b,d,x), (a,x,c,d) -> +(a,c,d,x), (x,b,c,d) -> -(b,c,d,x).
template <bool kWithinRounding>
bool in_perturbed_tetrahedron(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const int sign = kWithinRounding ? rounded_orientation3(a, b, c, d) : orientation3(a, b, c, d);
  if (sign == 0) return false;
  return perturbed_orientation3<kWithinRounding>(a, b, c, x) == sign &&
         -perturbed_orientation3<kWithinRounding>(a, b, d, x) == sign &&
         perturbed_orientation3<kWithinRounding>(a, c, d, x) == sign &&
         -perturbed_orientation3<kWithinRounding>(b, c, d, x) == sign;
}

}  // namespace

bool in_half_open_tetrahedron(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return in_perturbed_tetrahedron<false>(x, a, b, c, d);
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

bool coplanar_within_rounding(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                              const Eigen::Vector3d& d) {
  // In lexicographic order, so that the floating determinant, and so the decision, does not depend
  // on the order of the four points (every leaf and face that shares them decides alike).
  std::array<const Eigen::Vector3d*, 4> p = {&a, &b, &c, &d};
  std::sort(p.begin(), p.end(), [](const Eigen::Vector3d* u, const Eigen::Vector3d* v) {
    return std::lexicographical_compare(u->data(), u->data() + 3, v->data(), v->data() + 3);
  });
  const Eigen::Vector3d e1 = *p[1] - *p[0];
  const Eigen::Vector3d e2 = *p[2] - *p[0];
  const Eigen::Vector3d e3 = *p[3] - *p[0];
  const double det = e1.dot(e2.cross(e3));
  const double magnitude = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff(),
                                     d.cwiseAbs().maxCoeff()});
  const double n1 = e1.norm();
  const double n2 = e2.norm();
  const double n3 = e3.norm();
  // A change of each coordinate by δ changes det by at most about 2δ(n1 n2 + n1 n3 + n2 n3); the
  // floating determinant itself is off by less than 10 u·magnitude·(that sum).
  return std::abs(det) <= kCoordinateRounding * magnitude * (n1 * n2 + n1 * n3 + n2 * n3);
}

bool in_half_open_tetrahedron_at_knot(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return in_perturbed_tetrahedron<true>(x, a, b, c, d);
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
  // Coplanar within the rounding of the coordinates (exactly coplanar included): a flat four. Its
  // 1/|det|, were it kept, would be rounding noise of any size, and the half-open decisions at
  // points on its plane would not match it (docs/simplex-splines.md, "Knots coplanar within
  // rounding"). The test is only needed where |det| is small relative to the edges.
  const double scale = e1.squaredNorm() * e2.squaredNorm() * e3.squaredNorm();
  if (!(det * det > 1e-20 * scale) && coplanar_within_rounding(a, b, c, d)) return false;
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
