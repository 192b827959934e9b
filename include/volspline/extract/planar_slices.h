#pragma once
// Planar slices of a trivariate solid (Lasser 1994 §IV, Figs. 11-13): cross sections, series of
// parallel slices, the core section (three orthogonal slices through a point) and paddlewheel
// probes (planes through a common axis).
//
// The slice of the solid V by the plane n·x = d is the image of the zero set of
// g(u, v, w) = n·V(u, v, w) − d in the parameter domain. It is found there — marching
// tetrahedra (mesh/marching_tetrahedra.h) on the Kuhn tetrahedra of a knot-aligned sample grid —
// and mapped through V, so where the plane cuts the solid several times (a fold, a U-shaped
// solid) every sheet appears, and each vertex is the image of a domain point: the crossing on
// its tetrahedron edge is solved on g itself, not interpolated, and the point is V at that root,
// so it lies in the plane to rounding. Only the polygonal outline and the flat triangles between
// vertices are approximations; `resolution` controls them.
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/plane.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct SliceOptions {
  /// Segments across the domain per parameter direction, plus every knot (face_samples); the
  /// grid's cubes are cut into 6 Kuhn tetrahedra each.
  int resolution = 32;
};

/// The slice of `volume` by `plane`: triangles in the plane, part Part::Slice, each vertex
/// with its domain point as parameters. Empty if the plane misses the solid.
/// \throw InvalidInput for a plane with a zero or non-finite normal, resolution < 1, or control
/// points not in R^3.
TriangleMesh planar_slice(const BSplineVolume& volume, const Plane& plane, const SliceOptions& options = {});

/// The slices by several planes as one mesh, sampling the solid once.
TriangleMesh planar_slices(const BSplineVolume& volume, const std::vector<Plane>& planes, const SliceOptions& options = {});

/// Axis-aligned box (min, max) of V sampled on the knot-aligned grid of `resolution`: the
/// frame for a series of slices. \throw InvalidInput as planar_slice.
std::pair<Eigen::Vector3d, Eigen::Vector3d> sampled_bounding_box(const BSplineVolume& volume, int resolution = 16);

/// `count` planes with normal along coordinate `axis` (0 = x, 1 = y, 2 = z) cutting the box
/// [lo, hi] into count + 1 slabs of equal thickness (count == 1: the middle plane).
/// \throw InvalidInput if the axis is not 0..2 or count < 1.
std::vector<Plane> parallel_planes(int axis, int count, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// The three coordinate planes through `point` (x = p_x, y = p_y, z = p_z): the core section.
std::vector<Plane> core_planes(const Eigen::Vector3d& point);

/// `count` planes containing the line through `point` along `axis`, their normals turning about
/// the axis by 180°/count from one to the next (a paddlewheel probe).
/// \throw InvalidInput if count < 1 or the axis is zero or not finite.
std::vector<Plane> paddlewheel_planes(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, int count);

}  // namespace volspline
