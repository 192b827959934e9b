#pragma once
// Implicit primitives and their Boolean combinations (Peters & Wittman 1995, §1 and §6): every
// function is negative inside, and every primitive is a polynomial of degree ≤ 4 scaled so its
// gradient has length about 1 on the surface (so blend radii and tolerances are lengths).
// Quadrics (plane, sphere, ellipsoid, cylinder, cone) are cubics, hence reproduced exactly by the
// box spline's quasi-interpolation; the torus is quartic and reproduced to O(h⁴).
//
// A scene is evaluated in two ways:
//  * pointwise (scene_value): min / max / smooth minimum of the primitives' values, the exact
//    constructive-solid-geometry function, used outside the spline box and as the reference;
//  * in coefficient space (scene_field): each primitive is quasi-interpolated on one lattice and
//    the same operations are applied to the coefficients, entry by entry (§1: "apply any
//    Boolean operation ... to the coefficient space"). The result is a C² box spline whatever
//    the operations; docs/blend.md explains what this does to the surface.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/boxspline/lattice_field.h"

namespace volspline {

enum class PrimitiveKind { Plane, Sphere, Ellipsoid, Cylinder, Cone, Torus };

/// A primitive in its own frame: world point x maps to local y = rotation^T (x − origin); the
/// axis of a cylinder, cone or torus and the normal of a plane are the local z axis.
struct ImplicitPrimitive {
  PrimitiveKind kind = PrimitiveKind::Sphere;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /// Columns: the local axes in world coordinates (orthonormal, right-handed).
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  /// Sphere and cylinder radius; torus major radius.
  double radius = 1.0;
  /// Torus minor radius.
  double minor_radius = 0.0;
  /// Cone half angle in radians.
  double half_angle = 0.0;
  /// Ellipsoid semi-axes along the local x, y, z axes.
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();

  /// The implicit function (negative inside) and optionally its gradient:
  ///  plane      y_z
  ///  sphere     (|y|² − r²) / (2r)
  ///  ellipsoid  (Σ y_i²/a_i² − 1) ρ/2, ρ = (a_x a_y a_z)^{1/3}
  ///  cylinder   (y_x² + y_y² − r²) / (2r)
  ///  cone       ((y_x² + y_y²) cos²α − y_z² sin²α) / (2 sin α), apex at the origin; the quadric is
  ///             the double cone, negative inside both nappes
  ///  torus      ((|y|² + R² − r²)² − 4R² (y_x² + y_y²)) / (8 R² r)
  double value(const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr) const;
};

/// A right-handed orthonormal frame whose third column is `axis` (normalised).
/// \throw InvalidInput if `axis` is zero or not finite.
Eigen::Matrix3d frame_with_z_axis(const Eigen::Vector3d& axis);

enum class SceneOperation { Primitive, Union, Intersection, Difference, Blend };

struct SceneNode {
  SceneOperation operation = SceneOperation::Primitive;
  ImplicitPrimitive primitive;
  std::vector<SceneNode> children;
  /// Blend radius (SceneOperation::Blend).
  double radius = 0.0;
};

/// The C² smooth minimum with radius k > 0: min(a, b) − k/6 · max(0, 1 − |a − b|/k)³. Equal to
/// min(a, b) where |a − b| ≥ k; twice continuously differentiable everywhere (its second
/// derivative is continuous where |a − b| = k and at a = b).
double smooth_minimum(double a, double b, double k);

/// The C² smooth minimum of any number of values with radius k > 0: the expected value
///   E[min_i (a_i + u_i)],  u_i independent and uniform on [−k/2, k/2].
/// Symmetric in its arguments; equal to min where every other value exceeds the least by at least
/// k; for two values equal to smooth_minimum(a, b, k) (whose correction term is exactly this
/// expectation). C² because its Hessian is the Hessian measure of min (on the tie hyperplanes
/// a_i = a_j) smoothed by the box [−k/2, k/2]^n, whose faces are never parallel to a tie
/// hyperplane. If `derivatives` is not empty (it must then have values.size() entries), it gets
/// the partial derivatives, the probabilities that each value is the least (they sum to 1).
/// Accurate to rounding for any number of values (every quantity is formed from positive
/// terms); cost O(n) plus O(m log m) for the m values within k of the least (docs/blend.md).
/// Implemented in smooth_minimum.cpp.
double smooth_minimum(std::span<const double> values, double k, std::span<double> derivatives = {});

/// The pointwise (CSG) function of a node and optionally its gradient: union = min, intersection
/// = max, difference(A, B) = max(A, −B), blend = the n-ary smooth_minimum of the children.
double scene_value(const SceneNode& node, const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr);

struct Scene {
  /// Lattice spacing h of the box spline.
  double spacing = 0.1;
  /// The box replaced by the spline (§6); the spline's lattice covers it.
  Eigen::Vector3d box_min = Eigen::Vector3d::Constant(-1.0), box_max = Eigen::Vector3d::Constant(1.0);
  /// The region meshed; outside the box the primitives themselves (scene_value) define the
  /// surface. Absent: the box alone.
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> domain;
  SceneNode root;
};

/// The box spline of a scene on lattice_covering(box, spacing): primitives quasi-interpolated,
/// operations applied to the coefficients. \throw InvalidInput for a bad box, spacing or a
/// lattice that is too large.
LatticeField scene_field(const Scene& scene);

/// The number of primitives in a node.
int count_primitives(const SceneNode& node);

}  // namespace volspline
