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

#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct TetrahedralGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  /// Cubes per axis.
  std::array<int, 3> cells{0, 0, 0};
  /// (2 cells + 1) per axis values, x fastest; entries at edge midpoints are ignored.
  std::vector<double> values;
  /// One mesh part per cube (x fastest), or empty for part 6 everywhere.
  std::vector<std::int8_t> cube_parts;

  /// A grid of `cells` cubes with all values zero. \throw InvalidInput for a bad size.
  TetrahedralGrid(const Eigen::Vector3d& origin, double spacing, std::array<int, 3> cells);
  TetrahedralGrid() = default;

  std::array<int, 3> nodes() const { return {2 * cells[0] + 1, 2 * cells[1] + 1, 2 * cells[2] + 1}; }
  std::size_t node_index(int a, int b, int c) const {
    const auto n = nodes();
    return static_cast<std::size_t>(a) + n[0] * (static_cast<std::size_t>(b) + n[1] * static_cast<std::size_t>(c));
  }
  double& value(int a, int b, int c) { return values[node_index(a, b, c)]; }
  double value(int a, int b, int c) const { return values[node_index(a, b, c)]; }
  Eigen::Vector3d node_position(int a, int b, int c) const { return origin + 0.5 * spacing * Eigen::Vector3d(a, b, c); }

  /// Sets every face centre to the average of its 4 corners and every cube centre to the average
  /// of its 8 (the paper's control polyhedron, §7).
  void average_centres();
};

/// The zero set of the piecewise linear interpolant of the grid values on the tetrahedral
/// partition. Vertices are placed on sign-changing edges by linear interpolation (negative
/// means inside; a zero value counts as outside) and shared between all triangles using the
/// edge, so the mesh is welded by construction and closed wherever the zero set does not leave
/// the grid. Triangles are counter-clockwise seen from the positive side. Vertex parameters are
/// the positions. Non-finite values count as outside.
TriangleMesh march_tetrahedra(const TetrahedralGrid& grid);

}  // namespace volspline
