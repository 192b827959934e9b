// The swept envelope against analytic answers: a box translated along a segment sweeps the convex
// hull of its two end positions.
#include "volspline/extract/swept_envelope.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "volspline/construct/primitives.h"
#include "volspline/construct/swept_examples.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

// s(u, v, w, t) = (a u, b v, c w) + t D, degree 1 in every direction.
BSplineHypervolume translated_box_map(const Eigen::Vector3d& size, const Eigen::Vector3d& d) {
  std::vector<double> points;
  for (int l = 0; l < 2; ++l)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const Eigen::Vector3d x = Eigen::Vector3d(i * size.x(), j * size.y(), k * size.z()) + l * d;
          points.insert(points.end(), {x.x(), x.y(), x.z()});
        }
  return BSplineHypervolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3,
                            points);
}

// x is in the hull of the box [0, size] and its translate by d iff some t in [0, 1] puts x - t d
// in the box: an intersection of intervals of t.
bool in_translated_box_hull(const Eigen::Vector3d& x, const Eigen::Vector3d& size, const Eigen::Vector3d& d) {
  double lo = 0, hi = 1;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0) {
      if (x[i] < 0 || x[i] > size[i]) return false;
      continue;
    }
    double a = (x[i] - size[i]) / d[i], b = x[i] / d[i];
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a);
    hi = std::min(hi, b);
  }
  return lo <= hi;
}

// The box [1, 2] x [-1/2, 1/2] x [0, 1] turned a full revolution about z: four exact quarter
// arcs in t, M_l g with M_l the rotation's control matrices.
BSplineHypervolume revolving_box() {
  const double h = std::sqrt(0.5);
  const std::array<std::array<double, 3>, 9> arc{{{1, 0, 1}, {1, 1, h}, {0, 1, 1}, {-1, 1, h}, {-1, 0, 1}, {-1, -1, h}, {0, -1, 1}, {1, -1, h}, {1, 0, 1}}};
  std::vector<double> points, weights;
  for (int l = 0; l < 9; ++l)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const double x = 1 + i, y = j - 0.5, z = k;
          const double c = arc[static_cast<std::size_t>(l)][0], sn = arc[static_cast<std::size_t>(l)][1];
          points.insert(points.end(), {c * x - sn * y, sn * x + c * y, z});
          weights.push_back(arc[static_cast<std::size_t>(l)][2]);
        }
  return BSplineHypervolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1),
                             KnotVector(2, {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1})},
                            3, points, weights);
}

// The superset of the revolving box: the faces z = 0, 1 turn in their own planes (Jacobian
// identically zero, skipped), and the only folds are where the faces x = 1 and x = 2 move
// tangentially, y = 0: the cylinders r = 1 and r = 2.
TEST(SweptEnvelope, RevolvingBoxFoldsOnTheCylindersOfItsFaceMidlines) {
  const std::vector<BSplineHypervolume> patches{revolving_box()};
  const SweptEnvelope superset = swept_envelope_superset(patches);
  const SweptEnvelopeStats& st = superset.stats;
  EXPECT_EQ(st.degenerate_three_faces, 2);
  EXPECT_EQ(st.rank_deficient_triangles, 0);
  EXPECT_EQ(st.cap_fold_triangles, 0);
  ASSERT_GT(st.face_sweep_fold_triangles, 0);
  const double r_out = std::sqrt(4.25);
  for (std::size_t f = 0; f < superset.mesh.num_triangles(); ++f) {
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(superset.mesh.triangles[f][static_cast<std::size_t>(j)]);
      const Eigen::Vector3d& x = superset.mesh.positions[v];
      const double r = std::hypot(x.x(), x.y());
      // Everything lies in the annulus; the folds on r = 1 or r = 2 to the tolerance.
      EXPECT_GE(r, 1 - 1e-9);
      EXPECT_LE(r, r_out + 1e-9);
      EXPECT_GE(x.z(), -1e-12);
      EXPECT_LE(x.z(), 1 + 1e-12);
      // Fold vertices of the faces u = 0, 1 (x = 1, 2): u at its end, v and w inside.
      if (superset.mesh.parts[f] == part_number(Part::SweepFace) &&
          (superset.mesh.parameters[v][0] == 0 || superset.mesh.parameters[v][0] == 1) && superset.mesh.parameters[v][1] > 0 &&
          superset.mesh.parameters[v][1] < 1 && superset.mesh.parameters[v][2] > 0 && superset.mesh.parameters[v][2] < 1) {
        EXPECT_NEAR(r, superset.mesh.parameters[v][0] == 0 ? 1.0 : 2.0, 2e-3) << x.transpose();
      }
    }
  }
}

// A ball of radius r moved by d: its generator does not fold (the centre and poles only touch
// J = 0), so the superset has no rank-deficient part and no cap folds; the face sweep of the
// sphere folds where d is tangent to it, on the cylinder of radius r about the segment.
TEST(SweptEnvelope, TranslatedBallFoldsOnTheCapsulesCylinder) {
  const double r = 0.5;
  const Eigen::Vector3d d(1.2, 0.3, -0.2);
  const BSplineVolume g = ball(r);
  std::vector<double> points, weights;
  for (int l = 0; l < 2; ++l)
    for (int i = 0; i < g.num_control_points_total(); ++i) {
      const auto ui = static_cast<std::size_t>(i);
      points.insert(points.end(), {g.points()[3 * ui] + l * d.x(), g.points()[3 * ui + 1] + l * d.y(), g.points()[3 * ui + 2] + l * d.z()});
      weights.push_back(g.weights()[ui]);
    }
  const std::vector<BSplineHypervolume> patches{BSplineHypervolume(
      {g.knot_vector(0), g.knot_vector(1), g.knot_vector(2), KnotVector::bezier(1)}, 3, points, weights)};
  const SweptEnvelope superset = swept_envelope_superset(patches);
  const SweptEnvelopeStats& st = superset.stats;
  EXPECT_EQ(st.rank_deficient_triangles, 0);
  EXPECT_EQ(st.cap_fold_triangles, 0);
  ASSERT_GT(st.face_sweep_fold_triangles, 0);
  const double diagonal = 2 * r * std::sqrt(3.0) + d.norm();
  std::size_t fold_vertices = 0;
  for (std::size_t f = 0; f < superset.mesh.num_triangles(); ++f) {
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(superset.mesh.triangles[f][static_cast<std::size_t>(j)]);
      const Eigen::Vector3d& x = superset.mesh.positions[v];
      const double t = std::clamp(x.dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double distance = (x - t * d).norm();
      EXPECT_LE(distance, r * (1 + 1e-9));  // the superset lies in the capsule
      // Fold vertices of the sphere's sweep (u = 1, the other three parameters inside; the poles
      // v = 0, 1 are degenerate: J vanishes there too, and their sheets map to the poles' paths):
      // on the cylinder, to the tolerance.
      const Eigen::Vector3d& p = superset.mesh.parameters[v];
      const double tv = superset.times[v];
      if (superset.mesh.parts[f] == part_number(Part::SweepFace) && p[0] == 1 && p[1] > 1e-9 && p[1] < 1 - 1e-9 && p[2] > 0 && p[2] < 1 &&
          tv > 0 && tv < 1) {
        ++fold_vertices;
        EXPECT_NEAR(distance, r, 1e-3 * diagonal) << x.transpose() << " at " << p.transpose() << " " << tv;
      }
    }
  }
  EXPECT_GT(fold_vertices, 100u);
}

// The trimming finds the sheets from the superset's triangles and assumes them within twice the
// tolerance of their sheets (ImageContouringOptions::superset_error). The folds' chords bend
// away from the sheet by the square of their cells' size, so at fine tolerances the cells must
// shrink with the tolerance: at level 3 whatever the tolerance, the capsule's fold chords stood
// 8.2e-4 of the diagonal off the cylinder, more than twice 1e-4, and at --tol 1e-4 the
// trimming put vertices there (docs/envelopes.md, "Fine tolerances").
TEST(SweptEnvelope, FoldChordsStayWithinTheSupersetErrorAtFineTolerances) {
  // examples/swept-translated-ball.json: a ball of radius 1 moved by (3, 0, 0).
  const double r = 1;
  const Eigen::Vector3d d(3, 0, 0);
  const std::vector<BSplineHypervolume> patches = swept_patches(translated_ball(r, d));
  for (const double tolerance : {1e-3, 1e-4}) {
    SweptEnvelopeOptions options;
    options.tolerance = tolerance;
    const SweptEnvelope superset = swept_envelope_superset(patches, options);
    const auto [low, high] = superset.mesh.bounding_box();
    const double diagonal = (high - low).norm();
    double farthest = 0;
    std::size_t chords = 0;
    for (std::size_t f = 0; f < superset.mesh.num_triangles(); ++f) {
      if (superset.mesh.parts[f] != part_number(Part::SweepFace)) continue;
      // Fold triangles of the sphere's sweep: every corner at u = 1 with v, w and t inside.
      bool fold = true;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int j = 0; j < 3; ++j) {
        const auto v = static_cast<std::size_t>(superset.mesh.triangles[f][static_cast<std::size_t>(j)]);
        const Eigen::Vector3d& p = superset.mesh.parameters[v];
        fold = fold && p[0] == 1 && p[1] > 1e-9 && p[1] < 1 - 1e-9 && p[2] > 0 && p[2] < 1 && superset.times[v] > 1e-9 &&
               superset.times[v] < 1 - 1e-9;
        centroid += superset.mesh.positions[v] / 3;
      }
      if (!fold) continue;
      const double t = std::clamp(centroid.dot(d) / d.squaredNorm(), 0.0, 1.0);
      farthest = std::max(farthest, std::abs((centroid - t * d).norm() - r));
      ++chords;
    }
    EXPECT_GT(chords, 100u) << tolerance;
    EXPECT_LE(farthest, 2 * tolerance * diagonal) << tolerance;
  }
}

TEST(SweptEnvelope, AutomaticAdaptiveRatioKeepsTheCoarseCellsDownTo4e5) {
  EXPECT_EQ(automatic_adaptive_ratio(1e-2), 4);
  EXPECT_EQ(automatic_adaptive_ratio(1e-3), 4);
  EXPECT_EQ(automatic_adaptive_ratio(5e-4), 8);
  EXPECT_EQ(automatic_adaptive_ratio(3e-4), 16);
  EXPECT_EQ(automatic_adaptive_ratio(1e-4), 32);
  EXPECT_EQ(automatic_adaptive_ratio(1e-6), 64);
  // Coarse cells of 3 x tolerance x ratio: between 0.012 / sqrt 2 and 0.012 sqrt 2 of the
  // diagonal down to 4.5e-5 (then the ratio stays 64).
  for (double tolerance = 4.5e-5; tolerance <= 1e-3; tolerance *= 1.05) {
    const double coarse = 3 * tolerance * automatic_adaptive_ratio(tolerance);
    EXPECT_GE(coarse, 0.0084) << tolerance;
    EXPECT_LE(coarse, 0.017) << tolerance;
  }
  EXPECT_THROW(automatic_adaptive_ratio(0), InvalidInput);
  SweptEnvelopeOptions bad;
  bad.crease_width = -1;
  EXPECT_THROW(swept_envelope(swept_patches(translated_box({1, 1, 1}, {1, 0, 0})), bad), InvalidInput);
  bad = {};
  bad.adaptive_ratio = 66;
  EXPECT_THROW(swept_envelope(swept_patches(translated_box({1, 1, 1}, {1, 0, 0})), bad), InvalidInput);
}

TEST(SweptEnvelope, TranslatedBoxIsTheHullOfItsEndPositions) {
  const Eigen::Vector3d size(1.0, 0.6, 0.4), d(0.7, 0.5, -0.3);
  const BSplineHypervolume s = translated_box_map(size, d);
  SweptEnvelopeOptions options;
  const SweptEnvelope superset = swept_envelope_superset({s}, options);
  EXPECT_EQ(superset.stats.rank_deficient_triangles, 0);
  EXPECT_GT(superset.stats.cap_face_triangles, 0);
  EXPECT_GT(superset.stats.edge_sweep_triangles, 0);
  const TrimmedBoundary trimmed = trim_superset(
      superset.mesh, superset.times,
      [&](std::size_t t, const Eigen::Vector3d& b) { return swept_envelope_point({s}, superset, t, b); },
      [&](const Eigen::Vector3d& x) { return std::optional<bool>(in_translated_box_hull(x, size, d)); });
  const SupersetTrimmingStats& st = trimmed.stats;
  EXPECT_TRUE(st.closed) << st.boundary_edges << " boundary edges at " << st.open_at;
  EXPECT_TRUE(st.oriented);
  EXPECT_TRUE(st.self_intersection_free) << st.self_intersecting_pairs;
  EXPECT_EQ(st.components, 1);
  const double exact = size.prod() + std::abs(d.x()) * size.y() * size.z() + std::abs(d.y()) * size.x() * size.z() +
                       std::abs(d.z()) * size.x() * size.y();
  EXPECT_NEAR(st.volume, exact, 1e-9 * exact);
  EXPECT_NEAR(enclosed_volume(trimmed.mesh), exact, 1e-9 * exact);
  // Every vertex on the hull's boundary: the hull is convex and contains its centre, so a point
  // of the boundary moved a little towards the centre is inside, moved away outside.
  const Eigen::Vector3d centre = 0.5 * size + 0.5 * d;
  for (const auto& x : trimmed.mesh.positions) {
    EXPECT_TRUE(in_translated_box_hull(x + 1e-9 * (centre - x), size, d)) << x.transpose();
    EXPECT_FALSE(in_translated_box_hull(x - 1e-9 * (centre - x), size, d)) << x.transpose();
  }
}

// The whole pipeline on the library's swept solid: certified membership (SplineImage) instead
// of the analytic one, the same exact hull.
TEST(SweptEnvelope, TrimmedWithCertifiedMembershipTheTranslatedBoxIsItsHull) {
  const Eigen::Vector3d size(0.8, 0.5, 0.6), d(-0.4, 0.9, 0.35);
  const SweptEnvelope e = swept_envelope(swept_patches(translated_box(size, d)));
  const SupersetTrimmingStats& st = e.stats.trimming;
  EXPECT_TRUE(st.closed) << st.boundary_edges << " boundary edges at " << st.open_at;
  EXPECT_TRUE(st.oriented);
  EXPECT_TRUE(st.self_intersection_free);
  EXPECT_EQ(st.components, 1);
  EXPECT_EQ(st.pieces_undecided, 0);
  const double exact = size.prod() + std::abs(d.x()) * size.y() * size.z() + std::abs(d.y()) * size.x() * size.z() +
                       std::abs(d.z()) * size.x() * size.y();
  EXPECT_NEAR(enclosed_volume(e.mesh), exact, 1e-9 * exact);
  ASSERT_EQ(e.times.size(), e.mesh.num_vertices());
  // Tags: every vertex's (u, v, w, t) maps to it.
  const auto patches = swept_patches(translated_box(size, d));
  for (std::size_t v = 0; v < e.mesh.num_vertices(); ++v) {
    const auto& p = e.mesh.parameters[v];
    const Eigen::VectorXd x = patches[0].evaluate({p[0], p[1], p[2], e.times[v]});
    EXPECT_LE((Eigen::Vector3d(x[0], x[1], x[2]) - e.mesh.positions[v]).norm(), 1e-12);
  }
  // Trimming a superset computed beforehand gives the same boundary as the whole pipeline.
  const SweptEnvelope superset = swept_envelope_superset(patches);
  const SweptEnvelope again = trim_swept_envelope(patches, superset);
  EXPECT_EQ(again.mesh.positions, e.mesh.positions);
  EXPECT_EQ(again.mesh.triangles, e.mesh.triangles);
  EXPECT_EQ(again.mesh.parts, e.mesh.parts);
  EXPECT_EQ(again.times, e.times);
  EXPECT_EQ(again.stats.trimming.volume, st.volume);
  SweptEnvelopeOptions bad;
  bad.contour_cell_factor = 0;
  EXPECT_THROW(trim_swept_envelope(patches, superset, bad), InvalidInput);
}

// The output does not depend on how the threads were scheduled. The paper's Fig. 5 (a cylinder
// tumbled along a line) at 3e-3 adapts its grid once, from edges the parallel verification finds
// in an order that varies between runs; which cells that splits once depended on that order.
TEST(SweptEnvelope, OneThreadAndManyGiveTheSameMesh) {
  const auto patches = swept_patches(tumbling_cylinder());
  SweptEnvelopeOptions options;
  options.tolerance = 3e-3;
  const SweptEnvelope many = swept_envelope(patches, options);
  EXPECT_GE(many.stats.trimming.grid_adaptations, 1);
  SweptEnvelope one;
  {
    const tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
    one = swept_envelope(patches, options);
  }
  EXPECT_EQ(one.mesh.positions, many.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, many.mesh.triangles);
  EXPECT_EQ(one.mesh.parts, many.mesh.parts);
  EXPECT_EQ(one.times, many.times);
  EXPECT_EQ(one.stats.trimming.grid_cells, many.stats.trimming.grid_cells);
}

// An adaptation that would grow the grid more than max_adaptation_growth times (past the floor)
// is not made: the edges beyond the tolerance stay, counted, and the result is the contour before
// it. Fig. 5 at 3e-3 adapts once (the test above); with growth 1 and no floor it may not.
TEST(SweptEnvelope, AnAdaptationGrowingTheGridPastItsBoundIsRefusedAndCounted) {
  const auto patches = swept_patches(tumbling_cylinder());
  SweptEnvelopeOptions options;
  options.tolerance = 3e-3;
  options.max_adaptation_growth = 1;
  options.max_adaptation_floor = 0;
  const SweptEnvelope refused = swept_envelope(patches, options);
  const SupersetTrimmingStats& t = refused.stats.trimming;
  EXPECT_TRUE(t.grid_adaptation_refused);
  EXPECT_EQ(t.grid_adaptations, 0);
  EXPECT_GT(t.refinement_edges_beyond_tolerance, 0);
  EXPECT_TRUE(t.closed && t.oriented && t.self_intersection_free);
  options.max_adaptation_growth = 4;
  options.max_adaptation_floor = 1000000;
  const SweptEnvelope adapted = swept_envelope(patches, options);
  EXPECT_FALSE(adapted.stats.trimming.grid_adaptation_refused);
  EXPECT_GE(adapted.stats.trimming.grid_adaptations, 1);
  EXPECT_GT(adapted.stats.trimming.grid_cells, t.grid_cells);
  EXPECT_LE(adapted.stats.trimming.grid_cells, 4 * t.grid_cells);
  // Growth 1 but a floor above the grid: made.
  options.max_adaptation_growth = 1;
  options.max_adaptation_floor = 1000000000;
  const SweptEnvelope floored = swept_envelope(patches, options);
  EXPECT_FALSE(floored.stats.trimming.grid_adaptation_refused);
  EXPECT_EQ(floored.stats.trimming.grid_cells, adapted.stats.trimming.grid_cells);
  options.max_adaptation_growth = 0.5;
  EXPECT_THROW(swept_envelope(patches, options), InvalidInput);
  options.max_adaptation_growth = 4;
  options.max_adaptation_floor = -1;
  EXPECT_THROW(swept_envelope(patches, options), InvalidInput);
}

// Coarse cells wider than 4 units: the adaptations are graded toward the points the
// verification found (refine_cells_at), in whatever order the threads found them; bends are split
// only to crease_width. The same mesh from one thread and many.
TEST(SweptEnvelope, GradedAdaptationsGiveTheSameMeshOnOneThreadAndMany) {
  const auto patches = swept_patches(tumbling_cylinder());
  SweptEnvelopeOptions options;
  options.tolerance = 2e-3;
  options.adaptive_ratio = 16;
  const SweptEnvelope many = swept_envelope(patches, options);
  EXPECT_GE(many.stats.trimming.grid_adaptations, 1);
  EXPECT_EQ(many.stats.trimming.coarse_ratio, 16);
  EXPECT_EQ(many.stats.trimming.crease_width, 4);
  EXPECT_TRUE(many.stats.trimming.closed && many.stats.trimming.oriented && many.stats.trimming.self_intersection_free);
  SweptEnvelope one;
  {
    const tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
    one = swept_envelope(patches, options);
  }
  EXPECT_EQ(one.mesh.positions, many.mesh.positions);
  EXPECT_EQ(one.mesh.triangles, many.mesh.triangles);
  EXPECT_EQ(one.stats.trimming.grid_cells, many.stats.trimming.grid_cells);
}

}  // namespace
}  // namespace volspline
