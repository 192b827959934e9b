#pragma once
// Marching tetrahedra on the tetrahedral partition of a regular grid of cubes (Peters & Wittman
// 1995, §3.2 and §7): every cube is cut into 24 tetrahedra (cube centre, face centre, the two
// ends of one edge of that face), the same partition the 7-direction box spline lives on. A
// tetrahedron decides the connectivity of its zero sheet uniquely (no marching-cubes
// ambiguity): no triangle, one triangle, or a quadrilateral as two triangles.
//
// Values live on the "doubled" grid: node (a, b, c) is the point origin + (spacing/2)(a, b, c);
// corners have three even coordinates, face centres one even, cube centres none. Edge midpoints
// (one odd coordinate) are not used.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/parts.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct TetrahedralGrid {
  /// What `values` holds: every partition vertex of the doubled grid, or the cube corners only,
  /// face and cube centres then being the averages of their 4 and 8 corners (the paper's control
  /// polyhedron, §7), computed on the fly.
  enum class Layout { AllNodes, CornersAveraged };
  Layout layout = Layout::AllNodes;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  /// Cubes per axis.
  std::array<int, 3> cells{0, 0, 0};
  /// AllNodes: (2 cells + 1) per axis values, x fastest, entries at edge midpoints ignored.
  /// CornersAveraged: (cells + 1) per axis corner values, x fastest.
  std::vector<double> values;
  /// The mesh part of each cube's triangles (x fastest), or empty for Part::BlendSpline
  /// everywhere (mesh/parts.h).
  std::vector<Part> cube_parts;

  /// A grid of `cells` cubes with all values zero. \throw InvalidInput if the spacing is not
  /// positive and finite, an axis has no cube, or `values` would hold more than 2^27 numbers.
  TetrahedralGrid(const Eigen::Vector3d& origin, double spacing, std::array<int, 3> cells, Layout layout = Layout::AllNodes);
  TetrahedralGrid() = default;

  std::array<int, 3> nodes() const { return {2 * cells[0] + 1, 2 * cells[1] + 1, 2 * cells[2] + 1}; }
  std::size_t node_index(int a, int b, int c) const {
    const auto n = nodes();
    return static_cast<std::size_t>(a) + n[0] * (static_cast<std::size_t>(b) + n[1] * static_cast<std::size_t>(c));
  }
  /// AllNodes layout: the value at doubled-grid node (a, b, c).
  double& value(int a, int b, int c) { return values[node_index(a, b, c)]; }
  double value(int a, int b, int c) const { return values[node_index(a, b, c)]; }
  /// CornersAveraged layout: the value at corner (i, j, k) = doubled node (2i, 2j, 2k).
  double& corner(int i, int j, int k) {
    return values[static_cast<std::size_t>(i) + (cells[0] + 1) * (static_cast<std::size_t>(j) + (cells[1] + 1) * static_cast<std::size_t>(k))];
  }
  double corner(int i, int j, int k) const { return const_cast<TetrahedralGrid*>(this)->corner(i, j, k); }
  Eigen::Vector3d node_position(int a, int b, int c) const { return origin + 0.5 * spacing * Eigen::Vector3d(a, b, c); }
};

/// The zero set of the piecewise linear interpolant of the grid values on the tetrahedral
/// partition, by the project's marching tetrahedra (mesh/marching_tetrahedra.h) with the
/// doubled-grid node indices as sample ids. Vertices are placed on sign-changing edges by linear
/// interpolation (negative means inside; a zero value counts as outside) and shared between all
/// triangles using the edge, so the mesh is welded by construction and closed wherever the zero
/// set does not leave the grid. Triangles are counter-clockwise seen from the positive side.
/// Vertex parameters are the positions; each triangle gets its cube's part. Non-finite values
/// count as outside.
/// \throw InvalidInput if cube_parts is neither empty nor one per cube, or `values` does not
/// have the size of the layout.
TriangleMesh march_tetrahedra(const TetrahedralGrid& grid);

}  // namespace volspline
