#pragma once
// Conforming longest-edge bisection of a tetrahedral mesh (Rivara): edges longer than a target
// are split at their midpoints, always the longest remaining one first, in every tetrahedron
// that contains it. Splitting an edge in all of its tetrahedra at once splits each face through
// it the same way from both sides, so the mesh stays conforming (face to face) by construction;
// taking the globally longest edge first makes every split the longest-edge bisection of each
// tetrahedron it cuts (up to ties), whose shapes stay bounded (Rivara 1984). Large tetrahedra
// are refined, small ones left alone: the local upsampling of Hua–He–Qin Fig. 13 used by
// extract/simplex_isosurface.h. Docs: docs/simplex-splines.md, "Isosurfaces".
#include <array>
#include <cstddef>
#include <vector>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

struct LongestEdgeBisectionOptions {
  /// Every edge of the result is at most this long (> 0).
  double target_edge = 0;
  /// The most tetrahedra the result may have (guards against a tiny target).
  std::size_t max_tetrahedra = 4'000'000;
};

struct LongestEdgeBisection {
  /// The original points first (same indices), then the edge midpoints; each tetrahedron
  /// positively oriented, like the input.
  TetrahedralMesh mesh;
  /// For each tetrahedron of `mesh`, the input tetrahedron it lies in.
  std::vector<int> parent;
  std::size_t bisections = 0;
};

/// \throw InvalidInput for a target that is not positive and finite, or when the result would
/// exceed max_tetrahedra. The input is assumed valid (validate_tetrahedral_mesh).
LongestEdgeBisection bisect_longest_edges(const TetrahedralMesh& mesh, const LongestEdgeBisectionOptions& options);

/// The length of the longest edge of the mesh.
double longest_edge_length(const TetrahedralMesh& mesh);

}  // namespace volspline
