#pragma once
// Questions one asks of a boundary mesh before trusting it as the surface of a solid: is it
// well formed, is it closed and consistently oriented, what area and volume does it bound.
// Welding lives here too because meshes assembled face by face only become closed once the
// copies of their shared vertices are merged.
#include <cstddef>

#include <vector>

#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// Checks the invariants every consumer of a TriangleMesh relies on: `parameters` and
/// `positions` have the same size, `parts` and `triangles` have the same size, every index is a
/// vertex, and positions and parameters are finite.
/// \throw InvalidInput naming the first offending vertex or triangle.
void validate_mesh(const TriangleMesh& mesh);

/// Counts of the undirected edges of a mesh, an edge being a pair of distinct vertex indices
/// (so coincident but unwelded vertices make separate edges; see weld_by_position).
struct EdgeStatistics {
  std::size_t edges = 0;
  /// Used by exactly one triangle.
  std::size_t boundary_edges = 0;
  /// Used by exactly two triangles.
  std::size_t manifold_edges = 0;
  /// Used by more than two triangles.
  std::size_t nonmanifold_edges = 0;
  /// Manifold edges whose two triangles traverse them in the same direction, so the triangles
  /// disagree about which side is outside.
  std::size_t inconsistently_oriented_edges = 0;

  /// Every edge is shared by exactly two triangles. A mesh without edges is not closed: it
  /// bounds nothing.
  bool closed() const { return edges > 0 && boundary_edges == 0 && nonmanifold_edges == 0; }
  /// Closed, and every edge is traversed once in each direction.
  bool closed_and_oriented() const { return closed() && inconsistently_oriented_edges == 0; }
};

/// Edge counts of `mesh`. The degenerate edge of a triangle with a repeated index is ignored.
/// \throw InvalidInput if the mesh is malformed (validate_mesh).
EdgeStatistics edge_statistics(const TriangleMesh& mesh);

/// Vertices whose triangles do not form one fan (one disk or half-disk around the vertex): two
/// cones touching at their apexes, or a triangle with the vertex twice. A closed, consistently
/// oriented mesh without such vertices is a 2-manifold surface, which CGAL's polygon mesh
/// structures take as it is (no orienting or vertex splitting first).
/// \throw InvalidInput if the mesh is malformed (validate_mesh).
std::size_t nonmanifold_vertices(const TriangleMesh& mesh);

/// For each vertex, the earliest vertex whose position lies within `tolerance` of it among those
/// kept so far (itself if none): the merge map weld_by_position applies, for callers that must
/// keep the vertices apart but need to know which coincide (seams of periodic
/// parameterisations). \throw as weld_by_position.
std::vector<int> coincident_vertices(const TriangleMesh& mesh, double tolerance);

/// Merges vertices whose positions lie within `tolerance` (Euclidean) of an earlier kept vertex;
/// the merged vertex keeps the position and parameters of the first one. Triangles that end up
/// with a repeated index are dropped, and vertices no triangle uses are removed. Merging is
/// greedy in vertex order, so a chain of points each within tolerance of the next is not
/// collapsed into one. `tolerance == 0` merges exactly equal positions only.
/// \throw InvalidInput if `tolerance` is negative or not finite, or the mesh is malformed.
void weld_by_position(TriangleMesh& mesh, double tolerance);

/// Sum of the triangle areas.
double surface_area(const TriangleMesh& mesh);

/// Signed volume enclosed by the mesh by the divergence theorem: positive when the triangles are
/// counter-clockwise seen from outside. Meaningful only for a closed mesh; for an open one the
/// value depends on the (unspecified) reference point.
double enclosed_volume(const TriangleMesh& mesh);

}  // namespace volspline
