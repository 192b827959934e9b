#pragma once
// A triangle mesh that remembers where each vertex came from in parameter space and which part
// of a solid's boundary each triangle belongs to. No member throws except std::bad_alloc; the
// checks of a mesh's consistency are mesh/mesh_checks.h.
#include <array>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/parts.h"

namespace volspline {

struct TriangleMesh {
  /// #V vertex positions.
  std::vector<Eigen::Vector3d> positions;
  /// #V parameter triples (u, v, w) of the vertices; same size as positions.
  std::vector<Eigen::Vector3d> parameters;
  /// #F triangles, counter-clockwise seen from outside where the producer knows the outside.
  std::vector<std::array<int, 3>> triangles;
  /// #F part numbers, one per triangle: the numbers of the part table (mesh/parts.h), or any
  /// number a mesh file carried.
  std::vector<int> parts;

  /// Appends a vertex; returns its index.
  int add_vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& parameter);
  /// Appends the triangle (a, b, c) of part number `part`; indices are not checked here.
  void add_triangle(int a, int b, int c, int part);
  void add_triangle(int a, int b, int c, Part part) { add_triangle(a, b, c, part_number(part)); }
  /// Appends `other`, renumbering its vertices.
  void append(const TriangleMesh& other);
  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  /// Axis-aligned box of the vertex positions (min, max); both zero for an empty mesh.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounding_box() const;
};

/// The triangles of part number `part` with the vertices they use (in their first order), e.g.
/// the box-spline surface of a blend alone (Peters & Wittman Fig. 4b).
TriangleMesh triangles_of_part(const TriangleMesh& mesh, int part);
inline TriangleMesh triangles_of_part(const TriangleMesh& mesh, Part part) { return triangles_of_part(mesh, part_number(part)); }

}  // namespace volspline
