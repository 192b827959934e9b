#pragma once
// Exact solid primitives as rational volumes (Lasser 1994, §III.1). Every body of revolution is
// built by revolve() from a profile in the plane through the axis (x radial, z axial, relative to
// `center`), so its parameterisation is: u, v those of the profile, w the angle (0 at +x,
// counter-clockwise about +z). Degenerate faces (a face collapsing to a point or a curve) are
// listed per function; docs/constructions.md has the whole table.
#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The axis-parallel box center +- size / 2, degree (1, 1, 1), u, v, w along x, y, z.
/// \throw InvalidInput (where() "size") unless every size component is positive and finite.
BSplineVolume box(const Eigen::Vector3d& size, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// The solid ball |x - center| <= radius, degree (1, 2, 2), 2 x 5 x 9 control points: a half
/// disk (u radius 0 -> radius, v latitude -90 -> 90 degrees in two quarter arcs) revolved
/// 360 degrees about the z axis through the center. Degenerate faces: u = 0 is the center
/// (a point), v = 0 and v = 1 are the axis segments to the poles, w = 0 and w = 1 are the same
/// half disk (an interior seam); u = 1 is the sphere.
/// \throw InvalidInput (where() "radius") unless radius > 0.
BSplineVolume ball(double radius, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// The cylinder inner <= rho <= radius, |z - center.z| <= height / 2 about the z axis through
/// the center, degree (1, 1, 2): u radial (inner -> radius), v axial (bottom -> top), w angle
/// (four quarter arcs). Solid when inner == 0, whose u = 0 face is then the axis segment;
/// w = 0 and w = 1 are the same interior seam.
/// \throw InvalidInput (where() "radius", "height", "inner") unless radius > 0, height > 0 and
/// 0 <= inner < radius.
BSplineVolume cylinder(double radius, double height, double inner = 0.0, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// The frustum with radius radius1 at z = center.z - height/2 and radius2 at the top, degree
/// (1, 1, 2): u radial (axis -> mantle), v axial, w angle. radius2 == 0 is a cone whose
/// v = 1 face is the apex (a point); likewise radius1 == 0. u = 0 is the axis segment, w = 0
/// and w = 1 are the same interior seam.
/// \throw InvalidInput (where() "radius1", "radius2", "height") unless both radii are >= 0,
/// not both 0, and height > 0.
BSplineVolume cone(double radius1, double radius2, double height, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// The solid torus (rho - major)^2 + (z - center.z)^2 <= minor^2, or the part of it between the
/// angles 0 and angle_deg about the z axis, degree (1, 2, 2): a disk of degree (1, 2) (u radius
/// 0 -> minor, v the circle in four quarter arcs, starting at the outer equator and going
/// up) revolved by revolve(). Degenerate faces: u = 0 is the core circle (a curve); v = 0 and
/// v = 1 are the same interior seam, and so are w = 0 and w = 1 when angle_deg is 360.
/// \throw InvalidInput (where() "minor", "major", "angle") unless 0 < minor < major and
/// 0 < angle_deg <= 360.
BSplineVolume torus(double major, double minor, double angle_deg = 360.0, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Lasser Fig. 2: the solid half torus (y >= center.y) as one rational Bézier volume of degree
/// (1, 2, 2) with points at infinity. The disk is the ruled surface between its upper (u = 0)
/// and lower (u = 1) half circles, each a quadratic with a weight-0 middle point (directions
/// +-z); it is revolved by revolve_single_segment with alpha = 180 degrees. Degenerate faces:
/// v = 0 and v = 1 are the outer and inner equator half circles (curves); u = 0 and u = 1 are
/// the upper and lower halves of the torus surface, w = 0 and w = 1 the end disks.
/// \throw InvalidInput (where() "minor", "major") unless 0 < minor < major.
BSplineVolume half_torus(double major = 2.0, double minor = 1.0, const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Lasser Fig. 3: part of a solid hyperboloid of one sheet, degree (1, 1, 2), a single Bézier
/// volume with points at infinity. The profile is the bilinear patch between the axis segment
/// (u = 0) and the line (throat_radius, z, z), |z| <= half_height (u = 1), skew to the axis;
/// v runs along z. Revolved by 180 degrees (revolve_single_segment), the line sweeps the
/// hyperboloid x^2 + y^2 - z^2 = throat_radius^2 (relative to the center). Faces: u = 0 the axis
/// (a segment), u = 1 the hyperboloid, v = 0 and v = 1 half disks in the planes z = -+half_height,
/// w = 0 and w = 1 both on the saddle y = x z / throat_radius.
/// \throw InvalidInput (where() "throat_radius", "half_height") unless both are positive.
BSplineVolume hyperboloid_segment(double throat_radius = 1.0, double half_height = 1.0,
                                  const Eigen::Vector3d& center = Eigen::Vector3d::Zero());

/// Joy-Duchaineau 1999, Fig. 1: the half cylinder surface swept along a line,
/// p(u, v, w) = (cos(pi u') + 3 w, sin(pi u'), v) on [0,1]^3. The half circle is the rational
/// quadratic with weights (1, 0, 1) (a weight-0 middle point, direction +y), so the point set
/// is exact but u' = (2 / pi) atan(u / (1 - u)) is a reparameterisation of u (equal at u = 0,
/// 1/2, 1): cos(pi u) is not rational in u. Linear in v and w (extrude by (3, 0, 0)). The
/// Jacobian vanishes on u = 1/2, where the sweep direction is tangent to the half cylinder.
BSplineVolume half_cylinder_sweep();

}  // namespace volspline
