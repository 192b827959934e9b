#pragma once
// Distances from points to a triangle mesh, for Hausdorff checks in tests: the triangles are
// bucketed in a uniform grid, and the search widens ring by ring until no closer triangle can
// be in a farther ring.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "volspline/mesh/triangle_mesh.h"

namespace volspline::test_support {

/// The distance from p to the triangle abc (closest point by regions, Ericson 2005, §5.1.5).
inline double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double den = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

class MeshDistance {
 public:
  explicit MeshDistance(const TriangleMesh& mesh) : mesh_(mesh) {
    const auto [lo, hi] = mesh.bounding_box();
    lo_ = lo;
    const double n = std::max(1.0, std::cbrt(static_cast<double>(mesh.num_triangles()) / 2));
    h_ = std::max((hi - lo).maxCoeff() / n, 1e-12);
    for (int d = 0; d < 3; ++d) n_[static_cast<std::size_t>(d)] = static_cast<int>((hi[d] - lo[d]) / h_) + 1;
    buckets_.resize(static_cast<std::size_t>(n_[0]) * static_cast<std::size_t>(n_[1]) * static_cast<std::size_t>(n_[2]));
    for (std::size_t f = 0; f < mesh.num_triangles(); ++f) {
      Eigen::Vector3d tlo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), thi = -tlo;
      for (int v : mesh.triangles[f]) {
        tlo = tlo.cwiseMin(mesh.positions[static_cast<std::size_t>(v)]);
        thi = thi.cwiseMax(mesh.positions[static_cast<std::size_t>(v)]);
      }
      const auto a = cell(tlo), b = cell(thi);
      for (int k = a[2]; k <= b[2]; ++k)
        for (int j = a[1]; j <= b[1]; ++j)
          for (int i = a[0]; i <= b[0]; ++i) buckets_[index(i, j, k)].push_back(f);
    }
  }

  double operator()(const Eigen::Vector3d& p) const {
    const auto c = cell(p);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= std::max({n_[0], n_[1], n_[2]}); ++ring) {
      // Every triangle in a farther ring is at least (ring) cells away from p's cell.
      if (best <= (ring - 1) * h_) break;
      for (int k = c[2] - ring; k <= c[2] + ring; ++k)
        for (int j = c[1] - ring; j <= c[1] + ring; ++j)
          for (int i = c[0] - ring; i <= c[0] + ring; ++i) {
            if (std::max({std::abs(i - c[0]), std::abs(j - c[1]), std::abs(k - c[2])}) != ring) continue;
            if (i < 0 || j < 0 || k < 0 || i >= n_[0] || j >= n_[1] || k >= n_[2]) continue;
            for (std::size_t f : buckets_[index(i, j, k)]) {
              const auto& t = mesh_.triangles[f];
              best = std::min(best, point_triangle_distance(p, mesh_.positions[static_cast<std::size_t>(t[0])],
                                                            mesh_.positions[static_cast<std::size_t>(t[1])],
                                                            mesh_.positions[static_cast<std::size_t>(t[2])]));
            }
          }
    }
    return best;
  }

 private:
  std::array<int, 3> cell(const Eigen::Vector3d& p) const {
    std::array<int, 3> c{};
    for (int d = 0; d < 3; ++d)
      c[static_cast<std::size_t>(d)] = std::clamp(static_cast<int>(std::floor((p[d] - lo_[d]) / h_)), 0, n_[static_cast<std::size_t>(d)] - 1);
    return c;
  }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(n_[1]) + static_cast<std::size_t>(j)) * static_cast<std::size_t>(n_[0]) +
           static_cast<std::size_t>(i);
  }

  const TriangleMesh& mesh_;
  Eigen::Vector3d lo_;
  double h_ = 1;
  std::array<int, 3> n_{};
  std::vector<std::vector<std::size_t>> buckets_;
};

}  // namespace volspline::test_support
