#pragma once
// The envelope of a swept trivariate solid S = s([0,1]^4), s(u,v,w,t) = c(t) + R(t) g(u,v,w)
// (Conkey–Joy 2000, eq. 1), one 4-variate spline per generator patch (construct/swept_solid.h).
//
// The superset (§3): by the implicit function theorem every boundary point of S is the image of
//  - a point of a 2-face of the 4-cube domain (24 squares: the caps' faces at t = 0, 1 and the
//    surfaces swept by the generator's edges), or
//  - a point where one of the eight 3-faces (the caps t = 0, 1 and the six face sweeps
//    s(0,v,w,t), ...) folds: the Jacobian of that trivariate map vanishes (Joy–Duchaineau 1999,
//    Theorem 4.1, found by extract/jacobian_zero_surface.h), or
//  - an interior point where J123 = J124 = J134 = J234 = 0 (§5–6, extract/rank_deficient_surface.h).
// The paper lists the boundaries of the eight 3-face solids; taking each 2-face once (it bounds
// two 3-faces) gives the same set without the duplicate sheets. A 3-face whose Jacobian vanishes
// identically (a face moving within its own plane) is skipped: its image is a surface whose
// points all lie on images of its 2-faces (its fibres are curves that end on them).
//
// The trimmed envelope (beyond the paper), by a certified point-in-image test
// (analysis/point_in_image.h) either way:
//  - contouring (extract/image_contouring.h): membership on a grid near the superset, marching
//    tetrahedra with vertices where grid edges cross the superset; closed, 2-manifold and
//    oriented by construction, whatever the sheets do (coincide, touch tangentially);
//  - the arrangement (extract/superset_trimming.h): the superset cut along all its mutual
//    intersections, each piece kept if points just off it on one side are outside S; exact
//    (the translated box's hull to 1e-9) but it breaks down where curved sheets coincide.
// Automatic takes the arrangement for polyhedral sweeps (every patch polynomial of degree 1)
// when its result is closed, oriented and free of self-intersections, else contouring.
// docs/envelopes.md, "Trimming".
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volspline/core/progress.h"
#include "volspline/extract/image_contouring.h"
#include "volspline/extract/jacobian_zero_surface.h"
#include "volspline/extract/sheet_line_crossing.h"
#include "volspline/extract/superset_trimming.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

enum class EnvelopeTrimming { Automatic, Arrangement, Contouring };

struct SweptEnvelopeOptions {
  /// Relative to the diagonal of the control points' bounding box: the chord error the face
  /// tessellations aim at and the cell size of the implicit parts.
  double tolerance = 1e-3;
  /// Bernstein coefficients (certified) or the paper's cone bounds, for the 3-face zero surfaces
  /// and the rank-deficient set alike.
  JacobianBoundMethod bounds = JacobianBoundMethod::Bezier;
  /// Budget of cells examined by each adaptive subdivision (the 3-face zero surfaces and the
  /// 4-dimensional rank-deficient set); reached budgets are reported in the statistics.
  std::int64_t max_cells = 2000000;
  /// Samples per direction of the 2-faces are chosen from the second derivatives so that the
  /// chord error is about tolerance, between these bounds.
  int min_samples = 4, max_samples = 256;
  /// Trim to the true boundary (otherwise the paper's superset).
  bool trim = true;
  /// The superset with the sweeps of faces two generator patches share from opposite sides
  /// (extract/interior_face_sweeps.h): the paper's superset has them; they lie inside the swept
  /// volume, so the trimming leaves them out (swept_envelope computes none, trim_swept_envelope
  /// drops any it is given).
  bool interior_faces = true;
  EnvelopeTrimming trimming_method = EnvelopeTrimming::Automatic;
  SupersetTrimmingOptions trimming;
  /// Contouring: grid spacing in multiples of `tolerance` (the other contouring options as
  /// `contouring` says; its cell_size and superset_error are set from tolerance).
  double contour_cell_factor = 3;
  /// Contouring on a coarse grid instead (this many multiples of `tolerance`; 0: not, the
  /// default), its edges refined toward the sheets to refinement_factor × tolerance
  /// (extract/sheet_refinement.h): the grid sets the topology, the sheets' equations the
  /// accuracy of smooth parts. Kept when closed, oriented and free of self-intersections
  /// (otherwise the grid of contour_cell_factor is used, unrefined); creases it cannot resolve
  /// are chamfered and counted (`refinement_unresolved_edges`). docs/envelopes.md, "Refinement
  /// toward the sheets".
  double coarse_cell_factor = 0;
  /// Adaptive cells (the default; an even number up to 64, kAutomaticRatio, or 0 for the uniform
  /// grid of contour_cell_factor): cells this many times the grid of contour_cell_factor, split into it
  /// where the contour bends by more than the crease angle or the verification finds an edge
  /// beyond the tolerance (ImageContouringOptions::coarse_ratio), edges refined toward the
  /// sheets as with coarse_cell_factor. Kept when closed, oriented and free of
  /// self-intersections (otherwise the uniform grid of contour_cell_factor is used, unrefined).
  /// Not used when coarse_cell_factor > 0. docs/envelopes.md, "Adaptive cells".
  /// kAutomaticRatio (the default): automatic_adaptive_ratio(tolerance), coarse cells 0.85–1.7 %
  /// of the diagonal down to tolerance 4.4e-5 (the ratio is at most 64).
  static constexpr int kAutomaticRatio = -1;
  int adaptive_ratio = kAutomaticRatio;
  /// With adaptive cells: the narrowest width (units of the fine grid) that cells where the
  /// contour bends are split to before the verification asks for more
  /// (ImageContouringOptions::crease_width); 0 (the default): a quarter of the adaptive ratio used,
  /// at least 1 (with the automatic ratio the width of 1e-3's fine cells: 1 at 1e-3 and above, 8
  /// at 1e-4).
  int crease_width = 0;
  /// With adaptive cells: the bound on an adaptation's growth of the grid
  /// (ImageContouringOptions::max_adaptation_growth, max_adaptation_floor; these override the
  /// same fields of `contouring` in the adaptive pass).
  double max_adaptation_growth = 4;
  std::int64_t max_adaptation_floor = 1000000;
  double refinement_factor = 0.25;
  ImageContouringOptions contouring;
  Progress* progress = nullptr;
};

struct SweptEnvelopeStats {
  /// Superset triangles per source: 2-faces of the caps, 2-faces swept by edges, zero surfaces
  /// of the caps, of the face sweeps, and the rank-deficient set.
  std::int64_t cap_face_triangles = 0, edge_sweep_triangles = 0, cap_fold_triangles = 0, face_sweep_fold_triangles = 0,
               rank_deficient_triangles = 0;
  /// 3-faces whose Jacobian vanishes identically (skipped, see above).
  int degenerate_three_faces = 0;
  /// 3-faces whose Jacobian keeps a weak sign: they do not fold (no zero surface to extract).
  int fold_free_three_faces = 0;
  /// 3-faces left out as interior (SweptEnvelopeOptions::interior_faces false): their folds
  /// and their squares at t = 0 and 1.
  int interior_face_sweeps = 0;
  /// Cells of the 3-face zero surfaces and of the rank-deficient set.
  std::int64_t cells_examined = 0, cells_kept = 0;
  std::int64_t rank_cells_examined = 0, rank_cells_kept = 0;
  /// Parts of rank cells tested while they were split (RankDeficientStats::part_cells_examined).
  std::int64_t rank_part_cells_examined = 0;
  /// Minors divided by the factor of a collapsed domain face (RankDeficientStats).
  int rank_minors_divided_by_faces = 0;
  /// Triangles of the rank-deficient set made from lattice 2-faces (RankDeficientStats).
  std::int64_t rank_lattice_face_triangles = 0;
  bool budget_reached = false;
  std::array<int, 4> samples{};
  double seconds_faces = 0, seconds_folds = 0, seconds_rank_deficient = 0, seconds_total = 0;
  SupersetTrimmingStats trimming;
  /// Which trimming gave the result (Automatic never appears).
  EnvelopeTrimming trimmed_by = EnvelopeTrimming::Automatic;
};

struct SweptEnvelope {
  /// Parts Part::SweepCap, SweepFace, SweepRankDeficient (mesh/parts.h); parameters (u, v, w).
  TriangleMesh mesh;
  /// t per vertex.
  std::vector<double> times;
  /// Which generator patch each vertex comes from.
  std::vector<int> patches;
  /// The superset only (empty once trimmed): per triangle, the sheet it approximates (a square:
  /// two fixed parameters; a fold of a 3-face: one fixed and fold; the rank-deficient set: none
  /// fixed), for Newton onto the true sheet (extract/sheet_line_crossing.h).
  std::vector<SupersetSheet> sheets;
  SweptEnvelopeStats stats;
};

/// The superset of the boundary of s(domain) for one or more 4-variate patches, every vertex
/// with its (u, v, w, t). \throw InvalidInput for no patches, a patch not in R^3, or options out
/// of range; as rank_deficient_surface for a generator that is not a volume.
SweptEnvelope swept_envelope_superset(const std::vector<BSplineHypervolume>& patches,
                                      const SweptEnvelopeOptions& options = {});

/// The point of the envelope's sheet under `triangle` at `barycentric`: s at the interpolated
/// (u, v, w, t) on the patch of the triangle's first vertex (clamped to the domain). \throw
/// std::out_of_range for a triangle or patch that does not exist.
Eigen::Vector3d swept_envelope_point(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& envelope,
                                     std::size_t triangle, const Eigen::Vector3d& barycentric);

/// The superset trimmed to the boundary of the union of the patches' images (options.trim), or
/// the superset (!options.trim). \throw as swept_envelope_superset.
SweptEnvelope swept_envelope(const std::vector<BSplineHypervolume>& patches, const SweptEnvelopeOptions& options = {});

/// The adaptive ratio SweptEnvelopeOptions::kAutomaticRatio stands for: 4 at tolerances of 1e-3
/// and above, and below that 4 x the power of two nearest 1e-3 / tolerance, at most 64 (32 at
/// 1e-4). The coarse cells set the topology, the refinement toward the sheets the accuracy, so
/// the coarse cells need not shrink with the tolerance: with 4 at 1e-4 the capsule takes 59 s
/// and 5.8 million triangles, with 32 3.3 s and 192,000 (docs/envelopes.md, "Fine tolerances").
int automatic_adaptive_ratio(double tolerance);

/// swept_envelope's trimming of a superset already computed by swept_envelope_superset(patches,
/// options) (with the same patches and options), for callers that want both without computing
/// the superset twice. \throw InvalidInput for options out of range.
SweptEnvelope trim_swept_envelope(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& superset,
                                  const SweptEnvelopeOptions& options = {});

}  // namespace volspline
