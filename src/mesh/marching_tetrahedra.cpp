#include "volspline/mesh/marching_tetrahedra.h"

#include <Eigen/Geometry>

namespace volspline {

int MarchingTetrahedra::edge_vertex(const Sample& a, const Sample& b) {
  const Sample& lo = a.id < b.id ? a : b;
  const Sample& hi = a.id < b.id ? b : a;
  const std::array<std::int64_t, 2> key{lo.id, hi.id};
  const auto found = edge_vertices_.find(key);
  if (found != edge_vertices_.end()) return found->second;
  // Always interpolated from the lower id's end, so every tetrahedron computes the same point.
  const double t = lo.value / (lo.value - hi.value);
  const int index = static_cast<int>(vertices_.size());
  vertices_.push_back(lo.point + t * (hi.point - lo.point));
  vertex_edges_.push_back(key);
  edge_vertices_.emplace(key, index);
  return index;
}

void MarchingTetrahedra::emit(int a, int b, int c, const Eigen::Vector3d& toward_positive) {
  const Eigen::Vector3d& pa = vertices_[static_cast<std::size_t>(a)];
  const Eigen::Vector3d n = (vertices_[static_cast<std::size_t>(b)] - pa).cross(vertices_[static_cast<std::size_t>(c)] - pa);
  if (n.dot(toward_positive) < 0) std::swap(b, c);
  triangles_.push_back({a, b, c});
}

void MarchingTetrahedra::reserve(std::size_t vertices, std::size_t triangles) {
  edge_vertices_.reserve(vertices);
  vertices_.reserve(vertices);
  vertex_edges_.reserve(vertices);
  triangles_.reserve(triangles);
}

void MarchingTetrahedra::add_tetrahedron(const std::array<Sample, 4>& t) {
  std::array<int, 4> positive{}, negative{};
  int np = 0, nn = 0;
  for (int i = 0; i < 4; ++i) {
    if (t[static_cast<std::size_t>(i)].value >= 0) {
      positive[static_cast<std::size_t>(np++)] = i;
    } else {
      negative[static_cast<std::size_t>(nn++)] = i;
    }
  }
  if (np == 0 || nn == 0) return;
  auto s = [&](int i) -> const Sample& { return t[static_cast<std::size_t>(i)]; };
  Eigen::Vector3d pos_centre = Eigen::Vector3d::Zero(), neg_centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < np; ++i) pos_centre += s(positive[static_cast<std::size_t>(i)]).point / np;
  for (int i = 0; i < nn; ++i) neg_centre += s(negative[static_cast<std::size_t>(i)]).point / nn;
  const Eigen::Vector3d toward = pos_centre - neg_centre;
  if (np == 1 || nn == 1) {
    // Fig. 6a: one vertex against three; one triangle across the three edges at that vertex.
    const int lone = np == 1 ? positive[0] : negative[0];
    std::array<int, 3> v{};
    int m = 0;
    for (int i = 0; i < 4; ++i) {
      if (i != lone) v[static_cast<std::size_t>(m++)] = edge_vertex(s(lone), s(i));
    }
    emit(v[0], v[1], v[2], toward);
    return;
  }
  // Fig. 6b: two against two; the quadrilateral across the four mixed edges, in cyclic order
  // p0-n0, p0-n1, p1-n1, p1-n0, as two triangles.
  const int p0 = positive[0], p1 = positive[1], n0 = negative[0], n1 = negative[1];
  const int a = edge_vertex(s(p0), s(n0)), b = edge_vertex(s(p0), s(n1)), c = edge_vertex(s(p1), s(n1)),
            d = edge_vertex(s(p1), s(n0));
  emit(a, b, c, toward);
  emit(a, c, d, toward);
}

}  // namespace volspline
