#include "volspline/mesh/vertex_clustering.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <tuple>
#include <unordered_map>

#include "volspline/core/error.h"

namespace volspline {

namespace {

struct ClusterCellHash {
  std::size_t operator()(const std::array<long long, 3>& c) const {
    return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
  }
};

}  // namespace

ClusteredMesh cluster_vertices(const TriangleMesh& mesh, double cell_size) {
  if (!(cell_size > 0) || !std::isfinite(cell_size))
    throw InvalidInput("expected a finite cube size > 0 for vertex clustering, got " + std::to_string(cell_size));
  ClusteredMesh out;
  out.cell_size = cell_size;
  const Eigen::Vector3d origin = mesh.bounding_box().first;
  std::unordered_map<std::array<long long, 3>, int, ClusterCellHash> cluster_of_cell;
  std::vector<int> members;
  out.cluster_of_vertex.resize(mesh.num_vertices());
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d q = (mesh.positions[v] - origin) / cell_size;
    const std::array<long long, 3> cell{static_cast<long long>(std::floor(q.x())), static_cast<long long>(std::floor(q.y())),
                                        static_cast<long long>(std::floor(q.z()))};
    const auto [it, added] = cluster_of_cell.try_emplace(cell, static_cast<int>(out.mesh.num_vertices()));
    if (added) {
      out.mesh.add_vertex(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      members.push_back(0);
    }
    const auto c = static_cast<std::size_t>(it->second);
    out.mesh.positions[c] += mesh.positions[v];
    out.mesh.parameters[c] += mesh.parameters[v];
    ++members[c];
    out.cluster_of_vertex[v] = it->second;
  }
  for (std::size_t c = 0; c < members.size(); ++c) {
    out.mesh.positions[c] /= members[c];
    out.mesh.parameters[c] /= members[c];
  }
  std::set<std::tuple<int, int, int, int>> kept;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[static_cast<std::size_t>(k)] = out.cluster_of_vertex[static_cast<std::size_t>(mesh.triangles[t][static_cast<std::size_t>(k)])];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    std::array<int, 3> sorted = c;
    std::sort(sorted.begin(), sorted.end());
    if (!kept.emplace(sorted[0], sorted[1], sorted[2], mesh.parts[t]).second) continue;
    out.mesh.add_triangle(c[0], c[1], c[2], mesh.parts[t]);
  }
  return out;
}

ClusteredMesh reduce_to_triangle_budget(const TriangleMesh& mesh, std::size_t max_triangles) {
  if (max_triangles == 0) throw InvalidInput("expected a triangle budget > 0");
  if (mesh.num_triangles() <= max_triangles) {
    ClusteredMesh same{mesh, std::vector<int>(mesh.num_vertices()), 0};
    std::iota(same.cluster_of_vertex.begin(), same.cluster_of_vertex.end(), 0);
    return same;
  }
  double edges = 0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      edges += (mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])] -
                mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])])
                   .norm();
  const auto [lo, hi] = mesh.bounding_box();
  // A cube of the mean edge keeps about as many triangles as there are; the number falls with the
  // square of the cube's edge on a surface, so the first fitting size is soon found.
  double cell = std::max(edges / (3.0 * static_cast<double>(mesh.num_triangles())), 1e-12 * std::max((hi - lo).norm(), 1e-300));
  for (;;) {
    ClusteredMesh reduced = cluster_vertices(mesh, cell);
    if (reduced.mesh.num_triangles() <= max_triangles) return reduced;
    cell *= 1.25;
  }
}

}  // namespace volspline
