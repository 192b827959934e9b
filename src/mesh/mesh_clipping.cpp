#include "volspline/mesh/mesh_clipping.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

class Clipper {
 public:
  Clipper(const TriangleMesh& mesh, const std::vector<Plane>& planes) : planes_(planes) {
    validate_mesh(mesh);
    for (std::size_t i = 0; i < planes.size(); ++i) {
      const Plane& p = planes[i];
      if (!p.normal.allFinite() || !std::isfinite(p.offset) || p.normal.norm() == 0)
        throw InvalidInput("clipping plane " + std::to_string(i) + " needs a finite nonzero normal and a finite offset");
    }
    out_.positions = mesh.positions;
    out_.parameters = mesh.parameters;
  }

  // Splits the convex polygon by each plane in turn: what lies on a negative side leaves the
  // region for good (kept when `outside`); what stays positive for all planes is the region.
  void add(const std::vector<int>& polygon, int part, bool outside) {
    std::vector<int> rest = polygon;
    for (std::size_t i = 0; i < planes_.size() && rest.size() >= 3; ++i) {
      std::vector<int> negative, positive;
      split(rest, i, negative, positive);
      if (outside) emit(negative, part);
      rest = std::move(positive);
    }
    if (!outside) emit(rest, part);
  }

  TriangleMesh finish() {
    // Drop the vertices no triangle uses (those of removed parts).
    std::vector<int> index(out_.positions.size(), -1);
    TriangleMesh compact;
    for (auto& t : out_.triangles)
      for (int& v : t) {
        if (index[static_cast<std::size_t>(v)] < 0)
          index[static_cast<std::size_t>(v)] =
              compact.add_vertex(out_.positions[static_cast<std::size_t>(v)], out_.parameters[static_cast<std::size_t>(v)]);
        v = index[static_cast<std::size_t>(v)];
      }
    compact.triangles = std::move(out_.triangles);
    compact.parts = std::move(out_.parts);
    return compact;
  }

 private:
  double side(int v, std::size_t plane) const {
    return planes_[plane].normal.dot(out_.positions[static_cast<std::size_t>(v)]) - planes_[plane].offset;
  }

  // The vertex where edge (a, b) crosses plane `plane`, made once per edge and plane.
  int crossing(int a, int b, std::size_t plane) {
    const auto key = std::make_tuple(std::min(a, b), std::max(a, b), plane);
    const auto it = crossings_.find(key);
    if (it != crossings_.end()) return it->second;
    const int lo = std::min(a, b), hi = std::max(a, b);  // interpolate from a fixed end: both sides agree
    const double sa = side(lo, plane), sb = side(hi, plane);
    const double t = sa / (sa - sb);
    const Eigen::Vector3d p = out_.positions[static_cast<std::size_t>(lo)] +
                              t * (out_.positions[static_cast<std::size_t>(hi)] - out_.positions[static_cast<std::size_t>(lo)]);
    const Eigen::Vector3d q = out_.parameters[static_cast<std::size_t>(lo)] +
                              t * (out_.parameters[static_cast<std::size_t>(hi)] - out_.parameters[static_cast<std::size_t>(lo)]);
    const int v = out_.add_vertex(p, q);
    crossings_.emplace(key, v);
    return v;
  }

  // Sutherland–Hodgman against one plane; vertices on the plane go to both sides.
  void split(const std::vector<int>& polygon, std::size_t plane, std::vector<int>& negative, std::vector<int>& positive) {
    const std::size_t n = polygon.size();
    // A polygon in the plane, or touching it from one side, belongs to that side alone (the
    // region is open: a face lying in a cut plane is not cut away, and never emitted twice).
    double low = 0, high = 0;
    for (const int v : polygon) {
      low = std::min(low, side(v, plane));
      high = std::max(high, side(v, plane));
    }
    if (high <= 0) {
      negative = polygon;
      return;
    }
    if (low >= 0) {
      positive = polygon;
      return;
    }
    for (std::size_t k = 0; k < n; ++k) {
      const int a = polygon[k], b = polygon[(k + 1) % n];
      const double sa = side(a, plane), sb = side(b, plane);
      if (sa <= 0) negative.push_back(a);
      if (sa >= 0) positive.push_back(a);
      if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) {
        const int c = crossing(a, b, plane);
        negative.push_back(c);
        positive.push_back(c);
      }
    }
  }

  void emit(const std::vector<int>& polygon, int part) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      const int a = polygon[0], b = polygon[k], c = polygon[k + 1];
      if (a != b && b != c && a != c) out_.add_triangle(a, b, c, part);
    }
  }

  const std::vector<Plane>& planes_;
  TriangleMesh out_;
  std::map<std::tuple<int, int, std::size_t>, int> crossings_;
};

TriangleMesh clip(const TriangleMesh& mesh, const std::vector<Plane>& planes, bool outside) {
  Clipper clipper(mesh, planes);
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    clipper.add({tri[0], tri[1], tri[2]}, mesh.parts[t], outside);
  }
  return clipper.finish();
}

}  // namespace

TriangleMesh remove_convex_region(const TriangleMesh& mesh, const std::vector<Plane>& planes) {
  return clip(mesh, planes, true);
}

TriangleMesh keep_convex_region(const TriangleMesh& mesh, const std::vector<Plane>& planes) {
  return clip(mesh, planes, false);
}

}  // namespace volspline
