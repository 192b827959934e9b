#include "volspline/boxspline/lattice_isosurface.h"

#include <cmath>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "volspline/core/error.h"

namespace volspline {

TetrahedralGrid::TetrahedralGrid(const Eigen::Vector3d& o, double h, std::array<int, 3> n) : origin(o), spacing(h), cells(n) {
  if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInput("expected a positive, finite grid spacing");
  std::size_t total = 1;
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1) throw InvalidInput("expected at least one cube per axis, got " + std::to_string(n[d]));
    total *= static_cast<std::size_t>(2 * n[d] + 1);
    if (total > (std::size_t{1} << 27)) throw InvalidInput("expected a grid of at most 2^27 nodes (use fewer levels or a smaller region)");
  }
  values.assign(total, 0.0);
}

void TetrahedralGrid::average_centres() {
  for (int c = 0; c < cells[2]; ++c)
    for (int b = 0; b < cells[1]; ++b)
      for (int a = 0; a < cells[0]; ++a) {
        const int x = 2 * a, y = 2 * b, z = 2 * c;
        double corner[2][2][2];
        double sum = 0.0;
        for (int k = 0; k < 2; ++k)
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) sum += corner[i][j][k] = value(x + 2 * i, y + 2 * j, z + 2 * k);
        value(x + 1, y + 1, z + 1) = sum / 8.0;
        // The faces at the lower side of each axis; the upper ones belong to the next cube or,
        // at the end of the grid, are done here too.
        for (int s = 0; s < 2; ++s) {
          if (s == 1 && a + 1 < cells[0]) continue;
          value(x + 2 * s, y + 1, z + 1) = (corner[s][0][0] + corner[s][1][0] + corner[s][0][1] + corner[s][1][1]) / 4.0;
        }
        for (int s = 0; s < 2; ++s) {
          if (s == 1 && b + 1 < cells[1]) continue;
          value(x + 1, y + 2 * s, z + 1) = (corner[0][s][0] + corner[1][s][0] + corner[0][s][1] + corner[1][s][1]) / 4.0;
        }
        for (int s = 0; s < 2; ++s) {
          if (s == 1 && c + 1 < cells[2]) continue;
          value(x + 1, y + 1, z + 2 * s) = (corner[0][0][s] + corner[1][0][s] + corner[0][1][s] + corner[1][1][s]) / 4.0;
        }
      }
}

namespace {

/// The 24 tetrahedra of a cube as offsets on the doubled grid from the cube's lowest corner:
/// C the centre, F a face centre, A and B the ends of an edge of that face.
struct Tetrahedron {
  std::array<std::array<int, 3>, 4> vertex;
};

std::array<Tetrahedron, 24> cube_tetrahedra() {
  std::array<Tetrahedron, 24> out{};
  int n = 0;
  for (int i = 0; i < 3; ++i)
    for (int si = -1; si <= 1; si += 2)
      for (int jslot = 0; jslot < 2; ++jslot)
        for (int sj = -1; sj <= 1; sj += 2) {
          const int j = jslot == 0 ? (i + 1) % 3 : (i + 2) % 3, k = 3 - i - j;
          std::array<int, 3> c{1, 1, 1};
          std::array<int, 3> f = c;
          f[i] += si;
          std::array<int, 3> a = f, b = f;
          a[j] += sj, b[j] += sj;
          a[k] -= 1, b[k] += 1;
          out[n++].vertex = {c, f, a, b};
        }
  return out;
}

bool inside(double v) { return v < 0.0; }

}  // namespace

TriangleMesh march_tetrahedra(const TetrahedralGrid& grid) {
  static const std::array<Tetrahedron, 24> tetrahedra = cube_tetrahedra();
  TriangleMesh mesh;
  const auto nodes = grid.nodes();
  const std::uint64_t node_count = static_cast<std::uint64_t>(nodes[0]) * nodes[1] * nodes[2];
  std::unordered_map<std::uint64_t, int> edge_vertex;
  edge_vertex.reserve(1024);


  for (int c = 0; c < grid.cells[2]; ++c)
    for (int b = 0; b < grid.cells[1]; ++b)
      for (int a = 0; a < grid.cells[0]; ++a) {
        const int x = 2 * a, y = 2 * b, z = 2 * c;
        // Skip cubes whose 15 partition vertices share one sign.
        int negatives = 0;
        for (int k = 0; k <= 2; ++k)
          for (int j = 0; j <= 2; ++j)
            for (int i = 0; i <= 2; ++i) {
              const int odd = (i & 1) + (j & 1) + (k & 1);
              if (odd == 1) continue;
              negatives += inside(grid.value(x + i, y + j, z + k));
            }
        if (negatives == 0 || negatives == 15) continue;
        const int part = grid.cube_parts.empty()
                             ? 6
                             : grid.cube_parts[static_cast<std::size_t>(a) +
                                               grid.cells[0] * (static_cast<std::size_t>(b) + grid.cells[1] * static_cast<std::size_t>(c))];
        for (const Tetrahedron& tet : tetrahedra) {
          std::size_t id[4];
          double v[4];
          Eigen::Vector3d p[4];
          int in = 0;
          for (int q = 0; q < 4; ++q) {
            const auto& o = tet.vertex[q];
            id[q] = grid.node_index(x + o[0], y + o[1], z + o[2]);
            v[q] = grid.values[id[q]];
            if (!std::isfinite(v[q])) v[q] = 1.0;
            p[q] = grid.node_position(x + o[0], y + o[1], z + o[2]);
            in += inside(v[q]);
          }
          if (in == 0 || in == 4) continue;
          const auto edge = [&](int q0, int q1) {
            std::size_t n0 = id[q0], n1 = id[q1];
            int r0 = q0, r1 = q1;
            if (n0 > n1) std::swap(n0, n1), std::swap(r0, r1);
            const std::uint64_t key = static_cast<std::uint64_t>(n0) * node_count + n1;
            const auto [it, added] = edge_vertex.try_emplace(key, 0);
            if (added) {
              const double t = v[r0] / (v[r0] - v[r1]);
              const Eigen::Vector3d position = p[r0] + t * (p[r1] - p[r0]);
              it->second = mesh.add_vertex(position, position);
            }
            return it->second;
          };
          // A positive vertex orients each triangle: its normal points towards it.
          int outside_vertex = 0;
          while (inside(v[outside_vertex])) ++outside_vertex;
          const auto emit = [&](int i0, int i1, int i2) {
            const Eigen::Vector3d& a0 = mesh.positions[static_cast<std::size_t>(i0)];
            const Eigen::Vector3d n = (mesh.positions[static_cast<std::size_t>(i1)] - a0).cross(mesh.positions[static_cast<std::size_t>(i2)] - a0);
            if (n.dot(p[outside_vertex] - a0) >= 0.0) mesh.add_triangle(i0, i1, i2, part);
            else mesh.add_triangle(i0, i2, i1, part);
          };
          int ins[4], outs[4], ni = 0, no = 0;
          for (int q = 0; q < 4; ++q) (inside(v[q]) ? ins[ni++] : outs[no++]) = q;
          if (ni == 1 || no == 1) {
            const int lone = ni == 1 ? ins[0] : outs[0];
            const int* others = ni == 1 ? outs : ins;
            emit(edge(lone, others[0]), edge(lone, others[1]), edge(lone, others[2]));
          } else {
            // Two inside (i0, i1), two outside (o0, o1): the quadrilateral i0o0, i0o1, i1o1, i1o0.
            const int e0 = edge(ins[0], outs[0]), e1 = edge(ins[0], outs[1]), e2 = edge(ins[1], outs[1]),
                      e3 = edge(ins[1], outs[0]);
            emit(e0, e1, e2);
            emit(e0, e2, e3);
          }
        }
      }
  return mesh;
}

}  // namespace volspline
