#pragma once
// From a superset of a solid's boundary to the boundary itself: the boundary of the image S of
// a spline map (a folded trivariate solid, a swept solid) lies on a set of sheets that also has
// pieces inside S (Joy–Duchaineau 1999 and Conkey–Joy 2000 stop there). The sheets are cut along
// all their mutual intersections (CGAL's exact autorefinement of the triangle soup), so that every
// piece is wholly on the boundary or wholly inside; each piece is then classified by a certified
// membership test of two points just off it, on the true surface's side of each, and kept, with
// its outward side out, only when exactly one of them is outside S. Sheets that cover the same
// part of the boundary twice (symmetric generators make them) are kept once. docs/envelopes.md.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/core/progress.h"
#include "volspline/mesh/self_intersections.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct SupersetTrimmingOptions {
  /// Distance of the two test points from the surface, relative to the superset's bounding-box
  /// diagonal: small against every feature, large against the membership test's resolution.
  double offset = 1e-6;
  /// Relative to the diagonal: two kept pieces closer than this (and parallel) are one sheet of
  /// the boundary covered twice; the smaller one is dropped.
  double duplicate_distance = 1e-3;
  /// Test points per piece (the largest triangles); the majority of decided answers counts.
  int samples_per_piece = 3;
  Progress* progress = nullptr;
};

struct SupersetTrimmingStats {
  std::int64_t superset_triangles = 0, refined_triangles = 0, result_triangles = 0;
  /// Pieces: connected parts of one sheet between intersection curves.
  std::int64_t pieces = 0, pieces_boundary = 0, pieces_inside = 0, pieces_outside = 0, pieces_duplicate = 0,
               pieces_undecided = 0;
  std::int64_t membership_queries = 0;
  /// Contouring: queries of points asked before (answered from memory, not counted above).
  std::int64_t membership_queries_remembered = 0;
  /// Vertex tags (the parameters of the map a vertex lies on, SweptEnvelope::times and
  /// patches included): how many were moved to a preimage within the tolerance of their vertex
  /// (interpolated tags), how many found none (left as they were), and the largest distance
  /// from a vertex to the image of its tag after that.
  std::int64_t tags_corrected = 0, tags_beyond_tolerance = 0;
  double largest_tag_distance = 0;
  /// The result: closed (every edge shared by two triangles), consistently oriented, free of
  /// self-intersections (CGAL, after rounding to doubles), its connected components and volume.
  bool closed = false, oriented = false, self_intersection_free = false;
  std::int64_t boundary_edges = 0, nonmanifold_edges = 0, self_intersecting_pairs = 0;
  int components = 0;
  double volume = 0;
  /// Where the result is open: up to a few boundary-edge midpoints, "x y z; ...".
  std::string open_at;
  double seconds_refine = 0, seconds_classify = 0, seconds_checks = 0;
  /// Contouring only (extract/image_contouring.h): the grid spacing (absolute), grid cells and
  /// corners examined, the corners whose label was inferred from a neighbour's (not asked), grid edges where the boundary was found without a superset sheet
  /// crossing them (placed by bisection instead), crossings placed on a sheet by Newton, those
  /// found on a sheet only after bisection (the superset's triangles missed the crossing), and
  /// crease vertices and edge flips.
  double cell_size = 0;
  std::int64_t grid_cells = 0, grid_corners = 0, grid_corners_inferred = 0, crossings_off_superset = 0, crossings_on_sheets = 0,
               crossings_after_bisection = 0, crease_vertices = 0, crease_flips = 0;
  /// Contouring: rounds in which crease flips or fans that made self-intersecting faces were undone.
  std::int64_t crease_repairs = 0;
  /// Contouring with adaptive cells (ImageContouringOptions::coarse_ratio > 1): coarse cells split
  /// into fine ones (grid_cells counts the complex's cells, coarse and fine).
  std::int64_t grid_cells_refined = 0;
  /// Contouring: the coarse cells' width in fine cells (1: a uniform grid) and the narrowest
  /// width bends were split to (ImageContouringOptions::coarse_ratio, crease_width).
  int coarse_ratio = 1, crease_width = 1;
  /// ... and the times the contour was made again with more cells refined where the verification
  /// found edges farther than the tolerance from the boundary.
  std::int64_t grid_adaptations = 0;
  /// ... and whether the last adaptation asked for was refused as growing the complex more than
  /// ImageContouringOptions::max_adaptation_growth times past max_adaptation_floor cells (the
  /// edges beyond the tolerance stay, counted).
  bool grid_adaptation_refused = false;
  /// Contouring with refinement toward the sheets (extract/sheet_refinement.h): the tolerance
  /// (absolute), rounds, edges split, edges whose sheet point was not found, edges left above
  /// the tolerance and the largest distance left.
  double refinement_tolerance = 0;
  std::int64_t refinement_rounds = 0, refinement_splits = 0, refinement_failed_edges = 0, refinement_edges_above_tolerance = 0,
               refinement_unresolved_edges = 0, refinement_edges_verified = 0, refinement_edges_beyond_tolerance = 0;
  double refinement_largest_remaining = 0, seconds_sheet_refinement = 0;
  /// Contouring: cells (or tetrahedra) across a crease whose crease point could not be put on
  /// the curve where its two sheets meet (no fan, a corner of three sheets, or Newton failed):
  /// chamfered there by up to about the cell size.
  std::int64_t crease_cells_unsnapped = 0;
  /// Swept envelopes: grids contoured (1: the coarse grid with refinement was kept; 2: it was
  /// not, and the fine grid was used) and why the coarse one was not kept.
  int grid_passes = 1;
  std::string coarse_grid_rejected;
};

/// Where on the true surface a point of the superset is: for superset triangle `triangle` and
/// barycentric coordinates b (b sums to 1), the point of the sheet it approximates, and the
/// extra parameter (t of a swept solid; 0 when there is none) interpolated there.
using SupersetSurfacePoint = std::function<Eigen::Vector3d(std::size_t triangle, const Eigen::Vector3d& barycentric)>;
/// Is x in S? true inside, false outside, nullopt undecided (certified both ways).
using ImageMembershipTest = std::function<std::optional<bool>(const Eigen::Vector3d& x)>;

struct TrimmedBoundary {
  /// The boundary pieces, outward, welded; parts and parameters from the superset triangles
  /// they were cut from (parameters interpolated at new vertices).
  TriangleMesh mesh;
  /// The superset's extra per-vertex parameter, interpolated likewise (empty if none given).
  std::vector<double> extra;
  /// Per vertex, a corner of the superset triangle it lies on (for tags such as a patch).
  std::vector<int> source_vertex;
  SupersetTrimmingStats stats;
};

/// Fills the result half of `stats` for `mesh`: triangles, closed, oriented, boundary and
/// non-manifold edges (and where it is open), components, volume, self-intersections (CGAL's
/// exact predicates on the doubles), and, if asked, the self-intersecting pairs of triangle
/// indices. With `record`, the self-intersection test looks only where the mesh differs from
/// the one the record was last filled from (mesh/self_intersections.h), with the same answer.
/// \throw InvalidInput for a malformed mesh.
void measure_trimmed_boundary(const TriangleMesh& mesh, SupersetTrimmingStats& stats,
                              std::vector<std::pair<std::size_t, std::size_t>>* intersecting_faces = nullptr,
                              SelfIntersectionRecord* record = nullptr);

/// Trims `superset` (any orientation, non-manifold edges allowed) to the boundary of S.
/// `extra` is an optional per-vertex parameter (empty or one per vertex). The membership test
/// is called from several threads at once. \throw InvalidInput for a malformed superset or
/// options out of range.
TrimmedBoundary trim_superset(const TriangleMesh& superset, const std::vector<double>& extra,
                              const SupersetSurfacePoint& surface_point, const ImageMembershipTest& inside,
                              const SupersetTrimmingOptions& options = {});

}  // namespace volspline
