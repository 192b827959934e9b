#include "volspline/extract/swept_envelope.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <exception>
#include <unordered_map>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include "volspline/analysis/jacobian_bezier.h"
#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/analysis/point_in_image.h"
#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/extract/image_membership.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/extract/interior_face_sweeps.h"
#include "volspline/extract/rank_deficient_surface.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/iso_restriction.h"

namespace volspline {

namespace {

using Clock = std::chrono::steady_clock;

using Parameter4 = std::array<double, 4>;

double control_diagonal(const std::vector<BSplineHypervolume>& patches) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& s : patches) {
    const auto& p = s.points();
    for (std::size_t i = 0; i + 2 < p.size(); i += 3) {
      const Eigen::Vector3d x(p[i], p[i + 1], p[i + 2]);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }
  return (hi - lo).norm();
}

// Samples per direction: the chord error of a segment of length h along direction d is about
// |s_dd| h^2 / 8, so h = sqrt(8 tol / max |s_dd|) (sampled on a 5^4 grid of the domain), merged
// with the breakpoints (face_samples) so that every Bézier piece is sampled.
std::array<std::vector<double>, 4> envelope_samples(const BSplineHypervolume& s, double tol_abs, const SweptEnvelopeOptions& o) {
  std::array<std::vector<double>, 4> grid;
  for (int d = 0; d < 4; ++d)
    for (int i = 0; i <= 4; ++i) grid[static_cast<std::size_t>(d)].push_back(s.domain_min(d) + (s.domain_max(d) - s.domain_min(d)) * i / 4);
  const auto values = s.evaluate_grid(grid, 2);
  const auto alphas = derivative_multi_indices<4>(2);
  const std::size_t n = 625;
  std::array<std::vector<double>, 4> samples;
  for (int d = 0; d < 4; ++d) {
    std::array<int, 4> second{};
    second[static_cast<std::size_t>(d)] = 2;
    const std::size_t alpha = static_cast<std::size_t>(std::find(alphas.begin(), alphas.end(), second) - alphas.begin());
    double m = 0;
    for (std::size_t p = 0; p < n; ++p) {
      const double* x = values.data() + (alpha * n + p) * 3;
      m = std::max(m, Eigen::Vector3d(x[0], x[1], x[2]).norm());
    }
    const double length = s.domain_max(d) - s.domain_min(d);
    const int count = m > 0 ? static_cast<int>(std::ceil(length / std::sqrt(8 * tol_abs / m))) : 1;
    samples[static_cast<std::size_t>(d)] = face_samples(s.knot_vector(d), std::clamp(count, o.min_samples, o.max_samples));
  }
  return samples;
}

// Whether the trivariate map's Jacobian vanishes identically: |J| on a 17^3 grid is below
// 1e-9 of |V_a| |V_b| |V_c| there (a nonzero polynomial of lower degree cannot vanish on the grid).
bool jacobian_vanishes_identically(const BSplineVolume& v) {
  std::array<std::vector<double>, 3> grid;
  for (int d = 0; d < 3; ++d)
    for (int i = 0; i <= 16; ++i) grid[static_cast<std::size_t>(d)].push_back(v.domain_min(d) + (v.domain_max(d) - v.domain_min(d)) * i / 16);
  const auto g = v.evaluate_grid(grid, 1);
  const std::size_t n = 17 * 17 * 17;
  double j = 0, scale = 0;
  for (std::size_t p = 0; p < n; ++p) {
    j = std::max(j, std::abs(jacobian_determinant(g.data() + 3 * p, static_cast<std::ptrdiff_t>(3 * n))));
    double product = 1;
    for (std::size_t a = 1; a <= 3; ++a) {
      const double* x = g.data() + (a * n + p) * 3;
      product *= Eigen::Vector3d(x[0], x[1], x[2]).norm();
    }
    scale = std::max(scale, product);
  }
  return j <= 1e-9 * scale;
}

// Whether J keeps a weak sign on the whole volume (every Bernstein coefficient of every piece on
// one side, up to its proven error bound and 1e-10 of the largest): then the trivariate map does
// not fold, and J = 0 only where it touches zero (degenerate faces of a ball or a cylinder),
// which bounds nothing (the rule of RankCertificate::NoFold, docs/envelopes.md).
bool jacobian_keeps_weak_sign(const BSplineVolume& v) {
  const double input_error = extraction_error_bound(v);
  std::vector<JacobianBernstein> pieces;
  double largest = 0;
  for (const BSplineVolume& piece : bezier_pieces(v.translated_to_local_origin())) {
    pieces.push_back(jacobian_bezier_coefficients(piece, input_error));
    for (double c : pieces.back().coefficients.coefficients) largest = std::max(largest, std::abs(c));
  }
  bool positive = true, negative = true;
  for (const JacobianBernstein& j : pieces) {
    const double margin = j.error_bound + 1e-10 * largest;
    for (double c : j.coefficients.coefficients) {
      positive = positive && c >= -margin;
      negative = negative && c <= margin;
    }
  }
  return positive || negative;
}

// The superset of one patch into `out`.
// Whether face (direction, end) of patch `patch` is among `faces`.
bool listed_face(const std::vector<PatchFace>& faces, int patch, int direction, int end) {
  return std::find(faces.begin(), faces.end(), PatchFace{patch, direction, end}) != faces.end();
}

// The folds of a patch's eight 3-faces s(c = 0 or 1) (Joy–Duchaineau's implicit surface of each
// trivariate solid), or why a face has none: face f is direction f / 2 at end f % 2.
enum class FaceFolds { Interior, Degenerate, FoldFree, Found };
struct PatchFolds {
  std::array<FaceFolds, 8> kind{};
  std::array<SolidBoundary, 8> boundary;
};

// Face job % 8 of patch job / 8, for three_face_folds.
void face_folds_of(const std::vector<BSplineHypervolume>& patches, const std::vector<PatchFace>& interior, const BoundaryOptions& zero,
                   std::size_t job, std::vector<PatchFolds>& folds) {
  const std::size_t patch = job / 8, f = job % 8;
  const BSplineHypervolume& s = patches[patch];
  const int c = static_cast<int>(f / 2), end = static_cast<int>(f % 2);
  FaceFolds& kind = folds[patch].kind[f];
  if (c < 3 && listed_face(interior, static_cast<int>(patch), c, end)) {
    kind = FaceFolds::Interior;
    return;
  }
  const BSplineVolume cube = restrict_to_iso(s, c, end ? s.domain_max(c) : s.domain_min(c));
  if (jacobian_vanishes_identically(cube)) {
    kind = FaceFolds::Degenerate;
  } else if (jacobian_keeps_weak_sign(cube)) {
    kind = FaceFolds::FoldFree;
  } else {
    kind = FaceFolds::Found;
    folds[patch].boundary[f] = jacobian_zero_surface(cube, zero);
  }
}

// All patches' 3-faces are independent: their folds are found in one parallel pass (the torus's
// four patches have one folded face each), then appended patch by patch in face order, so the
// output does not depend on the threads.
std::vector<PatchFolds> three_face_folds(const std::vector<BSplineHypervolume>& patches, const SweptEnvelopeOptions& options,
                                         const std::vector<PatchFace>& interior) {
  BoundaryOptions zero;
  // The zero surfaces' flatness tolerance is on J relative to its scale; linear interpolation in
  // cells that flat places vertices within about tolerance of the surface.
  zero.tolerance = std::min(0.05, 10 * options.tolerance);
  // The flatness of J says nothing of how far the map bends across a cell, so the triangles'
  // chords stand off the fold by about the square of the cell's size: the capsule's cylinder
  // 8.2e-4 of the diagonal at level 3. The contouring assumes the superset within 2 x the
  // tolerance of the sheets (superset_error) and finds no sheet crossing where it is farther,
  // so below 1e-3 the cells go one level finer for every factor 4 (the chords' error falls
  // with the tolerance; docs/envelopes.md, "Fine tolerances").
  // At most 12 (tolerances down to about 1e-12; BoundaryOptions allows 20).
  zero.min_level = std::min(12, 3 + (options.tolerance < 1e-3 ? static_cast<int>(std::ceil(0.5 * std::log2(1e-3 / options.tolerance) - 1e-9)) : 0));
  zero.max_cells = options.max_cells;
  zero.bounds = options.bounds;
  zero.snap = true;
  std::vector<PatchFolds> folds(patches.size());
  // A job's error is kept and the first in patch and face order rethrown, as the serial loop did
  // (TBB would rethrow whichever it caught first).
  std::vector<std::exception_ptr> errors(8 * patches.size());
  tbb::parallel_for(std::size_t{0}, 8 * patches.size(), [&](std::size_t job) {
    try {
      face_folds_of(patches, interior, zero, job, folds);
    } catch (...) {
      errors[job] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return folds;
}

// The superset of one patch into `out`, without the sweeps of the faces in `interior` (their
// folds and their squares at t = 0 and 1; the squares their edges sweep stay, as those edges
// bound other faces too); `folds`: its 3-faces' folds (three_face_folds).
void patch_superset(const BSplineHypervolume& s, int patch_index, double tol_abs, const SweptEnvelopeOptions& options,
                    const std::vector<PatchFace>& interior, const PatchFolds& folds, SweptEnvelope& out) {
  SweptEnvelopeStats& stats = out.stats;
  const auto samples = envelope_samples(s, tol_abs, options);
  for (int d = 0; d < 4; ++d)
    stats.samples[static_cast<std::size_t>(d)] = std::max(stats.samples[static_cast<std::size_t>(d)], static_cast<int>(samples[static_cast<std::size_t>(d)].size()));

  // The 24 squares, sampled on the common per-direction samples so that squares sharing an edge
  // share its vertices (one vertex per 4-index).
  auto faces_start = Clock::now();
  std::array<std::size_t, 4> count{};
  for (int d = 0; d < 4; ++d) count[static_cast<std::size_t>(d)] = samples[static_cast<std::size_t>(d)].size();
  std::unordered_map<std::uint64_t, int> vertex_of;
  std::vector<Parameter4> params;
  auto vertex = [&](const std::array<std::size_t, 4>& i) {
    const std::uint64_t key = ((i[0] * count[1] + i[1]) * count[2] + i[2]) * count[3] + i[3];
    const auto [it, fresh] = vertex_of.try_emplace(key, static_cast<int>(params.size()));
    if (fresh) params.push_back({samples[0][i[0]], samples[1][i[1]], samples[2][i[2]], samples[3][i[3]]});
    return it->second;
  };
  struct Tri {
    std::array<int, 3> v;
    Part part;
    SupersetSheet sheet;
  };
  std::vector<Tri> tris;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      std::array<int, 2> fixed{};
      int k = 0;
      for (int d = 0; d < 4; ++d)
        if (d != a && d != b) fixed[static_cast<std::size_t>(k++)] = d;
      const Part part = (fixed[0] == 3 || fixed[1] == 3) ? Part::SweepCap : Part::SweepFace;
      const SupersetSheet sheet{static_cast<std::uint8_t>((1 << fixed[0]) | (1 << fixed[1])), false};
      for (int end0 = 0; end0 < 2; ++end0)
        for (int end1 = 0; end1 < 2; ++end1) {
          if (fixed[1] == 3 && listed_face(interior, patch_index, fixed[0], end0)) continue;
          std::array<std::size_t, 4> idx{};
          idx[static_cast<std::size_t>(fixed[0])] = end0 ? count[static_cast<std::size_t>(fixed[0])] - 1 : 0;
          idx[static_cast<std::size_t>(fixed[1])] = end1 ? count[static_cast<std::size_t>(fixed[1])] - 1 : 0;
          for (std::size_t i = 0; i + 1 < count[static_cast<std::size_t>(a)]; ++i)
            for (std::size_t j = 0; j + 1 < count[static_cast<std::size_t>(b)]; ++j) {
              auto at = [&](std::size_t di, std::size_t dj) {
                std::array<std::size_t, 4> q = idx;
                q[static_cast<std::size_t>(a)] = i + di;
                q[static_cast<std::size_t>(b)] = j + dj;
                return vertex(q);
              };
              const int v00 = at(0, 0), v10 = at(1, 0), v01 = at(0, 1), v11 = at(1, 1);
              tris.push_back({{v00, v10, v11}, part, sheet});
              tris.push_back({{v00, v11, v01}, part, sheet});
              ++(part == Part::SweepCap ? stats.cap_face_triangles : stats.edge_sweep_triangles);
              ++(part == Part::SweepCap ? stats.cap_face_triangles : stats.edge_sweep_triangles);
            }
        }
    }
  const std::vector<double> x = s.evaluate_points(params, 0);
  const int base = static_cast<int>(out.mesh.num_vertices());
  for (std::size_t v = 0; v < params.size(); ++v) {
    out.mesh.add_vertex(Eigen::Vector3d(x[3 * v], x[3 * v + 1], x[3 * v + 2]), Eigen::Vector3d(params[v][0], params[v][1], params[v][2]));
    out.times.push_back(params[v][3]);
    out.patches.push_back(patch_index);
  }
  for (const Tri& t : tris) {
    out.mesh.add_triangle(base + t.v[0], base + t.v[1], base + t.v[2], t.part);
    out.sheets.push_back(t.sheet);
  }
  stats.seconds_faces += seconds_since(faces_start);

  // The folds of the eight 3-faces (Joy–Duchaineau's implicit surface of each trivariate solid).
  const auto folds_start = Clock::now();
  const std::array<FaceFolds, 8>& face_kind = folds.kind;
  const std::array<SolidBoundary, 8>& face_folds = folds.boundary;
  for (int c = 0; c < 4; ++c)
    for (int end = 0; end < 2; ++end) {
      const double value = end ? s.domain_max(c) : s.domain_min(c);
      const auto ff = static_cast<std::size_t>(2 * c + end);
      if (face_kind[ff] == FaceFolds::Interior) {
        ++stats.interior_face_sweeps;
        continue;
      }
      if (face_kind[ff] == FaceFolds::Degenerate) {
        ++stats.degenerate_three_faces;
        continue;
      }
      if (face_kind[ff] == FaceFolds::FoldFree) {
        ++stats.fold_free_three_faces;
        continue;
      }
      const SolidBoundary& z = face_folds[ff];
      stats.cells_examined += z.stats.cells_examined;
      stats.cells_kept += z.stats.cells_kept;
      if (z.stats.cells_examined >= options.max_cells) stats.budget_reached = true;
      const Part part = c == 3 ? Part::SweepCap : Part::SweepFace;
      const int zbase = static_cast<int>(out.mesh.num_vertices());
      for (std::size_t v = 0; v < z.mesh.num_vertices(); ++v) {
        Parameter4 p{};
        int k = 0;
        for (int d = 0; d < 4; ++d) p[static_cast<std::size_t>(d)] = d == c ? value : z.mesh.parameters[v][k++];
        out.mesh.add_vertex(z.mesh.positions[v], Eigen::Vector3d(p[0], p[1], p[2]));
        out.times.push_back(p[3]);
        out.patches.push_back(patch_index);
      }
      for (const auto& t : z.mesh.triangles) {
        out.mesh.add_triangle(zbase + t[0], zbase + t[1], zbase + t[2], part);
        out.sheets.push_back({static_cast<std::uint8_t>(1 << c), true});
      }
      (c == 3 ? stats.cap_fold_triangles : stats.face_sweep_fold_triangles) += static_cast<std::int64_t>(z.mesh.num_triangles());
    }
  stats.seconds_folds += seconds_since(folds_start);

  // The rank-deficient set inside the 4-cube (§5–6). Marching is linear on cells of 2^-L of a
  // Bézier piece, so its error is about (2^-L)^2 of the piece's size: L from sqrt(tolerance).
  const auto rank_start = Clock::now();
  RankDeficientOptions rank;
  rank.bounds = options.bounds;
  rank.tolerance = std::min(0.25, std::sqrt(options.tolerance));
  rank.max_cells = options.max_cells;
  rank.progress = options.progress;
  const RankDeficientSurface r = rank_deficient_surface(s, rank);
  stats.rank_cells_examined += r.stats.cells_examined;
  stats.rank_cells_kept += r.stats.cells_kept;
  stats.rank_part_cells_examined += r.stats.part_cells_examined;
  stats.rank_minors_divided_by_faces += r.stats.minors_divided_by_faces;
  stats.rank_lattice_face_triangles += r.stats.lattice_face_triangles;
  if (r.stats.budget_exhausted) stats.budget_reached = true;
  const int rbase = static_cast<int>(out.mesh.num_vertices());
  for (std::size_t v = 0; v < r.mesh.num_vertices(); ++v) {
    out.mesh.add_vertex(r.mesh.positions[v], r.mesh.parameters[v]);
    out.times.push_back(r.t[v]);
    out.patches.push_back(patch_index);
  }
  for (const auto& t : r.mesh.triangles) {
    out.mesh.add_triangle(rbase + t[0], rbase + t[1], rbase + t[2], Part::SweepRankDeficient);
    out.sheets.push_back({0, false});
  }
  stats.rank_deficient_triangles += static_cast<std::int64_t>(r.mesh.num_triangles());
  stats.seconds_rank_deficient += seconds_since(rank_start);
}

void check_patches(const std::vector<BSplineHypervolume>& patches, const SweptEnvelopeOptions& options) {
  if (patches.empty()) throw InvalidInput("expected at least one 4-variate patch", "patches");
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (patches[i].dimension() != 3)
      throw InvalidInput("expected control points in R^3, got dimension " + std::to_string(patches[i].dimension()),
                         "patches[" + std::to_string(i) + "]");
  if (!(options.tolerance > 0 && options.tolerance < 1)) throw InvalidInput("expected 0 < tolerance < 1", "tolerance");
  if (options.min_samples < 2 || options.max_samples < options.min_samples)
    throw InvalidInput("expected 2 <= min_samples <= max_samples", "samples");
  if (options.max_cells < 1) throw InvalidInput("expected a positive budget of cells", "max_cells");
}

void check_trimming_options(const SweptEnvelopeOptions& options) {
  if (!(options.contour_cell_factor > 0 && options.contour_cell_factor * options.tolerance < 0.5))
    throw InvalidInput("expected 0 < contour_cell_factor * tolerance < 0.5", "contour_cell_factor");
  if (!(options.coarse_cell_factor >= 0 && options.coarse_cell_factor * options.tolerance < 0.5))
    throw InvalidInput("expected 0 <= coarse_cell_factor * tolerance < 0.5", "coarse_cell_factor");
  if (options.adaptive_ratio != 0 && options.adaptive_ratio != SweptEnvelopeOptions::kAutomaticRatio &&
      (options.adaptive_ratio < 2 || options.adaptive_ratio > 64 || options.adaptive_ratio % 2 != 0))
    throw InvalidInput("expected 0 (off), kAutomaticRatio or an even adaptive ratio from 2 to 64", "adaptive_ratio");
  if (options.crease_width < 0 || options.crease_width > 64) throw InvalidInput("expected 0 (automatic) or a width from 1 to 64", "crease_width");
  if (!(options.max_adaptation_growth >= 1)) throw InvalidInput("expected an adaptation growth of at least 1", "max_adaptation_growth");
  if (options.max_adaptation_floor < 0) throw InvalidInput("expected a floor of 0 cells or more", "max_adaptation_floor");
  if (!(options.refinement_factor >= 0 && options.refinement_factor * options.tolerance < 0.5))
    throw InvalidInput("expected 0 <= refinement_factor * tolerance < 0.5", "refinement_factor");
}

// The superset without the triangles of interior face sweeps (interior_face_sweeps): the folds
// of those 3-faces and their squares at t = 0 and 1, told apart by their sheets; and without the
// repeats of squares (duplicate_squares) whose first is kept. Vertices are kept (unused ones are
// harmless).
SweptEnvelope without_interior_face_sweeps(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& superset) {
  const std::vector<PatchFace> interior = interior_face_sweeps(patches);
  const std::vector<RepeatedSquare> repeated = duplicate_squares(patches);
  if ((interior.empty() && repeated.empty()) || superset.sheets.size() != superset.mesh.num_triangles()) return superset;
  // A square at t = 0 or 1 of an interior face is dropped with the face.
  const auto interior_square = [&](const PatchSquare& q) {
    if (!(q.fixed & (1 << 3))) return false;
    for (int c = 0; c < 3; ++c)
      if (q.fixed == ((1 << c) | (1 << 3)) && listed_face(interior, q.patch, c, (q.at_max >> c) & 1)) return true;
    return false;
  };
  std::vector<PatchSquare> dropped_repeats;
  for (const RepeatedSquare& r : repeated)
    if (!interior_square(r.same_as)) dropped_repeats.push_back(r.square);
  SweptEnvelope out = superset;
  out.mesh.triangles.clear();
  out.mesh.parts.clear();
  out.sheets.clear();
  for (std::size_t t = 0; t < superset.mesh.num_triangles(); ++t) {
    const SupersetSheet& sheet = superset.sheets[t];
    const auto v0 = static_cast<std::size_t>(superset.mesh.triangles[t][0]);
    const int patch = superset.patches[v0];
    const auto& s = patches[static_cast<std::size_t>(patch)];
    const auto at_max = [&](int d) {
      const double value = d < 3 ? superset.mesh.parameters[v0][d] : superset.times[v0];
      return value > 0.5 * (s.domain_min(d) + s.domain_max(d)) ? 1 : 0;
    };
    bool drop = false;
    for (int c = 0; c < 3 && !drop; ++c) {
      const bool on_face = sheet.fold ? sheet.fixed == (1 << c) : sheet.fixed == ((1 << c) | (1 << 3));
      if (!on_face) continue;
      drop = listed_face(interior, patch, c, at_max(c));
    }
    if (!drop && !sheet.fold && std::popcount(static_cast<unsigned>(sheet.fixed)) == 2) {
      PatchSquare square{patch, sheet.fixed, 0};
      for (int d = 0; d < 4; ++d)
        if ((sheet.fixed >> d) & 1) square.at_max |= at_max(d) << d;
      drop = std::find(dropped_repeats.begin(), dropped_repeats.end(), square) != dropped_repeats.end();
    }
    if (drop) continue;
    out.mesh.triangles.push_back(superset.mesh.triangles[t]);
    out.mesh.parts.push_back(superset.mesh.parts[t]);
    out.sheets.push_back(sheet);
  }
  return out;
}

}  // namespace

SweptEnvelope swept_envelope_superset(const std::vector<BSplineHypervolume>& patches, const SweptEnvelopeOptions& options) {
  check_patches(patches, options);
  const auto start = Clock::now();
  SweptEnvelope out;
  const double tol_abs = options.tolerance * control_diagonal(patches);
  const std::vector<PatchFace> interior = options.interior_faces ? std::vector<PatchFace>{} : interior_face_sweeps(patches);
  const auto folds_start = Clock::now();
  const std::vector<PatchFolds> folds = three_face_folds(patches, options, interior);
  out.stats.seconds_folds = seconds_since(folds_start);
  for (std::size_t i = 0; i < patches.size(); ++i) patch_superset(patches[i], static_cast<int>(i), tol_abs, options, interior, folds[i], out);
  out.stats.seconds_total = seconds_since(start);
  return out;
}

Eigen::Vector3d swept_envelope_point(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& envelope,
                                     std::size_t triangle, const Eigen::Vector3d& barycentric) {
  const auto& tri = envelope.mesh.triangles.at(triangle);
  std::array<double, 4> p{};
  for (int j = 0; j < 3; ++j) {
    const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
    for (int k = 0; k < 3; ++k) p[static_cast<std::size_t>(k)] += barycentric[j] * envelope.mesh.parameters[v][k];
    p[3] += barycentric[j] * envelope.times[v];
  }
  const auto& s = patches.at(static_cast<std::size_t>(envelope.patches[static_cast<std::size_t>(tri[0])]));
  for (int d = 0; d < 4; ++d) p[static_cast<std::size_t>(d)] = std::clamp(p[static_cast<std::size_t>(d)], s.domain_min(d), s.domain_max(d));
  Eigen::Vector3d x;
  s.evaluate(p, x.data());
  return x;
}

SweptEnvelope swept_envelope(const std::vector<BSplineHypervolume>& patches, const SweptEnvelopeOptions& options) {
  check_trimming_options(options);
  if (!options.trim) return swept_envelope_superset(patches, options);
  // The trimming needs no interior sheets: computing them would cost time twice.
  SweptEnvelopeOptions without_interior = options;
  without_interior.interior_faces = false;
  return trim_swept_envelope(patches, swept_envelope_superset(patches, without_interior), options);
}

SweptEnvelope trim_swept_envelope(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& given,
                                  const SweptEnvelopeOptions& options) {
  check_trimming_options(options);
  const auto start = Clock::now();
  const SweptEnvelope superset = without_interior_face_sweeps(patches, given);
  const SplineImage<4> image(patches);
  const ImageMembershipTest inside = image_membership_test(image);
  auto finish = [&](TrimmedBoundary trimmed, EnvelopeTrimming method) {
    SweptEnvelope out;
    out.stats = superset.stats;
    out.stats.trimming = trimmed.stats;
    out.stats.trimmed_by = method;
    out.mesh = std::move(trimmed.mesh);
    out.times = std::move(trimmed.extra);
    for (int v : trimmed.source_vertex) out.patches.push_back(superset.patches[static_cast<std::size_t>(v)]);
    std::vector<Parameter4> tags(out.mesh.num_vertices());
    for (std::size_t v = 0; v < tags.size(); ++v)
      tags[v] = {out.mesh.parameters[v][0], out.mesh.parameters[v][1], out.mesh.parameters[v][2], out.times[v]};
    correct_vertex_tags<4>(image, out.mesh, tags, out.patches, options.tolerance * control_diagonal(patches), out.stats.trimming);
    for (std::size_t v = 0; v < tags.size(); ++v) {
      out.mesh.parameters[v] = Eigen::Vector3d(tags[v][0], tags[v][1], tags[v][2]);
      out.times[v] = tags[v][3];
    }
    out.stats.seconds_total += seconds_since(start);
    return out;
  };
  bool polyhedral = true;
  for (const auto& s : patches) {
    polyhedral = polyhedral && !s.is_rational();
    for (int d = 0; d < 4; ++d) polyhedral = polyhedral && s.knot_vector(d).degree() <= 1;
  }
  if (options.trimming_method == EnvelopeTrimming::Arrangement ||
      (options.trimming_method == EnvelopeTrimming::Automatic && polyhedral)) {
    const SupersetSurfacePoint surface_point = [&](std::size_t t, const Eigen::Vector3d& b) {
      return swept_envelope_point(patches, superset, t, b);
    };
    SupersetTrimmingOptions trimming = options.trimming;
    if (!trimming.progress) trimming.progress = options.progress;
    TrimmedBoundary trimmed = trim_superset(superset.mesh, superset.times, surface_point, inside, trimming);
    const SupersetTrimmingStats& t = trimmed.stats;
    if (options.trimming_method == EnvelopeTrimming::Arrangement ||
        (t.closed && t.oriented && t.self_intersection_free && t.pieces_undecided == 0))
      return finish(std::move(trimmed), EnvelopeTrimming::Arrangement);
  }
  ImageContouringOptions contouring = options.contouring;
  contouring.cell_size = options.contour_cell_factor * options.tolerance;
  contouring.superset_error = std::min(0.25, 2 * options.tolerance);
  if (!contouring.progress) contouring.progress = options.progress;
  // Vertices onto the true sheets: Newton on the sheet's own equations from given parameters.
  const SheetCrossingFrom exact_from = [&](std::size_t triangle, const Eigen::Vector4d& start, double lambda, const Eigen::Vector3d& a,
                                           const Eigen::Vector3d& b) -> std::optional<SheetCrossing> {
    const auto v0 = static_cast<std::size_t>(superset.mesh.triangles[triangle][0]);
    const auto& s = patches[static_cast<std::size_t>(superset.patches[v0])];
    const std::array<double, 4> p{start[0], start[1], start[2], start[3]};
    const auto c = sheet_line_crossing<4>(s, superset.sheets[triangle], p, lambda, a, b);
    if (!c) return std::nullopt;
    SheetCrossing x;
    x.lambda = c->lambda;
    x.parameters = Eigen::Vector3d(c->parameter[0], c->parameter[1], c->parameter[2]);
    x.extra = c->parameter[3];
    x.normal = c->normal;
    return x;
  };
  // ... from the (u, v, w, t) interpolated in the superset triangle, its fixed parameters exactly
  // at the first corner's value (a domain bound).
  const SupersetSheetCrossing exact = [&](std::size_t triangle, const Eigen::Vector3d& barycentric, double lambda,
                                          const Eigen::Vector3d& a, const Eigen::Vector3d& b) -> std::optional<SheetCrossing> {
    const auto& tri = superset.mesh.triangles[triangle];
    Eigen::Vector4d p = Eigen::Vector4d::Zero();
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
      p.head<3>() += barycentric[j] * superset.mesh.parameters[v];
      p[3] += barycentric[j] * superset.times[v];
    }
    const SupersetSheet& sheet = superset.sheets[triangle];
    const auto v0 = static_cast<std::size_t>(tri[0]);
    for (int d = 0; d < 4; ++d)
      if ((sheet.fixed >> d) & 1) p[d] = d < 3 ? superset.mesh.parameters[v0][d] : superset.times[v0];
    return exact_from(triangle, p, lambda, a, b);
  };
  // One number per sheet: the patch, the fixed parameters and the bounds they are fixed at, fold.
  std::vector<int> sheet_of_triangle;
  sheet_of_triangle.reserve(superset.sheets.size());
  for (std::size_t t = 0; t < superset.sheets.size(); ++t) {
    const SupersetSheet& sheet = superset.sheets[t];
    const auto v0 = static_cast<std::size_t>(superset.mesh.triangles[t][0]);
    const auto& s = patches[static_cast<std::size_t>(superset.patches[v0])];
    int at_max = 0;
    for (int d = 0; d < 4; ++d)
      if ((sheet.fixed >> d) & 1) {
        const double value = d < 3 ? superset.mesh.parameters[v0][d] : superset.times[v0];
        if (value > 0.5 * (s.domain_min(d) + s.domain_max(d))) at_max |= 1 << d;
      }
    sheet_of_triangle.push_back(((superset.patches[v0] * 16 + sheet.fixed) * 16 + at_max) * 2 + (sheet.fold ? 1 : 0));
  }
  // The coarse grid sets the topology and the creases; refinement toward the sheets the
  // accuracy of the smooth parts. Kept when closed, oriented and free of self-intersections;
  // edges it could not refine (chamfered creases, features between two crossings of a coarse
  // cell, failed Newton) are checked by membership tests at the tolerance and counted.
  std::string rejected;
  // Coarse cells wider than a quarter of the diagonal see nothing: the ratio is lowered to fit.
  int adaptive_ratio = options.adaptive_ratio == SweptEnvelopeOptions::kAutomaticRatio ? automatic_adaptive_ratio(options.tolerance)
                                                                                       : options.adaptive_ratio;
  while (adaptive_ratio >= 2 && adaptive_ratio * options.contour_cell_factor * options.tolerance >= 0.25) adaptive_ratio -= 2;
  if ((options.coarse_cell_factor > 0 || adaptive_ratio > 1) && options.refinement_factor > 0) {
    ImageContouringOptions coarse = contouring;
    if (options.coarse_cell_factor > 0) coarse.cell_size = options.coarse_cell_factor * options.tolerance;
    else coarse.coarse_ratio = adaptive_ratio;
    // Bends split down to a quarter of the coarse cells (the unit cells of 1e-3 with the
    // automatic ratio: 8 units at 1e-4, 1 at 1e-3), finer only where the verification asks
    // (docs/envelopes.md, "Fine tolerances").
    coarse.crease_width = options.crease_width > 0 ? options.crease_width : std::max(1, adaptive_ratio / 4);
    coarse.max_adaptation_growth = options.max_adaptation_growth;
    coarse.max_adaptation_floor = options.max_adaptation_floor;
    coarse.refinement_tolerance = options.refinement_factor * options.tolerance;
    coarse.verification_distance = options.tolerance;
    TrimmedBoundary trimmed = contour_image_boundary(superset.mesh, superset.times, inside, coarse, exact, sheet_of_triangle, exact_from);
    const SupersetTrimmingStats& t = trimmed.stats;
    if (!t.closed || !t.oriented) rejected = "not closed and oriented";
    else if (!t.self_intersection_free) rejected = std::to_string(t.self_intersecting_pairs) + " self-intersecting pairs";
    if (rejected.empty()) return finish(std::move(trimmed), EnvelopeTrimming::Contouring);
  }
  // The fine grid, unrefined: its chords are within the tolerance already.
  TrimmedBoundary trimmed = contour_image_boundary(superset.mesh, superset.times, inside, contouring, exact, sheet_of_triangle, exact_from);
  if (!rejected.empty()) {
    trimmed.stats.grid_passes = 2;
    trimmed.stats.coarse_grid_rejected = rejected;
  }
  return finish(std::move(trimmed), EnvelopeTrimming::Contouring);
}

int automatic_adaptive_ratio(double tolerance) {
  if (!(tolerance > 0)) throw InvalidInput("expected a positive tolerance", "tolerance");
  if (tolerance >= 1e-3) return 4;
  const int doublings = std::min(4, static_cast<int>(std::lround(std::log2(1e-3 / tolerance))));
  return 4 << doublings;
}

}  // namespace volspline
