#pragma once
// Refinement of a contoured boundary toward the sheets its vertices lie on, until every edge's
// chord is within a tolerance of the sheet: the contouring grid (extract/image_contouring.h)
// then sets only the topology and the creases, and the accuracy of the smooth parts comes from
// the sheets' own equations. A grid fine enough for the chords of the most curved part would be
// fine everywhere; this is fine only where the boundary bends (docs/envelopes.md, "Refinement
// toward the sheets").
//
// An edge whose two ends lie on one sheet is split where the sheet crosses the line through the
// chord's midpoint along the ends' mean normal (Newton on the sheet's equations from the mean of
// the ends' parameters), if that point is farther from the midpoint than the tolerance. Faces
// are split by the edges split (one edge: two faces; two: three; three: four), so neighbouring
// faces stay conforming and the mesh stays closed, 2-manifold and consistently oriented. An
// edge between two crease points on the same two sheets is split where the sheets meet in the
// plane normal to the edge through its midpoint (sheet_crease_point), so creases are refined
// along their curve. Edges touching a vertex on no sheet, or joining two sheets across a crease
// elsewhere, are never split.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "volspline/extract/image_contouring.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// Where a vertex lies on one sheet of the superset: sheet number `sheet` (-1: none),
/// `triangle` one of that sheet's superset triangles, `parameters` the sheet's exact (u, v, w,
/// extra) there, `normal` its unit normal (either sign).
struct SheetPoint {
  int sheet = -1;
  std::size_t triangle = 0;
  Eigen::Vector4d parameters = Eigen::Vector4d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// A vertex of the mesh being refined: on one sheet (on[0]), on two (a crease point where they
/// meet: on[0] and on[1]) or on none; `source` is passed on to split vertices.
struct SheetVertex {
  std::array<SheetPoint, 2> on{};
  int source = 0;
  /// Edges at this vertex are not split (a caller undoing refinement that made faces intersect).
  bool frozen = false;
};

/// The point where sheets a and b meet (a crease of the boundary) in the plane through x0
/// normal to `direction` (the crease's direction, roughly): Newton on the two sheets' traces in
/// that plane, each step a line crossing of each sheet (`crossing`, within `reach` of the
/// current point) and the meeting point of their tangent lines. Updates a and b to the point's
/// parameters and normals; nothing if a crossing fails or the iteration does not settle to
/// 1e-9 reach within 12 steps.
std::optional<Eigen::Vector3d> sheet_crease_point(const SheetCrossingFrom& crossing, SheetPoint& a, SheetPoint& b, const Eigen::Vector3d& x0,
                                                  const Eigen::Vector3d& direction, double reach);

struct SheetRefinementStats;
struct SheetRefinementOptions;

/// The splits refine_to_sheets computed, kept for later calls on meshes that share edges with
/// this one. The contouring of swept envelopes makes its contour again after every crease repair
/// and grid adaptation, and most edges come back with the same two ends; an edge's split point
/// depends on its ends alone (positions, sheet points, source, in the order of their vertex
/// numbers) and on the options, so an edge met again reuses it (docs/envelopes.md, "Checks that
/// redo only what changed"). Use one memory only with one `crossing` and one set of options.
/// Safe to fill from the parallel loops of one call; a moved-from memory is empty again.
class SheetRefinementMemory {
 public:
  SheetRefinementMemory();
  ~SheetRefinementMemory();
  SheetRefinementMemory(SheetRefinementMemory&&) noexcept;
  SheetRefinementMemory& operator=(SheetRefinementMemory&&) noexcept;
  /// Edges remembered.
  std::size_t size() const;
  /// Edges whose split came from memory, over the memory's life.
  std::size_t reused() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
  friend SheetRefinementStats refine_to_sheets(TriangleMesh&, std::vector<SheetVertex>&, const SheetCrossingFrom&,
                                               const SheetRefinementOptions&, std::vector<std::size_t>*);
};

struct SheetRefinementOptions {
  /// Largest distance (absolute) allowed between an edge's midpoint and the sheet.
  double tolerance = 1e-3;
  /// Edges shorter than this (absolute) are not split.
  double shortest_edge = 0;
  int max_rounds = 12;
  /// Edges between two sheets whose normals at the ends are at most this far apart (a seam of
  /// one smooth surface, e.g. between patches) are refined too, on either end's sheet.
  double seam_angle_degrees = 20;
  /// If positive: two points of one sheet whose normals are farther apart than this lie on two
  /// branches of it (the sheet crosses itself, making a crease of the boundary), and an edge
  /// between them is refined as across a crease, not along the sheet. Only for meshes whose
  /// edges are short against the sheets' curvature (a contour, whose cells call normals that far
  /// apart a crease); 0 (default): a sheet is one branch. Either way, of the sheets two vertices
  /// share, the pair of points whose normals agree best is refined along; crease edges are
  /// matched by sheet numbers, normals telling only one sheet's two branches apart.
  double branch_angle_degrees = 0;
  /// With a membership test: edges between two sheets whose normals are farther apart (up to
  /// 80°: a seam on a curved surface, or a crease) are split too where the split point is on
  /// the boundary, i.e. `inside` answers differently at check_distance on either side of it
  /// along its normal.
  ImageMembershipTest inside;
  double check_distance = 0;
  /// With a membership test: an edge across a crease that no crease point resolves (a
  /// chamfer) is split where its two sheets meet (sheet_crease_point, checked on the boundary).
  /// Off by default: on the paper's examples it made more faces intersect than it resolved
  /// (docs/envelopes.md).
  bool split_across_creases = false;
  /// Splits of earlier calls to reuse, and where this call's are kept (optional).
  SheetRefinementMemory* memory = nullptr;
};

struct SheetRefinementStats {
  int rounds = 0;
  std::int64_t split_edges = 0;
  /// Edges above the tolerance whose sheet point was not found (Newton failed or left the
  /// segment) and so were not split.
  std::int64_t failed_edges = 0;
  /// Edges that may stand off the boundary by more than the tolerance (estimated from their
  /// length and end normals as a circular arc) and could not be split: failed ones, and those
  /// across a crease that no crease point resolves.
  std::int64_t unresolved_edges = 0;
  /// Edges still above the tolerance when the rounds ran out, and the largest such distance.
  std::int64_t edges_above_tolerance = 0;
  double largest_remaining_distance = 0;
  /// Edges of the result whose distance from the boundary refinement did not establish: at a
  /// vertex on no sheet, between sheets it does not refine across, failed, or left above the
  /// tolerance (vertex pairs; none of them is split afterwards, so they are edges of the result).
  std::vector<std::array<int, 2>> unverified_edges;
};

/// Splits edges of `mesh` (one SheetVertex per vertex in `vertices`; both grow together, the
/// new vertices' mesh parameters are their (u, v, w)) until each edge between two vertices of
/// one sheet is within options.tolerance of the sheet at its midpoint. New faces keep their
/// parent's part and orientation; `face_origin` (optional) gets, per face of the result, the
/// index of the face of the input it lies in. \throw InvalidInput if `vertices` is not one per
/// vertex or the options are out of range.
SheetRefinementStats refine_to_sheets(TriangleMesh& mesh, std::vector<SheetVertex>& vertices, const SheetCrossingFrom& crossing,
                                      const SheetRefinementOptions& options, std::vector<std::size_t>* face_origin = nullptr);

}  // namespace volspline
