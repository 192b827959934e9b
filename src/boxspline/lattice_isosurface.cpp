#include "volspline/boxspline/lattice_isosurface.h"

#include <cmath>
#include <string>

#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"

namespace volspline {

TetrahedralGrid::TetrahedralGrid(const Eigen::Vector3d& o, double h, std::array<int, 3> n, Layout l)
    : layout(l), origin(o), spacing(h), cells(n) {
  if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInput("expected a positive, finite grid spacing");
  std::size_t total = 1;
  for (int d = 0; d < 3; ++d) {
    if (n[d] < 1) throw InvalidInput("expected at least one cube per axis, got " + std::to_string(n[d]));
    total *= static_cast<std::size_t>(l == Layout::AllNodes ? 2 * n[d] + 1 : n[d] + 1);
    if (total > (std::size_t{1} << 27))
      throw InvalidInput("expected a grid of at most 2^27 nodes (use fewer levels or a smaller region)");
  }
  values.assign(total, 0.0);
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
  const std::size_t cubes = static_cast<std::size_t>(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  if (!grid.cube_parts.empty() && grid.cube_parts.size() != cubes) {
    throw InvalidInput("expected one part per cube (" + std::to_string(cubes) + "), got " + std::to_string(grid.cube_parts.size()));
  }
  std::size_t expected_values = 1;
  for (int d = 0; d < 3; ++d) {
    expected_values *= static_cast<std::size_t>(grid.layout == TetrahedralGrid::Layout::AllNodes ? 2 * grid.cells[d] + 1 : grid.cells[d] + 1);
  }
  if (grid.values.size() != expected_values) {
    throw InvalidInput("expected " + std::to_string(expected_values) + " grid values for the layout, got " + std::to_string(grid.values.size()));
  }
  static const std::array<Tetrahedron, 24> tetrahedra = cube_tetrahedra();
  // Surface vertices are made once per partition edge, keyed by the doubled-grid node indices
  // of its ends (mesh/marching_tetrahedra.h), so the mesh is welded by construction.
  MarchingTetrahedra marching;
  const std::size_t expected = 8 * (static_cast<std::size_t>(grid.cells[0]) * grid.cells[1] +
                                    static_cast<std::size_t>(grid.cells[1]) * grid.cells[2] +
                                    static_cast<std::size_t>(grid.cells[0]) * grid.cells[2]);
  marching.reserve(expected, 2 * expected);
  std::vector<int> parts;
  parts.reserve(2 * expected);

  for (int c = 0; c < grid.cells[2]; ++c)
    for (int b = 0; b < grid.cells[1]; ++b)
      for (int a = 0; a < grid.cells[0]; ++a) {
        const int x = 2 * a, y = 2 * b, z = 2 * c;
        // The 27 doubled-grid values of the cube (edge midpoints unused). Skip cubes whose
        // partition vertices share one sign.
        double local[3][3][3];
        int negatives = 0;
        if (grid.layout == TetrahedralGrid::Layout::CornersAveraged) {
          double sum = 0.0;
          for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 2; ++j)
              for (int i = 0; i < 2; ++i) {
                const double v = grid.corner(a + i, b + j, c + k);
                local[2 * i][2 * j][2 * k] = v;
                negatives += inside(v);
                sum += v;
              }
          // Averages of values of one sign keep that sign.
          if (negatives == 0 || negatives == 8) continue;
          local[1][1][1] = sum / 8.0;
          for (int s = 0; s <= 2; s += 2) {
            local[s][1][1] = (local[s][0][0] + local[s][2][0] + local[s][0][2] + local[s][2][2]) / 4.0;
            local[1][s][1] = (local[0][s][0] + local[2][s][0] + local[0][s][2] + local[2][s][2]) / 4.0;
            local[1][1][s] = (local[0][0][s] + local[2][0][s] + local[0][2][s] + local[2][2][s]) / 4.0;
          }
        } else {
          for (int k = 0; k <= 2; ++k)
            for (int j = 0; j <= 2; ++j)
              for (int i = 0; i <= 2; ++i) {
                if ((i & 1) + (j & 1) + (k & 1) == 1) continue;
                local[i][j][k] = grid.value(x + i, y + j, z + k);
                negatives += inside(local[i][j][k]);
              }
          if (negatives == 0 || negatives == 15) continue;
        }
        const Part part = grid.cube_parts.empty()
                              ? Part::BlendSpline
                              : grid.cube_parts[static_cast<std::size_t>(a) +
                                               grid.cells[0] * (static_cast<std::size_t>(b) + grid.cells[1] * static_cast<std::size_t>(c))];
        for (const Tetrahedron& tet : tetrahedra) {
          double v[4];
          int in = 0;
          for (int q = 0; q < 4; ++q) {
            const auto& o = tet.vertex[static_cast<std::size_t>(q)];
            v[q] = local[o[0]][o[1]][o[2]];
            if (!std::isfinite(v[q])) v[q] = 1.0;  // non-finite values count as outside
            in += inside(v[q]);
          }
          if (in == 0 || in == 4) continue;
          std::array<MarchingTetrahedra::Sample, 4> samples;
          for (int q = 0; q < 4; ++q) {
            const auto& o = tet.vertex[static_cast<std::size_t>(q)];
            samples[static_cast<std::size_t>(q)] = {static_cast<std::int64_t>(grid.node_index(x + o[0], y + o[1], z + o[2])),
                                                    grid.node_position(x + o[0], y + o[1], z + o[2]), v[q]};
          }
          marching.add_tetrahedron_oriented_by_corners(samples);
        }
        parts.resize(marching.triangles().size(), part_number(part));
      }

  TriangleMesh mesh;
  mesh.positions = marching.vertices();
  mesh.parameters = mesh.positions;
  mesh.triangles = marching.triangles();
  mesh.parts = std::move(parts);
  return mesh;
}

}  // namespace volspline
