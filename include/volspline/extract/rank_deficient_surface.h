#pragma once
// The implicit part of a swept solid's envelope (Conkey–Joy 2000 §3, §5, §6): the set in the
// 4-D domain of s(u, v, w, t) where the 4 x 3 Jacobian has rank <= 2, i.e. where the four
// sub-Jacobians J123, J124, J134, J234 (analysis/sub_jacobians.h) vanish together, generically a
// surface; it is meshed in the domain and mapped by s into R^3. docs/envelopes.md.
//
// Subdivision (§5): every Bézier piece is a root cell; a cell is excluded only when a certificate
// proves that the four cannot vanish together on it (RankCertificate: a strict sign of one of
// them, a direction separating the origin from the convex hull of their coefficient 4-vectors,
// or, with cone bounds, the paper's cones). Other cells are split into 16 halves (all four
// directions at once) until they reach the finest level 2^-L of their piece, L = ceil(log2(1 /
// tolerance)). Excluded cells stop early; so a cell that is not excluded is always refined to
// the finest level: every kept cell has the same size, and the kept cells are cells of one
// regular grid (per piece, and across pieces, whose grids meet on the piece boundaries).
//
// Marching 4-simplices (§6): each kept cell is split into the 24 Kuhn simplices (one per
// permutation of the four axes: the path from the low corner adding one unit vector at a time),
// a triangulation that is conforming on any regular grid. In each simplex the hypersurface
// J123 = 0 is interpolated linearly on the edges (J123 evaluated from the spline at the grid
// points): Case I gives one tetrahedron, Case II a prism cut into three. The prism's quads lie on
// the simplex's boundary tetrahedra, shared with the neighbouring simplex, so each quad's diagonal
// is drawn from its vertex with the smallest global key (every edge point is keyed by its grid
// edge): a rule that depends only on the quad, so both neighbours draw the same diagonal, and
// that is acyclic, so every prism splits into three tetrahedra (Dompierre et al. 1999). The
// paper's shortest-diagonal rule is neither (it depends on lengths that ties make ambiguous, and
// can pick a cyclic set of diagonals that no tetrahedra realise).
//
// In each tetrahedron the surface is where, on J123 = 0, s_t lies in the plane of s_u, s_v, s_w:
// marching tetrahedra of the scalar f = K . grad_uvw J123 with K = adj[s_u s_v s_w] s_t =
// (J234, -J134, J124). On J123 = 0 the adjugate has rank one, adj = q p^T with q the null vector of
// the Jacobian of the generator and p the normal of its image plane, so f = (q . grad J123)(p . s_t):
// one continuous polynomial with no sign to choose, vanishing where p . s_t = 0 (the rank-deficient
// set) and on the cusp curves of the fold (q . grad J123 = 0, q tangent to the fold), whose sheets
// (cusp curve x t) the marching finds too and the output drops by the angle between s_t and the
// image plane at their vertices (RankDeficientOptions::cusp_sine). f is
// evaluated exactly (second derivatives of s) at every edge point, never interpolated from the
// grid. Surface vertices are welded by the pair of edge-point keys of their tetrahedron edge, so
// the output is a conforming mesh, except where the set lies in a lattice 2-face: there the face
// itself is the surface (RankDeficientStats::lattice_face_triangles), and the marching's
// triangles next to it may meet it at T-junctions (a superset needs no more).
#include <cstdint>
#include <vector>

#include "volspline/analysis/jacobian_subdivision.h"
#include "volspline/core/progress.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct RankDeficientOptions {
  /// Bezier: the sign and hull certificates of the sub-Jacobians' Bernstein coefficients;
  /// Cone: the paper's cone bounds (polynomial maps only).
  JacobianBoundMethod bounds = JacobianBoundMethod::Bezier;
  /// Relative size of the finest cell within a Bézier piece, in (0, 1]: cells are refined to
  /// 2^-L of their piece in every parameter, L = ceil(log2(1 / tolerance)) (at most 12).
  double tolerance = 1.0 / 16;
  /// Budget of cells examined (>= 1). When it runs out the cells not examined are left out,
  /// counted in stats.cells_unresolved and flagged by stats.budget_exhausted.
  std::int64_t max_cells = 2000000;
  /// Cusp sheets: f also changes sign where the fold's null direction is tangent to it (see
  /// above), though there s_t is generally out of the image plane. A triangle is dropped when at
  /// each of its vertices the sine of the angle between s_t and the plane of s_u, s_v, s_w
  /// exceeds this (on the rank-deficient set it is 0, up to the interpolation error). 1 keeps
  /// every triangle.
  double cusp_sine = 0.1;
  /// Receives the phases "subdivision" (counts cells), "marching" (cells) and "mapping".
  Progress* progress = nullptr;
};

struct RankDeficientStats {
  /// L: the kept cells are 2^-L of their Bézier piece along every parameter.
  int finest_level = 0;
  /// Minors of Bézier pieces divided by the linear factor of a domain face they vanish on (a
  /// collapsed face: a cylinder's axis, a ball's poles), counted once per piece and minor.
  int minors_divided_by_faces = 0;
  /// Cells of the lattice (2^-k of a piece along every parameter) tested by a certificate.
  std::int64_t cells_examined = 0;
  /// Halves, quarters and eighths of cells tested while a cell is split into its 16 children
  /// one direction at a time (an excluded part's children are not examined).
  std::int64_t part_cells_examined = 0;
  /// Cells and parts excluded by each certificate (RankCertificate Sign, Hull, Cone).
  std::int64_t cells_excluded_by_sign = 0, cells_excluded_by_hull = 0, cells_excluded_by_cone = 0;
  /// Excluded because J123 keeps a weak sign (RankCertificate::NoFold).
  std::int64_t cells_excluded_without_fold = 0;
  /// Cells of the finest level not excluded: the ones marched.
  std::int64_t cells_kept = 0;
  /// Cells left unexamined because the budget ran out (0 unless budget_exhausted).
  std::int64_t cells_unresolved = 0;
  bool budget_exhausted = false;
  /// Tetrahedra of the hypersurface J123 = 0 made by the marching 4-simplices, and triangles
  /// of the output.
  std::int64_t tetrahedra = 0, triangles = 0;
  /// Triangles dropped as lying on a cusp sheet (RankDeficientOptions::cusp_sine).
  std::int64_t triangles_at_cusps = 0;
  /// Triangles of lattice 2-faces at whose four corners the four minors vanish to rounding: the
  /// set lies in the lattice there (a generator symmetric about a dyadic parameter), where the
  /// marching sees only rounding errors' signs (docs/envelopes.md, "Rank-deficient sets on the
  /// lattice"). Counted before the cusp filter.
  std::int64_t lattice_face_triangles = 0;
  double seconds_subdivision = 0, seconds_marching = 0, seconds_mapping = 0, seconds_total = 0;
};

struct RankDeficientSurface {
  /// Part::SweepRankDeficient; positions s(u, v, w, t), parameters (u, v, w). Triangles are not
  /// consistently oriented (a surface in the 4-D domain has no outside).
  TriangleMesh mesh;
  /// t of every vertex, parallel to mesh.positions.
  std::vector<double> t;
  RankDeficientStats stats;
};

/// The rank-deficient set of a 4-variate map into R^3 (a swept solid). Deterministic: the same
/// input gives the same mesh whatever the number of threads (unless the budget runs out).
/// \throw InvalidInput if the map is not into R^3, options are out of range (tolerance not in
/// (0, 1], cusp_sine not in [0, 1], max_cells < 1, 2^15 or more finest cells along a
/// parameter), cone bounds are asked for a rational map, or J123 vanishes identically
/// ("generator is not a volume: its Jacobian vanishes identically").
RankDeficientSurface rank_deficient_surface(const BSplineHypervolume& map, const RankDeficientOptions& options = {});

}  // namespace volspline
