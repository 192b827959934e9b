#pragma once
// The lattice of a free-form deformation (Lasser 1994, §III.2): a trivariate B-spline volume
// together with the "deformation domain", the box P0 + sU + tV + uW of eq. 10 in which the
// object to be deformed is embedded. U, V and W need not be orthogonal; (s, t, u) are found from
// a world point by eq. 10-11 (Cramer's rule on the three edge vectors). A segmented lattice
// (Lasser: "subdivided into sub-boxes corresponding to a segmented TPB volume") is a volume whose
// knot vectors have interior knots; its domain is still [0, 1]^3, so lattice coordinates and
// spline parameters are the same numbers and no rescaling can add rounding.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/io/model_file.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct Lattice {
  /// The deformation map in lattice coordinates: domain [0, 1]^3, into R^3, polynomial or
  /// rational (Lasser's weights w_ijk), one Bézier cell or several.
  BSplineVolume volume;
  /// P0 of eq. 10: the world position of lattice coordinates (0, 0, 0).
  Eigen::Vector3d origin;
  /// Columns U, V, W of eq. 10: the box edges. Linearly independent, not necessarily orthogonal.
  Eigen::Matrix3d axes;
};

/// World point -> lattice coordinates (s, t, u) = axes^{-1} (X - origin), computed as in
/// Lasser's eq. 10-11: s = (V x W).(X - P0) / (V x W).U and cyclically. Points of the deformation
/// domain get coordinates in [0, 1]^3.
Eigen::Vector3d lattice_coordinates(const Lattice& lattice, const Eigen::Vector3d& point);

/// Lattice coordinates -> world point of the undeformed box: origin + axes * (s, t, u).
Eigen::Vector3d lattice_box_point(const Lattice& lattice, const Eigen::Vector3d& coordinates);

/// Checks what every FFD function relies on: a volume into R^3 on the domain [0, 1]^3, finite
/// origin and axes, axes not coplanar (|det| > 1e-12 |U| |V| |W|).
/// \throw InvalidInput saying which requirement fails.
void validate_lattice(const Lattice& lattice);

/// The undeformed lattice around `points`: its control points are the Greville points of the
/// knot vectors mapped through the frame, V_ijk = P0 + g_i U + g_j V + g_k W. For one Bézier cell
/// g_i = i / l, which is Lasser's eq. 11; with interior knots the Greville abscissae are what make
/// the B-spline reproduce linear functions (sum_i g_i N_i(s) = s), so the deformation by this
/// lattice is the identity up to rounding.
///
/// `directions` (columns, any lengths, not coplanar) are the directions of U, V and W; the box
/// is the smallest one with edges along them that contains the points, enlarged on every side by
/// `margin` times its largest edge (so a flat set of points still gets a solid box).
/// `degree` >= 1 and `divisions` (Bézier cells per direction) >= 1 in each direction.
/// \throw InvalidInput for no points, non-finite points, degrees or divisions out of range
/// (degree <= kMaxModelDegree, divisions <= 1024), a negative or non-finite margin, coplanar
/// directions, or a box with an empty edge (all points on a plane and margin 0, or all equal).
Lattice undeformed_lattice(const std::vector<Eigen::Vector3d>& points, std::array<int, 3> degree,
                           std::array<int, 3> divisions = {1, 1, 1}, double margin = 0.05,
                           const Eigen::Matrix3d& directions = Eigen::Matrix3d::Identity());

/// The undeformed lattice around the vertices of `mesh` (see above).
Lattice undeformed_lattice(const TriangleMesh& mesh, std::array<int, 3> degree,
                           std::array<int, 3> divisions = {1, 1, 1}, double margin = 0.05,
                           const Eigen::Matrix3d& directions = Eigen::Matrix3d::Identity());

/// A lattice as a model file: one volume object named "lattice" (bezier_volume when it is a
/// single cell, else bspline_volume) whose metadata is
/// {"lattice": {"origin": [x, y, z], "axes": [[Ux, Uy, Uz], [Vx, Vy, Vz], [Wx, Wy, Wz]]}}.
/// \throw InvalidInput if the lattice is invalid (validate_lattice).
Model lattice_to_model(const Lattice& lattice);

/// The lattice stored in `model`. `source` (usually the file name) starts every message, which
/// then gives the JSON path: "lattice.json: objects[0].metadata.lattice.axes: expected three
/// non-coplanar vectors". Other keys of the metadata are ignored.
/// \throw InvalidInput unless the model has exactly one object, a volume into R^3 on [0, 1]^3,
/// with a valid "lattice" entry in its metadata.
Lattice lattice_from_model(const Model& model, const std::string& source);

}  // namespace volspline
