#pragma once
// Small closed meshes with known area and volume, built in code so tests need no data files.
// All are counter-clockwise seen from outside.
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline::test_support {

/// Connected components (triangles sharing a vertex) and the Euler characteristic V − E + F.
inline std::pair<int, long> components_and_euler(const TriangleMesh& mesh) {
  std::vector<int> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v)
      v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) parent[static_cast<std::size_t>(find(t[k]))] = find(t[0]);
  int components = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) components += find(static_cast<int>(v)) == static_cast<int>(v);
  const EdgeStatistics e = edge_statistics(mesh);
  return {components, static_cast<long>(mesh.num_vertices()) - static_cast<long>(e.edges) + static_cast<long>(mesh.num_triangles())};
}

/// The corners of the quad faces of the unit cube [0, 1]^3 (vertex x + 2y + 4z), one per part
/// 0..5 in the order u=min, u=max, v=min, v=max, w=min, w=max, counter-clockwise from outside.
inline constexpr std::array<std::array<int, 4>, 6> kCubeFaces = {{
    {0, 4, 6, 2},  // x = 0
    {1, 3, 7, 5},  // x = 1
    {0, 1, 5, 4},  // y = 0
    {2, 6, 7, 3},  // y = 1
    {0, 2, 3, 1},  // z = 0
    {4, 5, 7, 6},  // z = 1
}};

inline Eigen::Vector3d cube_corner(int i) {
  return {double(i & 1), double((i >> 1) & 1), double(i >> 2)};
}

/// The unit cube from 8 shared vertices and 12 triangles; parameters equal positions.
inline TriangleMesh unit_cube() {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.add_vertex(cube_corner(i), cube_corner(i));
  for (int part = 0; part < 6; ++part) {
    const auto& q = kCubeFaces[part];
    mesh.add_triangle(q[0], q[1], q[2], part);
    mesh.add_triangle(q[0], q[2], q[3], part);
  }
  return mesh;
}

/// The unit cube as 6 separate quads (24 vertices, nothing shared), the way a mesher that
/// handles one boundary face at a time produces it.
inline TriangleMesh unit_cube_as_separate_quads() {
  TriangleMesh mesh;
  for (int part = 0; part < 6; ++part) {
    const auto& q = kCubeFaces[part];
    std::array<int, 4> v{};
    for (int i = 0; i < 4; ++i) v[i] = mesh.add_vertex(cube_corner(q[i]), cube_corner(q[i]));
    mesh.add_triangle(v[0], v[1], v[2], part);
    mesh.add_triangle(v[0], v[2], v[3], part);
  }
  return mesh;
}

/// The tetrahedron with corners 0, e_x, e_y, e_z (volume 1/6), all faces part 0.
inline TriangleMesh unit_tetrahedron() {
  TriangleMesh mesh;
  const Eigen::Vector3d corners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& c : corners) mesh.add_vertex(c, c);
  mesh.add_triangle(0, 2, 1, 0);
  mesh.add_triangle(0, 1, 3, 0);
  mesh.add_triangle(0, 3, 2, 0);
  mesh.add_triangle(1, 2, 3, 0);
  return mesh;
}

/// A unit sphere approximated by an icosahedron subdivided `levels` times (20 * 4^levels
/// triangles). Each triangle's part is the cube face its centroid points at, as if the sphere
/// were a spline solid's boundary; parameters are the unit positions.
inline TriangleMesh icosphere(int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                         {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                         {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : points) p.normalize();
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoints;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = midpoints.try_emplace(key, static_cast<int>(points.size()));
      if (added) points.push_back((points[a] + points[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& f : faces) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  TriangleMesh mesh;
  for (const auto& p : points) mesh.add_vertex(p, p);
  for (const auto& f : faces) {
    const Eigen::Vector3d centroid = points[f[0]] + points[f[1]] + points[f[2]];
    Eigen::Index axis;
    centroid.cwiseAbs().maxCoeff(&axis);
    const int part = 2 * static_cast<int>(axis) + (centroid[axis] > 0 ? 1 : 0);
    mesh.add_triangle(f[0], f[1], f[2], part);
  }
  return mesh;
}

}  // namespace volspline::test_support
