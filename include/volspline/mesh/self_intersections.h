#pragma once
// Self-intersections of a triangle mesh by CGAL's exact predicates (Polygon Mesh Processing),
// and the same test repeated on a mesh that differs from an earlier one in a few triangles.
#include <array>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

/// What the last test of a mesh found: its vertices by position, its triangles by their vertices,
/// and the pairs of triangles that intersect. The contouring of swept envelopes measures its result after
/// every crease repair and grid adaptation, each of which changes a few percent of about
/// 200,000 triangles; with a record, the next test looks only at the pairs that involve a
/// triangle the earlier mesh did not have (docs/envelopes.md, "Checks that redo only what
/// changed"). A moved-from record is empty again.
class SelfIntersectionRecord {
 public:
  SelfIntersectionRecord();
  ~SelfIntersectionRecord();
  SelfIntersectionRecord(SelfIntersectionRecord&&) noexcept;
  SelfIntersectionRecord& operator=(SelfIntersectionRecord&&) noexcept;
  /// Triangles the last test with this record took from its record rather than testing them
  /// again (0 after a full test).
  std::size_t reused_triangles() const;
  /// Triangles the last test handed to CGAL.
  std::size_t tested_triangles() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
  friend std::vector<std::pair<std::size_t, std::size_t>> self_intersecting_triangles(const TriangleMesh&, SelfIntersectionRecord*);
};

/// The pairs (i, j), i < j, of triangles of `mesh` that intersect other than in the corners and
/// edges they share (CGAL::Polygon_mesh_processing::self_intersections, exact predicates on the
/// doubles), sorted. A mesh that is not a closed, consistently oriented 2-manifold is oriented as
/// a polygon soup first (which splits non-manifold vertices; triangles keep their indices).
///
/// With `record`, the answer is the same, found with less work where the mesh shares most
/// triangles with the mesh the record was last filled from: two triangles both in the earlier
/// mesh (the same three corner points) intersect now exactly when they did then, since
/// whether two triangles intersect depends on their corners alone, and corners shared then are
/// shared now (the record is used only where no two vertices of either mesh share a position).
/// So only the triangles new to this mesh, and the triangles whose boxes meet theirs, are
/// tested. The record is then filled from this mesh. \throw InvalidInput for a malformed mesh.
std::vector<std::pair<std::size_t, std::size_t>> self_intersecting_triangles(const TriangleMesh& mesh,
                                                                           SelfIntersectionRecord* record = nullptr);

}  // namespace volspline
