#include "volspline/mesh/mesh_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "volspline/core/bucket_sort.h"
#include "volspline/core/error.h"

namespace volspline {

namespace {

bool is_finite(const Eigen::Vector3d& p) { return p.allFinite(); }

std::string triangle_where(std::size_t t) { return "triangles[" + std::to_string(t) + "]"; }

// A directed edge packed so that sorting groups the uses of one undirected edge together; the
// low bit records whether this use runs from the smaller to the larger index.
std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b)));
  const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b)));
  return (lo << 33) | (hi << 1) | (a < b ? 1u : 0u);
}

struct CellKey {
  std::int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};

struct CellHash {
  std::size_t operator()(const CellKey& k) const noexcept {
    // Large odd multipliers spread neighbouring cells over the table.
    std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// Reference point for volume integrals: the divergence theorem holds for any origin on a closed
// mesh, and one near the mesh keeps the triple products small, so far-from-origin meshes do not
// lose their volume to cancellation.
Eigen::Vector3d reference_point(const TriangleMesh& mesh) {
  const auto [lo, hi] = mesh.bounding_box();
  return 0.5 * (lo + hi);
}

}  // namespace

void validate_mesh(const TriangleMesh& mesh) {
  if (mesh.parameters.size() != mesh.positions.size()) {
    throw InvalidInput("mesh has " + std::to_string(mesh.positions.size()) + " positions but " +
                       std::to_string(mesh.parameters.size()) + " parameter triples");
  }
  if (mesh.parts.size() != mesh.triangles.size()) {
    throw InvalidInput("mesh has " + std::to_string(mesh.triangles.size()) + " triangles but " +
                       std::to_string(mesh.parts.size()) + " part tags");
  }
  // Indices are int, so more vertices than that cannot be addressed at all.
  if (mesh.positions.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw InvalidInput("mesh has more vertices than an int index can address");
  }
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!is_finite(mesh.positions[v]) || !is_finite(mesh.parameters[v])) {
      throw InvalidInput("vertex position or parameter is not finite",
                         "vertices[" + std::to_string(v) + "]");
    }
  }
  const auto n = static_cast<long long>(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const int index : mesh.triangles[t]) {
      if (index < 0 || index >= n) {
        throw InvalidInput(
            "vertex index " + std::to_string(index) + " is not in [0, " + std::to_string(n) + ")",
            triangle_where(t));
      }
    }
  }
}

EdgeStatistics edge_statistics(const TriangleMesh& mesh) {
  validate_mesh(mesh);
  std::vector<std::uint64_t> uses;
  uses.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i) {
      const int a = t[i], b = t[(i + 1) % 3];
      if (a != b) uses.push_back(edge_key(a, b));
    }
  }
  sort_keys_by_high_bits(uses, 33, mesh.num_vertices());

  EdgeStatistics stats;
  for (std::size_t begin = 0; begin < uses.size();) {
    std::size_t end = begin, forward = 0;
    while (end < uses.size() && (uses[end] >> 1) == (uses[begin] >> 1)) forward += uses[end++] & 1u;
    const std::size_t count = end - begin;
    ++stats.edges;
    if (count == 1) {
      ++stats.boundary_edges;
    } else if (count == 2) {
      ++stats.manifold_edges;
      if (forward != 1) ++stats.inconsistently_oriented_edges;
    } else {
      ++stats.nonmanifold_edges;
    }
    begin = end;
  }
  return stats;
}

std::size_t nonmanifold_vertices(const TriangleMesh& mesh) {
  validate_mesh(mesh);
  // Per vertex, the links of its triangles (the opposite edge of each); one fan exactly when
  // they connect all its neighbours (union-find over the neighbours).
  const std::size_t n = mesh.num_vertices();
  std::vector<std::size_t> start(n + 1, 0);
  std::vector<char> repeated(n, 0);
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      for (const int v : t) repeated[static_cast<std::size_t>(v)] = 1;
      continue;
    }
    for (const int v : t) ++start[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::array<int, 2>> link(start[n]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    for (int j = 0; j < 3; ++j) link[fill[static_cast<std::size_t>(t[j])]++] = {t[(j + 1) % 3], t[(j + 2) % 3]};
  }
  // Vertices in blocks in parallel, each block with its own buffers.
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 4096), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& block, std::size_t count) {
        std::vector<int> neighbours, parent;
        for (std::size_t v = block.begin(); v < block.end(); ++v) {
          if (repeated[v]) {
            ++count;
            continue;
          }
          if (start[v] == start[v + 1]) continue;
          neighbours.clear();
          for (std::size_t i = start[v]; i < start[v + 1]; ++i) neighbours.insert(neighbours.end(), link[i].begin(), link[i].end());
          std::sort(neighbours.begin(), neighbours.end());
          neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
          parent.resize(neighbours.size());
          std::iota(parent.begin(), parent.end(), 0);
          const auto local = [&](int w) { return static_cast<int>(std::lower_bound(neighbours.begin(), neighbours.end(), w) - neighbours.begin()); };
          const auto find = [&](int a) {
            while (parent[static_cast<std::size_t>(a)] != a) a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
            return a;
          };
          std::size_t components = neighbours.size();
          for (std::size_t i = start[v]; i < start[v + 1]; ++i) {
            const int a = find(local(link[i][0])), b = find(local(link[i][1]));
            if (a != b) {
              parent[static_cast<std::size_t>(a)] = b;
              --components;
            }
          }
          if (components != 1) ++count;
        }
        return count;
      },
      std::plus<>());
}

std::vector<int> coincident_vertices(const TriangleMesh& mesh, double tolerance) {
  if (!std::isfinite(tolerance) || tolerance < 0) {
    throw InvalidInput("weld tolerance must be finite and >= 0, got " + std::to_string(tolerance));
  }
  validate_mesh(mesh);

  // Cells at least `tolerance` wide put every partner of a point in its own or an adjacent cell.
  // They are also at least 2^-40 of the largest coordinate, so cell indices fit comfortably in
  // 64 bits even for tolerance 0 (exact equality still lands in the same cell).
  double largest = 0;
  for (const auto& p : mesh.positions) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  const double cell = std::max({tolerance, std::ldexp(largest, -40), 1e-300});
  const auto cell_of = [cell](const Eigen::Vector3d& p) {
    return CellKey{static_cast<std::int64_t>(std::floor(p.x() / cell)),
                   static_cast<std::int64_t>(std::floor(p.y() / cell)),
                   static_cast<std::int64_t>(std::floor(p.z() / cell))};
  };

  const double tolerance2 = tolerance * tolerance;
  std::unordered_map<CellKey, std::vector<int>, CellHash> grid;
  grid.reserve(mesh.positions.size());
  std::vector<int> representative(mesh.positions.size());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Eigen::Vector3d& p = mesh.positions[v];
    const CellKey home = cell_of(p);
    int found = -1;
    // Prefer the earliest kept vertex among all candidates so the result does not depend on the
    // order in which neighbouring cells are visited.
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({home.x + dx, home.y + dy, home.z + dz});
          if (it == grid.end()) continue;
          for (const int kept : it->second) {
            if ((found < 0 || kept < found) &&
                (mesh.positions[kept] - p).squaredNorm() <= tolerance2) {
              found = kept;
            }
          }
        }
      }
    }
    if (found < 0) {
      found = static_cast<int>(v);
      grid[home].push_back(found);
    }
    representative[v] = found;
  }
  return representative;
}

void weld_by_position(TriangleMesh& mesh, double tolerance) {
  const std::vector<int> representative = coincident_vertices(mesh, tolerance);

  // Kept vertices retain their relative order, so the first vertex of the input stays first.
  std::vector<char> used(mesh.positions.size(), 0);
  std::vector<std::size_t> surviving;
  surviving.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const int a = representative[tri[0]], b = representative[tri[1]], c = representative[tri[2]];
    if (a == b || b == c || c == a) continue;
    used[a] = used[b] = used[c] = 1;
    surviving.push_back(t);
  }
  TriangleMesh welded;
  std::vector<int> new_index(mesh.positions.size(), -1);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (used[v]) new_index[v] = welded.add_vertex(mesh.positions[v], mesh.parameters[v]);
  }
  welded.triangles.reserve(surviving.size());
  welded.parts.reserve(surviving.size());
  for (const std::size_t t : surviving) {
    const auto& tri = mesh.triangles[t];
    welded.add_triangle(new_index[representative[tri[0]]], new_index[representative[tri[1]]],
                        new_index[representative[tri[2]]], mesh.parts[t]);
  }
  mesh = std::move(welded);
}

double surface_area(const TriangleMesh& mesh) {
  validate_mesh(mesh);
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    area += 0.5 * (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm();
  }
  return area;
}

double enclosed_volume(const TriangleMesh& mesh) {
  validate_mesh(mesh);
  const Eigen::Vector3d origin = reference_point(mesh);
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.positions[t[0]] - origin;
    const Eigen::Vector3d b = mesh.positions[t[1]] - origin;
    const Eigen::Vector3d c = mesh.positions[t[2]] - origin;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

}  // namespace volspline
