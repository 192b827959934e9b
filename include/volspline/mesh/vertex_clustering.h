#pragma once
// Fewer triangles for display: vertex clustering (Rossignac and Borrel 1993, "Multi-resolution 3D
// approximations for rendering complex scenes"). Space is cut into cubes; the vertices in one cube
// become one vertex at their mean; triangles whose corners fall into fewer than three cubes
// vanish. Parts (TriangleMesh::parts) are kept per triangle, so their seams stay where they were
// to within a cube. The result is an approximation for looking at (an interactive page,
// web/interactive_page.h), not for computing with: small features and holes below the cube size
// close, and manifoldness is not kept.
#include <cstddef>
#include <vector>

#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct ClusteredMesh {
  TriangleMesh mesh;
  /// For every vertex of the input, the vertex of `mesh` it became.
  std::vector<int> cluster_of_vertex;
  /// The edge of the cubes (0: the input was returned unchanged).
  double cell_size = 0;
};

/// Clusters the vertices of `mesh` in cubes of edge `cell_size` anchored at the minimum of its
/// bounding box. Triangles keep their orientation and part; two triangles of the same part on the
/// same three clusters become one. Parameters are averaged like positions.
/// \throw InvalidInput if cell_size is not finite and > 0.
ClusteredMesh cluster_vertices(const TriangleMesh& mesh, double cell_size);

/// `mesh` itself if it has at most `max_triangles` triangles; otherwise cluster_vertices with the
/// smallest cube (down a geometric sequence from the mean edge length, factor 1.25) whose result
/// has at most that many.
/// \throw InvalidInput if max_triangles is 0.
ClusteredMesh reduce_to_triangle_budget(const TriangleMesh& mesh, std::size_t max_triangles);

}  // namespace volspline
