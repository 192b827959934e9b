#pragma once
// The boundary of the image S of a spline map as the contour of its certified membership
// (analysis/point_in_image.h) on a grid, with every vertex on a sheet of a superset of the
// boundary (a folded trivariate solid's faces and J = 0 surface, Joy–Duchaineau 1999; a swept
// solid's envelope, Conkey–Joy 2000): the robust alternative to cutting the superset along its
// mutual intersections (extract/superset_trimming.h), which breaks down where curved sheets
// coincide or touch tangentially.
//
// The boundary of S lies on the superset, so only grid cells near it are examined: the corners
// of every cell the superset passes within `superset_error` of are classified, inside or
// outside; cells with a mixed face grow the region until no mixed face is left on its border.
// Marching tetrahedra (six Kuhn tetrahedra per cube, the same diagonal in every cube, so
// neighbouring cells triangulate their common face alike) then give a closed, 2-manifold,
// consistently oriented surface by construction: it is a level set of a piecewise linear
// function at a regular value, each triangle inside one tetrahedron. Its vertices are where a
// grid edge from an inside corner to an outside one crosses the superset (the crossing between
// the last inside and first outside stretch, found by membership tests between crossings), so
// they carry the sheet's source and parameters. Given the sheets' equations (`sheet_crossing`), each
// vertex is moved onto the true sheet by Newton (extract/sheet_line_crossing.h) and checked
// against the bracket the membership tests left; where no sheet the superset holds near the edge
// crosses inside that bracket, the crossing is bisected with membership tests and the nearby
// sheets are tried again there. Sharp creases (normals of a tetrahedron's vertices more than
// `crease_angle_degrees` apart) get a vertex where the tangent planes meet (the quadric of
// dual contouring, Ju et al. 2002) and the edges across the crease are flipped to join those
// vertices (extended marching cubes, Kobbelt et al. 2001). docs/envelopes.md, "Trimming by
// contouring".
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "volspline/core/progress.h"
#include "volspline/extract/superset_trimming.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct ImageContouringOptions {
  /// Grid spacing relative to the superset's bounding-box diagonal. Smooth parts of the
  /// boundary come out within about 3 h^2 / (8 r) of the true surface (r the radius of
  /// curvature); sharp creases are cut by up to about h / 2.
  double cell_size = 4e-3;
  /// How far (relative to the diagonal) the true boundary may lie from the superset's
  /// triangles: cells within it are examined.
  double superset_error = 2e-3;
  /// Bisection steps along a grid edge the superset does not cross.
  int bisection_steps = 12;
  /// Adaptive cells: 1, a uniform grid of `cell_size`; an even number up to 64, cells this many
  /// times wider, split down to cells of `cell_size` where the contour bends by more than
  /// `crease_angle_degrees` or a vertex found no sheet (by halves, see `halving_levels`), with
  /// coned transition cells in between so that the complex stays conforming (docs/envelopes.md,
  /// "Adaptive cells"). Meant with the refinement toward the sheets, which makes the wider
  /// cells' chords accurate.
  int coarse_ratio = 1;
  /// With adaptive cells: split a coarse cell by halves, level by level, only where the contour
  /// still bends at that width (an octree; ratio 6: straight into unit cells after the coarse
  /// level); false: every split cell straight into ratio^3 unit cells.
  bool halving_levels = true;
  /// With adaptive cells by halves: bends are split level by level only while the halves are at
  /// least this wide (in units of `cell_size`; the coarse cells' first split into halves is always
  /// made); creases in wider cells are made by crease points on
  /// both sheets, and only where the verification finds an edge beyond the tolerance are cells
  /// split further, down to unit cells. 1 (the default): bends are split down to unit cells.
  int crease_width = 1;
  /// Budget of distinct grid cells (InvalidInput beyond it: choose a larger cell size).
  std::int64_t max_cells = 20000000;
  /// With adaptive cells: an adaptation is not made (and SupersetTrimmingStats::
  /// grid_adaptation_refused is set) if it would make the complex more than this many times
  /// larger, and more than max_adaptation_floor cells. The verification's adaptations are local
  /// repairs (a thin fin, a missed crease); edges beyond the tolerance all over the surface
  /// come from a superset that misses the boundary there, which splitting cannot mend, and were
  /// once split until 7 GB were used (docs/envelopes.md, "Adaptive cells").
  double max_adaptation_growth = 4;
  std::int64_t max_adaptation_floor = 1000000;
  /// Tetrahedra whose vertices' sheet normals differ by more than this get a crease vertex
  /// (only with sheet equations; 0 turns it off).
  double crease_angle_degrees = 30;
  /// With `sheet_crossing_from`: edges between two vertices on one sheet are split until their
  /// midpoints are within this distance (relative to the diagonal) of the sheet
  /// (extract/sheet_refinement.h); 0: no refinement.
  double refinement_tolerance = 0;
  /// With refinement: every edge whose distance refinement did not establish (at a crease point,
  /// across a crease, failed) is checked by membership tests at its midpoint, this far (relative
  /// to the diagonal) along the outward normal on either side: outside beyond, inside before,
  /// i.e. the boundary crosses that segment. Failures are counted
  /// (`refinement_edges_beyond_tolerance`); 0: no check.
  double verification_distance = 0;
  /// Corners joined by grid edges that no superset triangle comes within superset_error of
  /// share their membership (the boundary lies on the sheets): each such component is asked at
  /// its first and last corner only (every corner where those disagree), or takes the label of a
  /// corner classified before that it touches. false: every corner is asked.
  bool infer_labels = true;
  Progress* progress = nullptr;
};

/// A vertex on the sheet under a superset triangle: where the segment a + lambda (b - a) crosses
/// it, the sheet's parameters and extra parameter there, and its unit normal (zero if unknown).
struct SheetCrossing {
  double lambda = 0;
  Eigen::Vector3d parameters = Eigen::Vector3d::Zero();
  double extra = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};
/// The crossing of [a, b] with the sheet that superset triangle `triangle` approximates, from
/// the point at `barycentric` in it (at `lambda` on the segment); nothing if the sheet does not
/// cross the segment there. Called from several threads at once.
using SupersetSheetCrossing = std::function<std::optional<SheetCrossing>(std::size_t triangle, const Eigen::Vector3d& barycentric,
                                                                         double lambda, const Eigen::Vector3d& a,
                                                                         const Eigen::Vector3d& b)>;

/// The crossing of [a, b] with the sheet of superset triangle `triangle`, Newton started from
/// the sheet's parameters `start` (u, v, w, extra) at `lambda` on the segment; nothing if it
/// does not converge on the segment. Called from several threads at once.
using SheetCrossingFrom = std::function<std::optional<SheetCrossing>(std::size_t triangle, const Eigen::Vector4d& start, double lambda,
                                                                     const Eigen::Vector3d& a, const Eigen::Vector3d& b)>;

/// The boundary of S, outward, from the superset of it and a membership test for S (called
/// from several threads at once; undecided counts as inside). Output as trim_superset: parts,
/// parameters and `extra` from the sheet (`sheet_crossing`) or interpolated in the superset triangle each
/// vertex lies on, source_vertex its first corner, stats measured by measure_trimmed_boundary.
/// \throw InvalidInput for a malformed superset, `extra` not one per vertex, options out of
/// range or a grid beyond max_cells. `sheet_of_triangle` (optional, with sheet_crossing): per
/// superset triangle a number shared by the triangles of one sheet; each sheet within
/// superset_error of a crossed edge is then tried from its nearest triangle, also where its
/// chords miss the edge (\throw InvalidInput unless one per triangle). `sheet_crossing_from`
/// (optional, with both): the refinement toward the sheets of options.refinement_tolerance.
TrimmedBoundary contour_image_boundary(const TriangleMesh& superset, const std::vector<double>& extra,
                                       const ImageMembershipTest& inside, const ImageContouringOptions& options = {},
                                       const SupersetSheetCrossing& sheet_crossing = {},
                                       const std::vector<int>& sheet_of_triangle = {},
                                       const SheetCrossingFrom& sheet_crossing_from = {});

}  // namespace volspline
