#pragma once
// A triangle mesh that remembers where each vertex came from in parameter space and which part
// of a solid's boundary each triangle belongs to (parts: see core/conventions.h).
#include <array>
#include <vector>

#include <Eigen/Core>

namespace volspline {

struct TriangleMesh {
  /// #V vertex positions.
  std::vector<Eigen::Vector3d> positions;
  /// #V parameter triples (u, v, w) of the vertices; same size as positions.
  std::vector<Eigen::Vector3d> parameters;
  /// #F triangles, counter-clockwise seen from outside where the producer knows the outside.
  std::vector<std::array<int, 3>> triangles;
  /// #F part tags (0..5 the faces u=min..w=max, 6 the implicit surface).
  std::vector<int> parts;

  int add_vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& parameter);
  void add_triangle(int a, int b, int c, int part);
  /// Appends `other`, renumbering its vertices.
  void append(const TriangleMesh& other);
  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  /// Axis-aligned box of the vertex positions (min, max); both zero for an empty mesh.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> bounding_box() const;
};

}  // namespace volspline
