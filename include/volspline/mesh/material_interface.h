#pragma once
// Two materials in scattered data, told apart by a jump of their values, and the surface between
// them (Hua–He–Qin §4.2, §5.2: field features are where the data are discontinuous; the knots go
// on that surface). Decisions: docs/fitting.md, "Sharp features".
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// How many nearest neighbours link a point to others in the neighbour graph of the data.
inline constexpr int kJumpNeighbours = 6;

struct JumpRegions {
  /// Per point: its region, regions numbered by their first point.
  std::vector<int> label;
  /// Points per region.
  std::vector<std::size_t> sizes;
  /// Neighbour pairs across which some column jumps (whatever their regions).
  std::size_t jump_edges = 0;
};

/// The regions of the data: connected components of the graph that links every point to its
/// kJumpNeighbours nearest others (CGAL's k-d tree; deterministic), without the links across which
/// some column of `values` (one row per point, e.g. normalised to [0, 1]) changes by more than
/// `jump`. \throw InvalidInput for jump <= 0, a row count that differs from the points, or fewer
/// than 2 points.
JumpRegions jump_regions(std::span<const Eigen::Vector3d> points, const Eigen::MatrixXd& values, double jump);

/// The surface between the points labelled 0 and those labelled 1 (other labels are ignored): its
/// samples are the neighbour pairs (kJumpNeighbours nearest) with one point of each. Near x it is
/// a plane: normal to the mean direction (from 0 to 1) of the `local_samples` pairs whose
/// midpoints are nearest x, and offset to the middle of the gap between those pairs' points of 0
/// and of 1 along that normal (the centroid of the midpoints where there is no gap). For a planar
/// interface between unevenly placed points the gap is narrow and the plane close to the true
/// one; for an interface through data points, which can be on either side, the plane lies up to
/// half a spacing off.
class MaterialInterface {
 public:
  /// \throw InvalidInput for sizes that differ, or when no neighbour pair joins 0 and 1.
  MaterialInterface(std::span<const Eigen::Vector3d> points, std::span<const int> label, int local_samples = 48);
  ~MaterialInterface();
  MaterialInterface(MaterialInterface&&) noexcept;
  MaterialInterface& operator=(MaterialInterface&&) noexcept;
  /// The signed distance from x to the local plane (negative on the side of 0), and the plane's
  /// unit normal pointing to 1 if `normal` is given.
  double level(const Eigen::Vector3d& x, Eigen::Vector3d* normal = nullptr) const;
  std::size_t sample_count() const;

 private:
  struct Samples;
  std::unique_ptr<Samples> samples_;
};

}  // namespace volspline
