#pragma once
// Joy–Duchaineau §5: bounds of the Jacobian determinant from cones around the control vectors of
// the three partial derivatives (Sederberg–Meyers cones). Kept as a selectable method so that it
// can be compared with the Bernstein bounds of analysis/jacobian_bezier.h on the same run.
//
// A cone is an axis a (unit) and a spread alpha: every unit vector of the set is within alpha of
// a. J = |v_u| |v_v| |v_w| (u . (v x w)) for unit u, v, w, so
//   J in L * (C_u . (C_v x C_w))                                              (eq. 1)
// with L the interval of the length products. Two deviations from the paper, both to keep the
// bound a bound: the lengths of vectors in the convex hull of control vectors can be shorter than
// every control vector, so L_min uses the projection onto the axis (0 when the spread reaches
// 90 degrees); and the cross-product cone is the cone around a_v x a_w that contains every
// (a_v + e_v) x (a_w + e_w) with |e| at most the chord of the spread, a proven superset of the
// paper's Fig. 4 construction that needs no great-circle tangents.
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace volspline {

struct Cone {
  Eigen::Vector3d axis{0, 0, 1};
  /// Radians in [0, pi]; pi means "any direction".
  double spread = 0;
};

/// The cone around the directions of `vectors` (axis: the normalised sum of their unit vectors;
/// spread: the largest angle to it). A zero vector, or a spread of 90 degrees or more (such a
/// cone is not convex, so it would not contain the convex hull), gives spread pi.
Cone bounding_cone(const std::vector<Eigen::Vector3d>& vectors);

/// The interval of u . v over unit vectors u in a, v in b.
std::pair<double, double> cone_dot(const Cone& a, const Cone& b);

/// The interval of u . (v x w) over unit u, v, w in the three cones.
std::pair<double, double> cone_triple_product(const Cone& u, const Cone& v, const Cone& w);

/// An interval containing a . (b x c) for every a, b, c in the convex hulls of the three vector
/// sets (eq. 1), widened by a relative 1e-9 of its magnitude to cover the roundings of the
/// trigonometric functions.
std::pair<double, double> cone_jacobian_bound(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                              const std::vector<Eigen::Vector3d>& c);

}  // namespace volspline
