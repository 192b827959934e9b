#include "vtk_lagrange_tetrahedron.h"

#include <cstddef>

#include "volspline/core/error.h"

namespace volspline {
namespace {

using LagrangeNode = std::array<int, 4>;

// The point k/n of the way from p to q (both with coordinates summing to a multiple of n).
LagrangeNode lagrange_between(const LagrangeNode& p, const LagrangeNode& q, int k, int n) {
  LagrangeNode r{};
  for (std::size_t c = 0; c < 4; ++c) r[c] = p[c] + (q[c] - p[c]) * k / n;
  return r;
}

// The corners of the simplex one layer in: each corner moved 1/n of the way towards each other one.
template <std::size_t N>
std::array<LagrangeNode, N> lagrange_inner_corners(const std::array<LagrangeNode, N>& v, int n) {
  std::array<LagrangeNode, N> inner{};
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t c = 0; c < 4; ++c) {
      int step = 0;
      for (std::size_t j = 0; j < N; ++j)
        if (j != i) step += v[j][c] - v[i][c];
      inner[i][c] = v[i][c] + step / n;
    }
  return inner;
}

void lagrange_triangle(const std::array<LagrangeNode, 3>& v, int n, std::vector<LagrangeNode>& out) {
  if (n < 0) return;
  if (n == 0) {
    out.push_back(v[0]);
    return;
  }
  out.insert(out.end(), v.begin(), v.end());
  static constexpr int kTriangleEdges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& e : kTriangleEdges)
    for (int k = 1; k < n; ++k) out.push_back(lagrange_between(v[static_cast<std::size_t>(e[0])], v[static_cast<std::size_t>(e[1])], k, n));
  if (n >= 3) lagrange_triangle(lagrange_inner_corners(v, n), n - 3, out);
}

void lagrange_tetrahedron(const std::array<LagrangeNode, 4>& v, int n, std::vector<LagrangeNode>& out) {
  if (n < 0) return;
  if (n == 0) {
    out.push_back(v[0]);
    return;
  }
  out.insert(out.end(), v.begin(), v.end());
  static constexpr int kTetrahedronEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : kTetrahedronEdges)
    for (int k = 1; k < n; ++k) out.push_back(lagrange_between(v[static_cast<std::size_t>(e[0])], v[static_cast<std::size_t>(e[1])], k, n));
  if (n >= 3) {
    static constexpr int kTetrahedronFaces[4][3] = {{0, 1, 3}, {2, 3, 1}, {0, 3, 2}, {0, 2, 1}};
    for (const auto& f : kTetrahedronFaces) {
      const std::array<LagrangeNode, 3> face{v[static_cast<std::size_t>(f[0])], v[static_cast<std::size_t>(f[1])], v[static_cast<std::size_t>(f[2])]};
      lagrange_triangle(lagrange_inner_corners(face, n), n - 3, out);
    }
  }
  if (n >= 4) lagrange_tetrahedron(lagrange_inner_corners(v, n), n - 4, out);
}

}  // namespace

std::vector<std::array<int, 4>> vtk_lagrange_tetrahedron_nodes(int order) {
  if (order < 1 || order > 10) throw InvalidInput("expected a Lagrange tetrahedron order from 1 to 10, got " + std::to_string(order), "order");
  std::vector<LagrangeNode> nodes;
  nodes.reserve(static_cast<std::size_t>((order + 1) * (order + 2) * (order + 3) / 6));
  std::array<LagrangeNode, 4> corners{};
  for (std::size_t i = 0; i < 4; ++i) corners[i][i] = order;
  lagrange_tetrahedron(corners, order, nodes);
  return nodes;
}

}  // namespace volspline
