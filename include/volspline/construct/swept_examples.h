#pragma once
// The generators, paths and swept solids of Conkey and Joy 2000, §5 (Figs. 4-8), and three swept
// solids whose swept volume is known in closed form, for tests of envelope code. The paper prints
// no control points; the ones chosen here are documented below. Every example is also a model
// file examples/swept-*.json (docs/sweeps.md, "Swept solids").
#include <vector>

#include <Eigen/Core>

#include "volspline/construct/swept_solid.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The solid torus about the z axis through the origin as four exact rational quarter patches
/// (torus() with angle 90, turned by 0, 90, 180 and 270 degrees about z): Fig. 4a's generator.
/// \throw InvalidInput unless 0 < minor < major.
std::vector<BSplineVolume> torus_quarter_patches(double major = 2.0, double minor = 0.5);

/// The cube [-1/2, 1/2]^3 as a triquadratic Bézier volume whose middle control point is pulled
/// up from (0, 0, 0) to (0, 0, 2.5), out through the top face: Fig. 6a's protrusion. At
/// (u, v) = (1/2, 1/2) the z-derivative on the top face is 2 (3/4 * 1/2 + 1/4 (1/2 - 2.5)) < 0
/// while it is positive at the bottom, so J changes sign (J = 0 on a fold surface).
BSplineVolume folded_cube();

/// The solid cylinder of radius 1 and height 2 (cylinder(), degree (1, 1, 2)) elevated to degree
/// (2, 2, 2), with the middle ring of control points (half radius, half height) pulled out to
/// radius 2.5, beyond the mantle: Fig. 7a's generator. J changes sign near the mantle's middle.
BSplineVolume folded_cylinder();

/// The half circle of `radius` in the xy plane from (radius, 0, 0) through (0, radius, 0) to
/// (-radius, 0, 0), two exact rational quadratic quarter arcs (weights 1, sqrt(1/2), 1).
/// \throw InvalidInput unless radius > 0.
BSplineCurve semicircle_path(double radius = 4.0);

/// The straight segment from `from` to `to`, degree 1.
/// \throw InvalidInput for non-finite points.
BSplineCurve line_path(const Eigen::Vector3d& from, const Eigen::Vector3d& to);

/// Fig. 4: torus_quarter_patches along semicircle_path with the fitted Frenet frame.
SweptSolid torus_along_semicircle();
/// Fig. 5: cylinder(1, 2) tumbled 180 degrees about the x axis along the line (0,0,0)-(6,0,0).
SweptSolid tumbling_cylinder();
/// Fig. 6: folded_cube along the cubic curved_loft_path (paper_examples.h), not rotated.
SweptSolid folded_cube_along_cubic();
/// Fig. 7: folded_cylinder rotated 90 degrees about its axis z along the line (0,0,0)-(0,0,6).
SweptSolid turning_folded_cylinder();
/// Fig. 8: folded_cube along semicircle_path, tumbled 180 degrees about the x axis.
SweptSolid tumbling_folded_cube();

/// The box of `size` centred at the origin translated along the segment from 0 to
/// `displacement` (fixed frame): the swept volume is the Minkowski sum of box and segment,
/// of volume abc + |D_x| bc + |D_y| ac + |D_z| ab.
/// \throw InvalidInput as box().
SweptSolid translated_box(const Eigen::Vector3d& size, const Eigen::Vector3d& displacement);

/// The exact rational ball() of `radius` at the origin along the segment from 0 to
/// `displacement`: the capsule of volume 4/3 pi r^3 + pi r^2 |D|.
/// \throw InvalidInput as ball().
SweptSolid translated_ball(double radius, const Eigen::Vector3d& displacement);

/// The box [1, 2] x [-1/2, 1/2] x [0, 1] turned once about the z axis (rotate:0,0,1:360) on the
/// constant path at the origin: the swept volume is the ring 1 <= rho <= sqrt(17) / 2,
/// 0 <= z <= 1, of volume pi (17 / 4 - 1).
SweptSolid rotating_box();

}  // namespace volspline
