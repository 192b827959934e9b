#include "box_grid.h"

#include <algorithm>
#include <cmath>

namespace volspline {

BoxGrid::BoxGrid(const std::vector<Eigen::AlignedBox3d>& boxes) {
  for (const Eigen::AlignedBox3d& b : boxes) bounds_.extend(b);
  if (boxes.empty()) return;
  const Eigen::Vector3d extent = bounds_.sizes().cwiseMax(1e-300);
  const double volume_per_cell = extent.prod() / (16.0 * static_cast<double>(boxes.size()));
  const double side = std::cbrt(volume_per_cell);
  for (int a = 0; a < 3; ++a) {
    const double count = std::isfinite(side) && side > 0 ? std::ceil(extent[a] / side) : 1.0;
    cells_[a] = static_cast<int>(std::clamp(count, 1.0, 128.0));
    cell_size_[a] = extent[a] / cells_[a];
  }
  auto cell_range = [&](const Eigen::AlignedBox3d& b, Eigen::Vector3i& lo, Eigen::Vector3i& hi) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::clamp(static_cast<int>(std::floor((b.min()[a] - bounds_.min()[a]) / cell_size_[a])), 0, cells_[a] - 1);
      hi[a] = std::clamp(static_cast<int>(std::floor((b.max()[a] - bounds_.min()[a]) / cell_size_[a])), 0, cells_[a] - 1);
    }
  };
  const std::size_t total = static_cast<std::size_t>(cells_.prod());
  std::vector<int> counts(total + 1, 0);
  Eigen::Vector3i lo, hi;
  for (const Eigen::AlignedBox3d& b : boxes) {
    cell_range(b, lo, hi);
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i) ++counts[static_cast<std::size_t>(i + cells_.x() * (j + cells_.y() * k)) + 1];
  }
  for (std::size_t c = 0; c < total; ++c) counts[c + 1] += counts[c];
  offsets_ = counts;
  ids_.resize(static_cast<std::size_t>(offsets_.back()));
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t id = 0; id < boxes.size(); ++id) {
    cell_range(boxes[id], lo, hi);
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i)
          ids_[static_cast<std::size_t>(fill[static_cast<std::size_t>(i + cells_.x() * (j + cells_.y() * k))]++)] = static_cast<int>(id);
  }
}

std::span<const int> BoxGrid::cell(int i, int j, int k) const {
  const std::size_t c = static_cast<std::size_t>(i + cells_.x() * (j + cells_.y() * k));
  return {ids_.data() + offsets_[c], static_cast<std::size_t>(offsets_[c + 1] - offsets_[c])};
}

int BoxGrid::cell_of(const Eigen::Vector3d& x) const {
  if (ids_.empty() || !bounds_.contains(x)) return -1;
  int index[3];
  for (int a = 0; a < 3; ++a)
    index[a] = std::clamp(static_cast<int>(std::floor((x[a] - bounds_.min()[a]) / cell_size_[a])), 0, cells_[a] - 1);
  return index[0] + cells_.x() * (index[1] + cells_.y() * index[2]);
}

std::pair<int, int> BoxGrid::query_positions(const Eigen::Vector3d& x) const {
  const int cell = cell_of(x);
  if (cell < 0) return {0, 0};
  const auto c = static_cast<std::size_t>(cell);
  return {offsets_[c], offsets_[c + 1]};
}

std::span<const int> BoxGrid::query(const Eigen::Vector3d& x) const {
  const auto [first, last] = query_positions(x);
  return {ids_.data() + first, static_cast<std::size_t>(last - first)};
}

}  // namespace volspline
