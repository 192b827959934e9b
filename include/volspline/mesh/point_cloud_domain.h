#pragma once
// A tetrahedral domain for scattered volume data (Hua–He–Qin §5.2): primary knots chosen among
// the data points, their Delaunay tetrahedralisation, and the occupancy map of the data (a
// ball at every data point), which removes the tetrahedra outside the object; boundary vertices
// classified by their solid angle. Decisions: docs/fitting.md, "The domain".
#include <cstddef>
#include <array>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

/// The indices of `count` points chosen by farthest-point sampling: first the seeds (in their
/// order, at most `count`), or without seeds the lexicographically smallest point (x, then y,
/// then z); each next one the point farthest from those chosen (ties: the lowest index).
/// Duplicates of chosen points are never chosen, so fewer than `count` come back when the points
/// have fewer distinct positions. Deterministic.
/// With `spacing` (one positive number per point), distances from point i are divided by
/// spacing[i]: the next point is the one farthest from those chosen *in units of its own
/// spacing*, so the chosen points are about spacing[i] apart around point i (a sizing field, as
/// in mesh generation).
/// \throw InvalidInput for count < 1, no points, or a spacing that is not positive and finite.
std::vector<int> farthest_point_subsample(std::span<const Eigen::Vector3d> points, int count, std::span<const int> seeds = {},
                                          std::span<const double> spacing = {});

/// The indices of the vertices of the points' convex hull (extreme points: points inside or on
/// a face or edge of the hull are not vertices; the lowest index of duplicates), sorted; empty
/// for fewer than 4 distinct points. CGAL's extreme_points_3 with exact predicates.
std::vector<int> convex_hull_vertices(std::span<const Eigen::Vector3d> points);

/// Which neighbour's distance is the radius of a ball of the occupancy map: the 8th nearest.
inline constexpr int kOccupancyNeighbour = 8;

/// The occupancy map of §5.2: a ball at every point whose radius is its distance to its
/// kOccupancyNeighbour-th nearest other point (the largest found where there are fewer).
/// The paper's radius, the shortest distance to the 1-ring (the nearest neighbour), leaves the
/// union full of holes unless the sampling is regular and isotropic (docs/fitting.md).
/// Duplicates are one point.
class OccupancyMap {
 public:
  explicit OccupancyMap(std::span<const Eigen::Vector3d> points);
  /// Whether x lies in the union of the (closed) balls.
  bool contains(const Eigen::Vector3d& x) const;
  /// The radius of point i's ball (0 if all points coincide).
  double radius(std::size_t i) const { return radii_[i]; }

 private:
  std::vector<Eigen::Vector3d> points_;
  std::vector<double> radii_;
  double cell_ = 1, largest_radius_ = 0;
  Eigen::Vector3d origin_;
  Eigen::Vector3i cells_;
  std::vector<int> cell_start_, cell_points_;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& x) const;
};

/// Boundary vertices by the solid angle Ω of the domain at them (§5.2): General (|Ω − 2π| ≤ π/2:
/// the boundary bends by at most 45°), Curve (on a feature line: a cube's edge has Ω = π, a
/// concave edge 3π; π/2 < |Ω − 2π| ≤ 5π/4), Corner (|Ω − 2π| > 5π/4: a cube's corner has π/2).
enum class VertexKind { Interior, General, Curve, Corner };

/// The solid angle of the domain at every point (4π inside, 2π on a flat boundary): the sum over
/// its tetrahedra of their solid angles at it (Van Oosterom–Strackee).
std::vector<double> vertex_solid_angles(const TetrahedralMesh& mesh);
/// The kinds of the points of `mesh` (Interior for those on no boundary face).
std::vector<VertexKind> classify_vertices(const TetrahedralMesh& mesh);

struct PointCloudDomainOptions {
  /// The number of primary knots; 0: max(4, points / 24). They are the vertices of the data's
  /// convex hull (when at most half the count, so that Ω covers the data's hull) followed by
  /// farthest-point samples.
  int primary_knots = 0;
  /// Knots inside the hull of the primary knots move by this fraction of their shortest Delaunay
  /// edge (deterministic directions) before the final Delaunay: grid data would otherwise give
  /// tetrahedra flat up to rounding, for which no knot clouds are valid. 0: no move.
  double jitter = 1e-2;
  /// Remove the Delaunay tetrahedra with an edge midpoint outside the occupancy map.
  bool clip_to_occupancy = true;
  /// Primary knots on a body-centred cubic lattice over the points' bounding box (cube corners on
  /// the box, about primary_knots of them; its Delaunay tetrahedra are congruent up to the
  /// jitter) instead of data points chosen by farthest-point sampling. Experimental
  /// (docs/fitting.md, "Baselines": smooth data).
  bool lattice = false;
  /// A sizing field for the farthest-point samples: one relative spacing per data point (empty:
  /// uniform). Knot optimisation (simplex/knot_placement.h) makes it from a first fit's error.
  std::vector<double> spacing;
};

/// The regular grid points form: its distinct x, y and z values (increasing) and, per point, its
/// node's index (x fastest).
struct CompleteGrid {
  std::array<std::vector<double>, 3> axes;
  std::vector<std::size_t> node;
};
/// The grid, if the points form a complete one: at least 2 distinct values of each coordinate
/// and every combination of them exactly once (the voxel centres of an image); nullopt otherwise.
std::optional<CompleteGrid> complete_grid_of(const std::vector<Eigen::Vector3d>& points);
inline bool is_complete_grid(const std::vector<Eigen::Vector3d>& points) { return complete_grid_of(points).has_value(); }

/// How many primary knots the lattice layout (PointCloudDomainOptions::lattice) places for these
/// points and this primary_knots option: about as many as asked, but whole cells, so a few
/// more or fewer (91 for 40 on a cube).
std::size_t lattice_primary_knots(std::span<const Eigen::Vector3d> points, int primary_knots);

struct PointCloudDomain {
  /// The domain: positively oriented, every point used.
  TetrahedralMesh mesh;
  /// For each point of the mesh, the index of the data point it is (or was moved from by the
  /// jitter); -1 for a lattice point (`lattice`) or a point of a cut at an interface.
  std::vector<int> data_index;
  std::vector<VertexKind> kinds;
  /// Tetrahedra of the Delaunay tetrahedralisation before clipping.
  std::size_t delaunay_tetrahedra = 0;
};

/// The domain of §5.2 for these data points.
/// \throw InvalidInput for fewer than 4 points, coplanar points, non-finite coordinates
/// (naming `points[i]`), or when clipping leaves no tetrahedron.
PointCloudDomain point_cloud_domain(std::span<const Eigen::Vector3d> points, const PointCloudDomainOptions& options = {});

}  // namespace volspline
