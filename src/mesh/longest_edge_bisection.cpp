#include "volspline/mesh/longest_edge_bisection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <string>
#include <unordered_map>
#include <utility>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {
namespace {

constexpr std::array<std::array<int, 2>, 6> kTetrahedronEdges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

std::uint64_t undirected_edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

struct PendingEdge {
  double length;
  int a, b;
  // Longest first; ties by the vertex indices, so the result does not depend on the heap's order.
  bool operator<(const PendingEdge& o) const {
    if (length != o.length) return length < o.length;
    return std::pair(a, b) > std::pair(o.a, o.b);
  }
};

}  // namespace

double longest_edge_length(const TetrahedralMesh& mesh) {
  double longest = 0;
  for (const auto& t : mesh.tetrahedra)
    for (const auto& e : kTetrahedronEdges)
      longest = std::max(longest, (mesh.points[static_cast<std::size_t>(t[e[0]])] - mesh.points[static_cast<std::size_t>(t[e[1]])]).norm());
  return longest;
}

LongestEdgeBisection bisect_longest_edges(const TetrahedralMesh& mesh, const LongestEdgeBisectionOptions& options) {
  if (!(options.target_edge > 0) || !std::isfinite(options.target_edge))
    throw InvalidInput("expected a positive target edge length, got " + format_double(options.target_edge));
  LongestEdgeBisection result;
  result.mesh = mesh;
  std::vector<Eigen::Vector3d>& points = result.mesh.points;
  std::vector<std::array<int, 4>>& tetrahedra = result.mesh.tetrahedra;
  result.parent.resize(tetrahedra.size());
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) result.parent[t] = static_cast<int>(t);

  std::unordered_map<std::uint64_t, std::vector<int>> edge_tetrahedra;
  std::priority_queue<PendingEdge> pending;
  const auto length = [&](int a, int b) { return (points[static_cast<std::size_t>(a)] - points[static_cast<std::size_t>(b)]).norm(); };
  const auto attach = [&](int t) {
    const auto& v = tetrahedra[static_cast<std::size_t>(t)];
    for (const auto& e : kTetrahedronEdges) {
      auto& list = edge_tetrahedra[undirected_edge_key(v[e[0]], v[e[1]])];
      if (list.empty()) {
        const double l = length(v[e[0]], v[e[1]]);
        if (l > options.target_edge) pending.push({l, std::min(v[e[0]], v[e[1]]), std::max(v[e[0]], v[e[1]])});
      }
      list.push_back(t);
    }
  };
  const auto detach = [&](int t) {
    const auto& v = tetrahedra[static_cast<std::size_t>(t)];
    for (const auto& e : kTetrahedronEdges) {
      const auto it = edge_tetrahedra.find(undirected_edge_key(v[e[0]], v[e[1]]));
      auto& list = it->second;
      list.erase(std::find(list.begin(), list.end(), t));
      if (list.empty()) edge_tetrahedra.erase(it);
    }
  };
  for (std::size_t t = 0; t < tetrahedra.size(); ++t) attach(static_cast<int>(t));

  while (!pending.empty()) {
    const PendingEdge edge = pending.top();
    pending.pop();
    const auto found = edge_tetrahedra.find(undirected_edge_key(edge.a, edge.b));
    if (found == edge_tetrahedra.end()) continue;  // already split
    const std::vector<int> around = found->second;
    if (tetrahedra.size() + around.size() > options.max_tetrahedra)
      throw InvalidInput("bisecting every edge longer than " + format_double(options.target_edge) + " would make more than " +
                         std::to_string(options.max_tetrahedra) + " tetrahedra; give a longer target edge");
    const int m = static_cast<int>(points.size());
    points.push_back(0.5 * (points[static_cast<std::size_t>(edge.a)] + points[static_cast<std::size_t>(edge.b)]));
    ++result.bisections;
    for (const int t : around) {
      detach(t);
      // Replacing one end of the edge by its midpoint keeps the orientation: the midpoint lies
      // on the segment, so the determinant halves and keeps its sign.
      std::array<int, 4> first = tetrahedra[static_cast<std::size_t>(t)], second = first;
      for (int c = 0; c < 4; ++c) {
        if (first[static_cast<std::size_t>(c)] == edge.b) first[static_cast<std::size_t>(c)] = m;
        if (second[static_cast<std::size_t>(c)] == edge.a) second[static_cast<std::size_t>(c)] = m;
      }
      tetrahedra[static_cast<std::size_t>(t)] = first;
      tetrahedra.push_back(second);
      result.parent.push_back(result.parent[static_cast<std::size_t>(t)]);
      attach(t);
      attach(static_cast<int>(tetrahedra.size() - 1));
    }
  }
  return result;
}

}  // namespace volspline
