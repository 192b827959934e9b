#pragma once
// Free-form deformation (Lasser 1994, §III.2; Sederberg-Parry 1986): a point of an object is
// located in the deformation domain by its lattice coordinates (eq. 10-11) and replaced by the
// lattice volume evaluated there. Lattices: deform/lattice.h. What is exact and what is not:
// docs/ffd.md.
#include <vector>

#include <Eigen/Core>

#include "volspline/deform/lattice.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The deformed position of `point`.
///
/// Inside the deformation domain (lattice coordinates c in [0, 1]^3) this is volume(c).
/// Outside, the point is moved by the displacement of the nearest point of the domain in lattice
/// coordinates: X + volume(clamp(c)) - box(clamp(c)), with clamp to [0, 1]^3 per coordinate.
/// Why this and not the two usual choices: leaving outside points unchanged (Sederberg-Parry)
/// tears the object apart at the box boundary as soon as a boundary control point moves, and
/// clamping (X -> volume(clamp(c))) flattens everything outside onto the boundary. The
/// displacement rule is continuous everywhere, is the identity for an undeformed lattice, and
/// agrees with "unchanged" whenever the outer layer of control points is left in place (a clamped
/// lattice's boundary depends on that layer only).
/// \throw InvalidInput if `point` is not finite.
Eigen::Vector3d deform_point(const Lattice& lattice, const Eigen::Vector3d& point);

/// deform_point for many points, evaluated in parallel (TensorSpline::evaluate_points); the
/// result equals deform_point point by point, bit for bit.
/// \throw InvalidInput naming the first non-finite point ("points[i]").
std::vector<Eigen::Vector3d> deform_points(const Lattice& lattice, const std::vector<Eigen::Vector3d>& points);

/// The mesh with every vertex position deformed (deform_points); triangles, parts and the
/// vertices' parameters are kept. Only vertices move: the deformed surface is the image of the
/// triangles' corners, so a coarse mesh should be subdivided before a strong bend.
/// \throw InvalidInput for a malformed mesh (validate_mesh).
TriangleMesh deform_mesh(const Lattice& lattice, const TriangleMesh& mesh);

/// The exact image of a spline curve (D = 1), surface (D = 2) or volume (D = 3) under the lattice
/// by functional composition (Lasser 1994, end of §III.2, [Las 91], [DeR 93]).
///
/// Each Bézier piece of the object, of degrees (d_1, ..., d_D), has lattice coordinates that are
/// polynomials of the same degrees (the frame of eq. 10 is affine); putting them into the
/// Bernstein polynomials of a lattice cell of degrees (p, q, r) gives a Bézier piece of degrees
/// (p + q + r) d_m, computed exactly with Bernstein products. The pieces are joined with knots of
/// full multiplicity minus one, so the result is C^0 across the object's knots (its true
/// smoothness is higher; knot removal would recover it). Rational objects and rational lattices
/// are composed in homogeneous form, which is again exact: the result is rational.
///
/// Exactness needs one polynomial per piece, so the object must lie in one lattice cell: always
/// for a single-cell (Bézier) lattice, and for a segmented lattice when the convex hull of the
/// object's control points falls inside one cell. The object must also lie inside the
/// deformation domain (its control points' lattice coordinates in [0, 1]^3 up to 1e-12), where
/// the result agrees with deform_point.
/// \throw InvalidInput if the object does not map into 3-space, has a point at infinity, its
/// control points leave the deformation domain, it crosses cell boundaries of a segmented
/// lattice (the message says to use one Bézier cell or deform a tessellation with deform_mesh),
/// or the composed degree would exceed kMaxModelDegree.
template <int D>
TensorSpline<D> compose(const Lattice& lattice, const TensorSpline<D>& object);

inline BSplineCurve deform_curve(const Lattice& lattice, const BSplineCurve& curve) { return compose(lattice, curve); }
inline BSplineSurface deform_surface(const Lattice& lattice, const BSplineSurface& surface) {
  return compose(lattice, surface);
}

extern template BSplineCurve compose(const Lattice&, const BSplineCurve&);
extern template BSplineSurface compose(const Lattice&, const BSplineSurface&);
extern template BSplineVolume compose(const Lattice&, const BSplineVolume&);

}  // namespace volspline
