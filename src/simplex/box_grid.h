#pragma once
// A uniform grid over axis-aligned boxes: which boxes may hold a point. The supports of the
// basis functions of a DMS spline volume and the tetrahedra of its domain are found this way
// (their boxes overlap a bounded number of cells, so a query costs O(1) for a reasonable mesh).
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace volspline {

class BoxGrid {
 public:
  BoxGrid() = default;
  /// About sixteen cells per box (a query then meets few boxes), at most 128 per axis.
  explicit BoxGrid(const std::vector<Eigen::AlignedBox3d>& boxes);
  /// The boxes whose cells hold x (a superset of the boxes that contain x; empty outside all).
  std::span<const int> query(const Eigen::Vector3d& x) const;
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  const Eigen::Vector3i& cells() const { return cells_; }
  /// The positions [first, last) of query(x) in ids(), for data kept in the grid's cell order
  /// (read in sequence rather than scattered over the boxes).
  std::pair<int, int> query_positions(const Eigen::Vector3d& x) const;
  /// The box of every position, cell by cell.
  const std::vector<int>& ids() const { return ids_; }
  /// The number of the cell that holds x (i + nx (j + ny k)), or -1 outside the bounds.
  int cell_of(const Eigen::Vector3d& x) const;
  /// The boxes of one cell (i, j, k), each index in range.
  std::span<const int> cell(int i, int j, int k) const;

 private:
  Eigen::AlignedBox3d bounds_;
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  Eigen::Vector3d cell_size_ = Eigen::Vector3d::Ones();
  std::vector<int> offsets_;
  std::vector<int> ids_;
};

}  // namespace volspline
