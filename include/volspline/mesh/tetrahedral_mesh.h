#pragma once
// A tetrahedralisation of a bounded domain: the domain Ω of a trivariate simplex spline
// (Hua–He–Qin §3.2) and anything else made of tetrahedra. The orientation predicate behind
// `orient_positively` and `validate_tetrahedral_mesh` is exact (CGAL's filtered orient3d on the
// double coordinates), so "degenerate" means exactly coplanar, not "small". How meshes are read,
// made and checked: docs/tetrahedral-domains.md.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// A tetrahedralisation: points and positively oriented tetrahedra (det[b-a, c-a, d-a] > 0).
struct TetrahedralMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 4>> tetrahedra;
};

/// The faces of a positively oriented tetrahedron (a, b, c, d), each oriented outward
/// (counter-clockwise seen from outside), face f opposite corner f: (b, c, d), (a, d, c),
/// (a, b, d), (a, c, b) as corner numbers 0..3.
inline constexpr std::array<std::array<int, 3>, 4> kOutwardTetrahedronFaces{
    {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

/// A face that belongs to exactly one tetrahedron, oriented outward (counter-clockwise seen from
/// outside), with the tetrahedron's index.
struct BoundaryFace {
  std::array<int, 3> vertices;
  int tetrahedron;
  /// The corner (0..3) of `tetrahedron` opposite the face.
  int opposite_corner;
};

/// The boundary faces in the order of their tetrahedra, then of kOutwardTetrahedronFaces.
/// The tetrahedra are assumed positively oriented (validate_tetrahedral_mesh); indices are not
/// checked. On a valid mesh the faces form a closed, consistently oriented surface.
std::vector<BoundaryFace> boundary_faces(const TetrahedralMesh& mesh);

/// For each point, whether it lies on a boundary face (the same assumptions as boundary_faces).
std::vector<bool> boundary_vertices(const TetrahedralMesh& mesh);

/// The part of each tetrahedron: tetrahedra that share a point (by index) are in one part, parts
/// numbered by their lowest tetrahedron. Parts may touch geometrically without sharing points (a
/// material interface whose points are duplicated, docs/fitting.md "Sharp features"); a simplex
/// spline over such a domain is one spline per part (docs/simplex-splines.md). Indices must be in
/// range.
std::vector<int> tetrahedron_parts(const TetrahedralMesh& mesh);

/// Reorients negatively oriented tetrahedra (swaps corners 2 and 3).
/// \throw InvalidInput naming `tetrahedra[i]` for a degenerate one (exact orientation predicate)
/// or one with an index out of range or a repeated corner, or naming `points[i]` for a
/// coordinate that is not finite.
void orient_positively(TetrahedralMesh& mesh);

/// Checks: indices in range, no degenerate tetrahedron (exact predicate), positive orientation,
/// every face shared by at most two tetrahedra with opposite orientation (a proper,
/// face-conforming mesh), no unused points. Also: at least one tetrahedron, finite coordinates, four distinct corners. Not checked
/// (it needs intersection tests): that tetrahedra sharing no face do not overlap.
/// \throw InvalidInput naming the tetrahedron (`tetrahedra[i]`) and what is wrong, or the point
/// (`points[i]`) that is unused or not finite.
void validate_tetrahedral_mesh(const TetrahedralMesh& mesh);

/// Sum of the tetrahedra's signed volumes det[b-a, c-a, d-a] / 6 (the volume of Ω for a valid
/// mesh).
double tetrahedral_mesh_volume(const TetrahedralMesh& mesh);

}  // namespace volspline
