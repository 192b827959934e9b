#pragma once
// Tetrahedral domains made in code for the tests of mesh/tetrahedral_* and simplex/, and the
// check of a boundary as a closed surface. No GoogleTest here, so benchmarks can include it.
#include <cstdint>
#include <filesystem>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/mesh/tetrahedral_mesh.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline::test_support {

/// The unit cube [0, 1]^3 as the six Kuhn tetrahedra around the diagonal (0,0,0)-(1,1,1),
/// corner i at (i & 1, (i >> 1) & 1, (i >> 2) & 1), positively oriented (tetrahedron 0 is
/// (0, 1, 3, 7)).
inline TetrahedralMesh kuhn_cube() {
  TetrahedralMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Paths 0 -> 7 through the cube's edges, one per permutation of the axes.
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& order : axes) {
    std::array<int, 4> t{0, 0, 0, 0};
    for (int k = 0; k < 3; ++k) t[k + 1] = t[k] | (1 << order[k]);
    mesh.tetrahedra.push_back(t);
  }
  orient_positively(mesh);
  return mesh;
}

/// The points of an m x m x m grid on [0, 1]^3, each moved by up to `jitter` times the
/// spacing in every coordinate (a fixed seed), boundary points kept on the cube's faces.
inline std::vector<Eigen::Vector3d> cube_grid_points(int m, double jitter, std::uint32_t seed = 7) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<Eigen::Vector3d> points;
  const double h = 1.0 / (m - 1);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int index[3] = {i, j, k};
        Eigen::Vector3d p;
        for (int c = 0; c < 3; ++c) {
          const double moved = index[c] * h + offset(random) * h;
          p[c] = (index[c] == 0 || index[c] == m - 1) ? index[c] * h : moved;
        }
        points.push_back(p);
      }
  return points;
}

/// The Delaunay tetrahedralisation of cube_grid_points: a cube domain with interior, face,
/// edge and corner vertices.
inline TetrahedralMesh delaunay_cube(int m, double jitter = 0.2) {
  return delaunay_tetrahedralization(cube_grid_points(m, jitter));
}

/// The boundary faces of `mesh` as a triangle mesh on all of its points (parameters zero,
/// part 0), for the closedness and area checks of mesh/mesh_checks.h.
inline TriangleMesh boundary_surface(const TetrahedralMesh& mesh) {
  TriangleMesh surface;
  for (const auto& p : mesh.points) surface.add_vertex(p, Eigen::Vector3d::Zero());
  for (const auto& f : boundary_faces(mesh)) surface.add_triangle(f.vertices[0], f.vertices[1], f.vertices[2], 0);
  return surface;
}

#ifdef VOLSPLINE_SOURCE_DIR
/// ../shared/data/volumes/ seen from the source tree, where tests find real data (tests only:
/// benchmarks have no source directory compiled in).
inline std::filesystem::path shared_volume_data() {
  return std::filesystem::path(VOLSPLINE_SOURCE_DIR).parent_path() / "shared" / "data" / "volumes";
}
#endif

}  // namespace volspline::test_support
