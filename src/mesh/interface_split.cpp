#include "volspline/mesh/interface_split.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "exact_orientation.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

int level_sign(double value) { return value < 0 ? -1 : (value > 0 ? 1 : 0); }

// The polygons bounding one side (sign `side`) of a cut tetrahedron: the tetrahedron's faces
// clipped to that side, and the interface polygon. Points are pre-duplication numbers.
std::vector<std::vector<int>> side_faces(const std::array<int, 4>& tet, const std::array<int, 4>& sign, int side,
                                         const std::function<int(int, int)>& crossing) {
  std::vector<std::vector<int>> faces;
  for (const std::array<int, 3>& f : kOutwardTetrahedronFaces) {
    std::vector<int> polygon;
    for (int k = 0; k < 3; ++k) {
      const auto u = static_cast<std::size_t>(f[static_cast<std::size_t>(k)]);
      const auto w = static_cast<std::size_t>(f[static_cast<std::size_t>((k + 1) % 3)]);
      if (sign[u] == side || sign[u] == 0) polygon.push_back(tet[u]);
      if (sign[u] * sign[w] == -1) polygon.push_back(crossing(tet[u], tet[w]));
    }
    if (polygon.size() >= 3) faces.push_back(std::move(polygon));
  }
  // The interface polygon: the corners on it and the crossings, in cyclic order (four points only
  // when two corners lie on each side: the crossings of a1b1, a1b2, a2b2, a2b1).
  std::vector<int> negative, positive, interface;
  for (std::size_t c = 0; c < 4; ++c) {
    if (sign[c] < 0) negative.push_back(tet[c]);
    if (sign[c] > 0) positive.push_back(tet[c]);
    if (sign[c] == 0) interface.push_back(tet[c]);
  }
  if (negative.size() == 2 && positive.size() == 2) {
    interface = {crossing(negative[0], positive[0]), crossing(negative[0], positive[1]), crossing(negative[1], positive[1]),
                 crossing(negative[1], positive[0])};
  } else {
    for (int a : negative)
      for (int b : positive) interface.push_back(crossing(a, b));
  }
  if (interface.size() >= 3) faces.push_back(std::move(interface));
  return faces;
}

}  // namespace

InterfaceSplit split_at_interface(const TetrahedralMesh& mesh, std::span<const double> level, std::span<const Eigen::Vector3d> normal,
                                  const InterfaceSplitOptions& options) {
  if (level.size() != mesh.points.size() || normal.size() != mesh.points.size())
    throw InvalidInput("expected a level and a normal for each of the " + std::to_string(mesh.points.size()) + " points, got " +
                       std::to_string(level.size()) + " and " + std::to_string(normal.size()));
  for (std::size_t i = 0; i < level.size(); ++i)
    if (!std::isfinite(level[i]) || !normal[i].allFinite()) throw InvalidInput("level or normal is not finite", "points[" + std::to_string(i) + "]");
  InterfaceSplit result;
  std::vector<Eigen::Vector3d> points = mesh.points;
  std::vector<double> lv(level.begin(), level.end());
  std::vector<std::vector<int>> incident(points.size());
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t)
    for (int v : mesh.tetrahedra[t]) incident[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));

  // Snapping: a point whose edge crosses the interface close to it moves onto the interface
  // (the plane of its level and normal), if no tetrahedron around it turns over.
  if (options.snap > 0) {
    std::vector<char> marked(points.size(), 0);
    for (const std::array<int, 4>& tet : mesh.tetrahedra)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) {
          const auto u = static_cast<std::size_t>(tet[static_cast<std::size_t>(a)]), w = static_cast<std::size_t>(tet[static_cast<std::size_t>(b)]);
          if (level_sign(lv[u]) * level_sign(lv[w]) != -1) continue;
          const double t = lv[u] / (lv[u] - lv[w]);  // the crossing's position from u
          if (t < options.snap) marked[u] = 1;
          if (t > 1 - options.snap) marked[w] = 1;
        }
    // A boundary point moves within its boundary face's plane (so Ω keeps its shape), and only
    // where that boundary is flat; points on edges and corners of ∂Ω stay.
    std::vector<Eigen::Vector3d> face_normal(points.size(), Eigen::Vector3d::Zero());
    std::vector<char> on_boundary(points.size(), 0), flat(points.size(), 1);
    for (const BoundaryFace& f : boundary_faces(mesh)) {
      const Eigen::Vector3d& a = points[static_cast<std::size_t>(f.vertices[0])];
      const Eigen::Vector3d n = (points[static_cast<std::size_t>(f.vertices[1])] - a).cross(points[static_cast<std::size_t>(f.vertices[2])] - a).normalized();
      for (int v : f.vertices) {
        const auto u = static_cast<std::size_t>(v);
        if (on_boundary[u] && face_normal[u].dot(n) < 1 - 1e-12) flat[u] = 0;
        on_boundary[u] = 1;
        face_normal[u] = n;
      }
    }
    for (std::size_t v = 0; v < points.size(); ++v) {
      if (!marked[v]) continue;
      Eigen::Vector3d direction = normal[v];
      if (on_boundary[v]) {
        if (!flat[v]) continue;
        direction -= direction.dot(face_normal[v]) * face_normal[v];
        if (direction.squaredNorm() < 0.25) continue;  // the interface meets ∂Ω at a grazing angle
      }
      // level(p − t d) = level(p) − t (n·d) = 0.
      const Eigen::Vector3d moved = points[v] - lv[v] / normal[v].dot(direction) * direction;
      const Eigen::Vector3d old = points[v];
      points[v] = moved;
      bool upright = true;
      for (int t : incident[v]) {
        const std::array<int, 4>& tet = mesh.tetrahedra[static_cast<std::size_t>(t)];
        upright = upright && exact::orientation(points[static_cast<std::size_t>(tet[0])], points[static_cast<std::size_t>(tet[1])],
                                                points[static_cast<std::size_t>(tet[2])], points[static_cast<std::size_t>(tet[3])]) > 0;
      }
      if (upright) {
        lv[v] = 0;
        ++result.snapped_points;
      } else {
        points[v] = old;
      }
    }
  }

  // Crossings, numbered after the mesh points in the order they are first met.
  std::map<std::pair<int, int>, int> crossing_number;
  std::vector<Eigen::Vector3d> crossing_point;
  const auto crossing = [&](int a, int b) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    const auto found = crossing_number.find(key);
    if (found != crossing_number.end()) return found->second;
    const auto u = static_cast<std::size_t>(key.first), w = static_cast<std::size_t>(key.second);
    const double t = lv[u] / (lv[u] - lv[w]);
    crossing_point.push_back(points[u] + t * (points[w] - points[u]));
    const int number = static_cast<int>(points.size() + crossing_point.size() - 1);
    crossing_number.emplace(key, number);
    return number;
  };
  const auto position = [&](int p) -> const Eigen::Vector3d& {
    return p < static_cast<int>(points.size()) ? points[static_cast<std::size_t>(p)] : crossing_point[static_cast<std::size_t>(p) - points.size()];
  };
  std::vector<std::array<int, 4>> pieces;  // pre-duplication numbers
  std::vector<int> piece_side;
  const auto add_piece = [&](std::array<int, 4> tet, int side) {
    const int o = exact::orientation(position(tet[0]), position(tet[1]), position(tet[2]), position(tet[3]));
    if (o == 0) return;  // a flat piece holds no volume
    if (o < 0) std::swap(tet[2], tet[3]);
    pieces.push_back(tet);
    piece_side.push_back(side);
  };
  for (const std::array<int, 4>& tet : mesh.tetrahedra) {
    std::array<int, 4> sign{};
    bool negative = false, positive = false;
    for (std::size_t c = 0; c < 4; ++c) {
      sign[c] = level_sign(lv[static_cast<std::size_t>(tet[c])]);
      negative = negative || sign[c] < 0;
      positive = positive || sign[c] > 0;
    }
    if (!(negative && positive)) {
      add_piece(tet, positive ? 1 : 0);
      continue;
    }
    ++result.cut_tetrahedra;
    for (int side : {-1, 1}) {
      const std::vector<std::vector<int>> faces = side_faces(tet, sign, side, crossing);
      int apex = std::numeric_limits<int>::max();
      for (const auto& f : faces) apex = std::min(apex, *std::min_element(f.begin(), f.end()));
      for (const auto& f : faces) {
        if (std::find(f.begin(), f.end(), apex) != f.end()) continue;
        if (f.size() == 3) {
          add_piece({apex, f[0], f[1], f[2]}, side > 0 ? 1 : 0);
          continue;
        }
        // A quadrilateral: the diagonal through its lowest-numbered corner, as its neighbour does.
        const auto low = static_cast<std::size_t>(std::min_element(f.begin(), f.end()) - f.begin());
        const auto at = [&](std::size_t k) { return f[(low + k) % 4]; };
        add_piece({apex, at(0), at(1), at(2)}, side > 0 ? 1 : 0);
        add_piece({apex, at(0), at(2), at(3)}, side > 0 ? 1 : 0);
      }
    }
  }
  std::size_t on_interface = crossing_point.size();
  for (double v : lv) on_interface += v == 0 ? 1 : 0;
  result.interface_points = on_interface;

  // One point per (pre-duplication point, side) used.
  std::map<std::pair<int, int>, int> output_number;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::array<int, 4> tet{};
    for (std::size_t c = 0; c < 4; ++c) {
      const std::pair<int, int> key{pieces[i][c], piece_side[i]};
      auto found = output_number.find(key);
      if (found == output_number.end()) {
        found = output_number.emplace(key, static_cast<int>(result.mesh.points.size())).first;
        result.mesh.points.push_back(position(pieces[i][c]));
      }
      tet[c] = found->second;
    }
    result.mesh.tetrahedra.push_back(tet);
    result.side.push_back(piece_side[i]);
  }
  return result;
}

}  // namespace volspline
