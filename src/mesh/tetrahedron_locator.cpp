#include "volspline/mesh/tetrahedron_locator.h"

#include <algorithm>
#include <cmath>

#include "exact_orientation.h"

namespace volspline {

TetrahedronLocator::TetrahedronLocator(const TetrahedralMesh& mesh) : mesh_(&mesh) {
  if (mesh.tetrahedra.empty() || mesh.points.empty()) return;
  origin_ = mesh.points[0];
  upper_ = mesh.points[0];
  for (const auto& p : mesh.points) {
    origin_ = origin_.cwiseMin(p);
    upper_ = upper_.cwiseMax(p);
  }
  // About one tetrahedron per cell on average: cells of the size of a typical tetrahedron.
  const Eigen::Vector3d extent = (upper_ - origin_).cwiseMax(1e-300);
  const double volume = extent.prod();
  cell_size_ = std::cbrt(volume / static_cast<double>(mesh.tetrahedra.size()));
  if (!(cell_size_ > 0) || !std::isfinite(cell_size_)) cell_size_ = extent.maxCoeff();
  for (int k = 0; k < 3; ++k) {
    cells_[k] = static_cast<int>(std::clamp(std::ceil(extent[k] / cell_size_), 1.0, 1024.0));
  }
  const auto cell_index = [&](const Eigen::Vector3i& c) { return c[0] + cells_[0] * (c[1] + cells_[1] * c[2]); };
  const std::size_t num_cells = static_cast<std::size_t>(cells_.prod());
  std::vector<int> counts(num_cells + 1, 0);
  const auto for_each_cell = [&](const std::array<int, 4>& t, auto&& visit) {
    Eigen::Vector3d lo = mesh.points[t[0]], hi = mesh.points[t[0]];
    for (int k = 1; k < 4; ++k) {
      lo = lo.cwiseMin(mesh.points[t[k]]);
      hi = hi.cwiseMax(mesh.points[t[k]]);
    }
    const Eigen::Vector3i a = cell_of(lo), b = cell_of(hi);
    for (int z = a[2]; z <= b[2]; ++z)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x) visit(cell_index({x, y, z}));
  };
  for (const auto& t : mesh.tetrahedra) for_each_cell(t, [&](int c) { ++counts[c + 1]; });
  for (std::size_t c = 0; c < num_cells; ++c) counts[c + 1] += counts[c];
  cell_start_ = counts;
  tetrahedra_.resize(counts[num_cells]);
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    for_each_cell(mesh.tetrahedra[t], [&](int c) { tetrahedra_[counts[c]++] = static_cast<int>(t); });
  }
}

Eigen::Vector3i TetrahedronLocator::cell_of(const Eigen::Vector3d& x) const {
  Eigen::Vector3i c;
  for (int k = 0; k < 3; ++k) {
    // Rounded subtraction and division are monotone, so a point inside a tetrahedron's box
    // falls in a cell between those of the box's corners: no cell is missed at a wall.
    c[k] = static_cast<int>(std::clamp(std::floor((x[k] - origin_[k]) / cell_size_), 0.0, double(cells_[k] - 1)));
  }
  return c;
}

int TetrahedronLocator::locate(const Eigen::Vector3d& x) const {
  if (cell_start_.empty() || !x.allFinite()) return -1;
  if ((x.array() < origin_.array()).any() || (x.array() > upper_.array()).any()) return -1;
  const exact::Point q = exact::to_cgal(x);
  const Eigen::Vector3i cell = cell_of(x);
  const int c = cell[0] + cells_[0] * (cell[1] + cells_[1] * cell[2]);
  // Each cell lists its tetrahedra in increasing order, so the first hit is the lowest index.
  for (int i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
    const int t = tetrahedra_[i];
    const auto& tet = mesh_->tetrahedra[t];
    const exact::Point a = exact::to_cgal(mesh_->points[tet[0]]), b = exact::to_cgal(mesh_->points[tet[1]]),
                       cc = exact::to_cgal(mesh_->points[tet[2]]), d = exact::to_cgal(mesh_->points[tet[3]]);
    if (exact::orientation(q, b, cc, d) >= 0 && exact::orientation(a, q, cc, d) >= 0 &&
        exact::orientation(a, b, q, d) >= 0 && exact::orientation(a, b, cc, q) >= 0) {
      return t;
    }
  }
  return -1;
}

}  // namespace volspline
