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

namespace {

// The corners of a tetrahedron by sign (values >= 0 count as positive), in corner order.
struct CornersBySign {
  std::array<int, 4> positive{}, negative{};
  int np = 0, nn = 0;
};

CornersBySign split_by_sign(const std::array<MarchingTetrahedra::Sample, 4>& t) {
  CornersBySign c;
  for (int i = 0; i < 4; ++i) {
    if (t[static_cast<std::size_t>(i)].value >= 0) {
      c.positive[static_cast<std::size_t>(c.np++)] = i;
    } else {
      c.negative[static_cast<std::size_t>(c.nn++)] = i;
    }
  }
  return c;
}

}  // namespace

void MarchingTetrahedra::add_tetrahedron(const std::array<Sample, 4>& t) {
  const auto [positive, negative, np, nn] = split_by_sign(t);
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

void MarchingTetrahedra::add_tetrahedron_oriented_by_corners(const std::array<Sample, 4>& t) {
  const auto [positive, negative, np, nn] = split_by_sign(t);
  if (np == 0 || nn == 0) return;
  auto s = [&](int i) -> const Sample& { return t[static_cast<std::size_t>(i)]; };
  const auto det = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) { return a.dot(b.cross(c)); };
  if (np == 1 || nn == 1) {
    // Surface vertex P_x = L + t_x (O_x − L) on the edge from the lone corner L to O_x, t_x ∈ [0, 1]:
    // (P_b − P_a) × (P_c − P_a) · (L − P_a) = −t_a t_b t_c det(O_a − L, O_b − L, O_c − L), so the
    // corners' determinant decides the order even where some t_x = 0.
    const int lone = np == 1 ? positive[0] : negative[0];
    std::array<int, 3> o{};
    int m = 0;
    for (int i = 0; i < 4; ++i) {
      if (i != lone) o[static_cast<std::size_t>(m++)] = i;
    }
    const Eigen::Vector3d& l = s(lone).point;
    const double d = det(s(o[0]).point - l, s(o[1]).point - l, s(o[2]).point - l);
    std::array<int, 3> v{edge_vertex(s(lone), s(o[0])), edge_vertex(s(lone), s(o[1])), edge_vertex(s(lone), s(o[2]))};
    // Normal towards L wanted if L is positive (d < 0 then), away from it if L is negative.
    if ((np == 1) == (d > 0)) std::swap(v[1], v[2]);
    triangles_.push_back(v);
    return;
  }
  // The quadrilateral p0-n0, p0-n1, p1-n1, p1-n0 is a plane section of the tetrahedron; its
  // orientation is that of the section through the edge midpoints, where the normal of the
  // first triangle dotted with (p0 + p1 − n0 − n1) is det(n1 − n0, p1 − p0, p0 + p1 − n0 − n1) / 4.
  const int p0 = positive[0], p1 = positive[1], n0 = negative[0], n1 = negative[1];
  const double d = det(s(n1).point - s(n0).point, s(p1).point - s(p0).point,
                       s(p0).point + s(p1).point - s(n0).point - s(n1).point);
  const int a = edge_vertex(s(p0), s(n0)), b = edge_vertex(s(p0), s(n1)), c = edge_vertex(s(p1), s(n1)),
            e = edge_vertex(s(p1), s(n0));
  if (d > 0) {
    triangles_.push_back({a, b, c});
    triangles_.push_back({a, c, e});
  } else {
    triangles_.push_back({a, c, b});
    triangles_.push_back({a, e, c});
  }
}

}  // namespace volspline
