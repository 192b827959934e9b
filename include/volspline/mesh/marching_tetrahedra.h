#pragma once
// The zero set of a function sampled at the vertices of tetrahedra, linear on each tetrahedron
// (marching tetrahedra: no ambiguous cases, Joy–Duchaineau §7, Fig. 6).
//
// Sample points are named by integer ids; the same id must always carry the same point and
// value. A surface vertex is made once per tetrahedron edge (keyed by the ids of its two ends,
// interpolated from the lower id's end), so two tetrahedra that share a face produce the same
// surface edge on it: the surface of a conforming tetrahedral mesh has no cracks.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// The six Kuhn tetrahedra of the unit cube: 000 -> e_p0 -> e_p0 + e_p1 -> 111 for each
/// permutation p of the axes (corner c of the cube: bit 0 x, bit 1 y, bit 2 z). All share the
/// diagonal 0-7, so cubes of a grid split their shared faces alike and marching tetrahedra on
/// them leaves no cracks.
inline constexpr std::array<std::array<int, 4>, 6> kKuhnTetrahedra{{
    {0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7},
}};

class MarchingTetrahedra {
 public:
  struct Sample {
    std::int64_t id;
    Eigen::Vector3d point;
    double value;
  };

  /// Adds the part of the zero set inside one tetrahedron: nothing, one triangle or two. Values
  /// >= 0 count as positive. Triangles are oriented so that their normal (counter-clockwise)
  /// points towards the positive side.
  void add_tetrahedron(const std::array<Sample, 4>& tetrahedron);

  /// As add_tetrahedron, but each triangle is oriented from the tetrahedron's corners (which of
  /// them are positive, and the sign of its volume), not from the triangle's own normal. The two
  /// agree on triangles of positive area. Where a sample value is exactly 0, surface vertices
  /// coincide with that sample and triangles of zero area appear; add_tetrahedron orients those
  /// arbitrarily (the mesh is then closed but not consistently oriented), this orients them like
  /// their neighbours (as if the 0 were a tiny positive value).
  void add_tetrahedron_oriented_by_corners(const std::array<Sample, 4>& tetrahedron);

  /// Room for this many surface vertices and triangles (saves rehashing on large grids).
  void reserve(std::size_t vertices, std::size_t triangles);

  /// Surface vertices (points of the sampled space) and, for each, the ids of the two samples of
  /// its edge (lower id first).
  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  const std::vector<std::array<std::int64_t, 2>>& vertex_edges() const { return vertex_edges_; }
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

  /// Moves a surface vertex (for example onto the exact zero set); edges keep their keys.
  void set_vertex(int index, const Eigen::Vector3d& point) { vertices_[static_cast<std::size_t>(index)] = point; }

 private:
  int edge_vertex(const Sample& a, const Sample& b);
  void emit(int a, int b, int c, const Eigen::Vector3d& toward_positive);

  struct EdgeHash {
    std::size_t operator()(const std::array<std::int64_t, 2>& e) const {
      return static_cast<std::size_t>(e[0] * 0x9E3779B97F4A7C15ULL ^ (e[1] + 0x7F4A7C159E3779B9ULL + (e[0] << 6)));
    }
  };
  std::unordered_map<std::array<std::int64_t, 2>, int, EdgeHash> edge_vertices_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<std::int64_t, 2>> vertex_edges_;
  std::vector<std::array<int, 3>> triangles_;
};

}  // namespace volspline
