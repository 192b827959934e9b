#pragma once
// The implicit part of a trivariate solid's boundary, the surface where the Jacobian determinant
// vanishes (Joy–Duchaineau 1999, Theorem 4.1): found by adaptive subdivision with certified bounds
// (§6) and extracted by crack-free marching tetrahedra on conforming tetrahedra (§7,
// mesh/conforming_tetrahedra.h) — or, for comparison, by marching tetrahedra of J sampled on a
// uniform grid (the brute-force way, as IRIT does). The whole boundary, faces included, is
// extract/solid_boundary.h. docs/boundary.md.
#include <array>
#include <cstdint>

#include "volspline/analysis/jacobian_subdivision.h"
#include "volspline/core/progress.h"
#include "volspline/mesh/parts.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

enum class ZeroSurfaceMethod { Adaptive, Uniform };

/// When the adaptive subdivision stops splitting a cell that the zero set may cross.
enum class StopCriterion {
  /// Bezier bounds only: when J is within tolerance * scale / 2 of an affine function on the
  /// cell (JacobianSubdivision::nonlinearity), so that linear interpolation by the marching
  /// tetrahedra is off by at most tolerance * scale; splits follow §6 (gradient variation).
  Flatness,
  /// The paper's §6 rule: when the width of the bound of J is at most tolerance * scale; splits
  /// go where |J_d| * size is largest. Cells then shrink to about tolerance / |grad J| all along
  /// the surface, flat or not.
  Width,
};

struct BoundaryOptions {
  JacobianBoundMethod bounds = JacobianBoundMethod::Bezier;
  ZeroSurfaceMethod method = ZeroSurfaceMethod::Adaptive;
  /// Flatness for Bezier bounds; cone bounds always use Width.
  StopCriterion stop = StopCriterion::Flatness;
  /// Adaptive: relative to scale, the largest |J| bound over the domain (see StopCriterion).
  double tolerance = 1e-3;
  /// Adaptive: budget of cells examined (bounded); the cells still queued when it runs out are
  /// kept as they are.
  std::int64_t max_cells = 200000;
  /// Adaptive: a cell the zero set may cross is split until it is at most 2^-min_level of its
  /// Bézier piece in every direction, whatever its bound, so that the surface is sampled finely
  /// enough to follow the geometry of the map even where J is nearly affine.
  int min_level = 3;
  /// Uniform: samples per direction are resolution + 1 (resolution^3 cubes, 6 tetrahedra each).
  int resolution = 64;
  /// Move every implicit vertex onto J = 0 by Newton steps in the domain before mapping it.
  bool snap = false;
  /// Samples per direction of the face patches (as tessellate_faces).
  int face_resolution = 24;
  /// Receives the phases "subdivision" (adaptive; counts cells), "sampling" (uniform),
  /// "tetrahedra", "marching", "snap", "mapping" and, for solid_boundary, "faces". Null: nobody
  /// listens.
  Progress* progress = nullptr;
};

struct BoundaryStats {
  std::int64_t cells_examined = 0;
  std::int64_t cells_kept = 0;
  /// Triangles per part number: Part::UMin..WMax the faces, Part::JacobianZero the implicit
  /// surface (mesh/parts.h); triangles_of reads it by part.
  std::array<std::int64_t, 7> triangles{};
  std::int64_t triangles_of(Part part) const { return triangles[static_cast<std::size_t>(part_number(part))]; }
  /// Largest |J| at implicit vertices over the largest |J| in the domain (sampled on a 17^3
  /// grid and at the vertices).
  double max_rel_jacobian_at_vertices = 0;
  /// Largest first-order distance |J| / |grad J| of an implicit vertex to J = 0, in the domain.
  double max_domain_distance = 0;
  /// Seconds per phase.
  double seconds_subdivision = 0, seconds_tetrahedra = 0, seconds_isosurface = 0, seconds_snap = 0, seconds_faces = 0,
         seconds_total = 0;
};

struct SolidBoundary {
  /// Parts Part::UMin..WMax the face patches (unless only the implicit surface was asked for),
  /// Part::JacobianZero the implicit surface; every vertex carries its (u, v, w).
  TriangleMesh mesh;
  BoundaryStats stats;
};

/// The implicit part alone (Part::JacobianZero). \throw InvalidInput for a volume not in R^3,
/// options out of range, or cone bounds on a rational volume.
SolidBoundary jacobian_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options = {});

}  // namespace volspline
