// The swept envelope against analytic answers: a box translated along a segment sweeps the convex
// hull of its two end positions.
#include "volspline/extract/swept_envelope.h"

#include <gtest/gtest.h>

#include "volspline/construct/primitives.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

// s(u, v, w, t) = (a u, b v, c w) + t D, degree 1 in every direction.
BSplineHypervolume translated_box(const Eigen::Vector3d& size, const Eigen::Vector3d& d) {
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

// The true point of a superset triangle at barycentric b: s at the interpolated (u, v, w, t).
SupersetSurfacePoint surface_point_of(const std::vector<BSplineHypervolume>& patches, const SweptEnvelope& e) {
  return [&patches, &e](std::size_t t, const Eigen::Vector3d& b) {
    const auto& tri = e.mesh.triangles[t];
    std::array<double, 4> p{};
    for (int j = 0; j < 3; ++j) {
      const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
      for (int k = 0; k < 3; ++k) p[static_cast<std::size_t>(k)] += b[j] * e.mesh.parameters[v][k];
      p[3] += b[j] * e.times[v];
    }
    const auto& s = patches[static_cast<std::size_t>(e.patches[static_cast<std::size_t>(tri[0])])];
    for (int d = 0; d < 4; ++d) p[static_cast<std::size_t>(d)] = std::clamp(p[static_cast<std::size_t>(d)], s.domain_min(d), s.domain_max(d));
    const Eigen::VectorXd x = s.evaluate(p);
    return Eigen::Vector3d(x[0], x[1], x[2]);
  };
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

TEST(SweptEnvelope, RevolvingBoxIsAnAnnulus) {
  const std::vector<BSplineHypervolume> patches{revolving_box()};
  const SweptEnvelope superset = swept_envelope_superset(patches);
  const double r_out = std::sqrt(4.25);
  const TrimmedBoundary trimmed = trim_superset(superset.mesh, superset.times, surface_point_of(patches, superset), [&](const Eigen::Vector3d& x) {
    const double r = std::hypot(x.x(), x.y());
    return std::optional<bool>(r >= 1 && r <= r_out && x.z() >= 0 && x.z() <= 1);
  });
  const SupersetTrimmingStats& st = trimmed.stats;
  std::cerr << "refine " << st.seconds_refine << " classify " << st.seconds_classify << " pieces " << st.pieces << " boundary " << st.pieces_boundary << " dup " << st.pieces_duplicate << " inside " << st.pieces_inside << " outside " << st.pieces_outside << " refined " << st.refined_triangles << " superset " << superset.mesh.num_triangles() << " degenerate3 " << superset.stats.degenerate_three_faces << " folds " << superset.stats.face_sweep_fold_triangles << "\n";
  EXPECT_TRUE(st.closed) << st.boundary_edges << " boundary edges at " << st.open_at << ", " << st.nonmanifold_edges << " non-manifold";
  EXPECT_TRUE(st.oriented);
  EXPECT_TRUE(st.self_intersection_free) << st.self_intersecting_pairs;
  const double exact = M_PI * (4.25 - 1);
  EXPECT_NEAR(st.volume, exact, 1e-2 * exact);
}

// A ball of radius r moved by d: a capsule.
TEST(SweptEnvelope, TranslatedBallIsACapsule) {
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
  { const auto& q = superset.stats; std::cerr << "capfaces " << q.cap_face_triangles << " edges " << q.edge_sweep_triangles << " capfolds " << q.cap_fold_triangles << " facefolds " << q.face_sweep_fold_triangles << " rank " << q.rank_deficient_triangles << " rankcells " << q.rank_cells_examined << " kept " << q.rank_cells_kept << " t " << q.seconds_faces << " " << q.seconds_folds << " " << q.seconds_rank_deficient << " samples " << q.samples[0] << " " << q.samples[1] << " " << q.samples[2] << " " << q.samples[3] << "\n"; }
  if (std::getenv("STOP")) return;
  const TrimmedBoundary trimmed = trim_superset(superset.mesh, superset.times, surface_point_of(patches, superset), [&](const Eigen::Vector3d& x) {
    const double t = std::clamp(x.dot(d) / d.squaredNorm(), 0.0, 1.0);
    return std::optional<bool>((x - t * d).norm() <= r);
  });
  const SupersetTrimmingStats& st = trimmed.stats;
  std::cerr << "refine " << st.seconds_refine << " classify " << st.seconds_classify << " pieces " << st.pieces << " boundary " << st.pieces_boundary << " dup " << st.pieces_duplicate << " inside " << st.pieces_inside << " outside " << st.pieces_outside << " undecided " << st.pieces_undecided << " refined " << st.refined_triangles << " superset " << superset.mesh.num_triangles() << " degenerate3 " << superset.stats.degenerate_three_faces << " folds " << superset.stats.face_sweep_fold_triangles << " capfolds " << superset.stats.cap_fold_triangles << " t " << superset.stats.seconds_total << "\n";
  EXPECT_TRUE(st.closed) << st.boundary_edges << " boundary edges at " << st.open_at << ", " << st.nonmanifold_edges << " non-manifold";
  EXPECT_TRUE(st.oriented);
  EXPECT_TRUE(st.self_intersection_free) << st.self_intersecting_pairs;
  const double exact = M_PI * r * r * d.norm() + 4.0 / 3 * M_PI * r * r * r;
  EXPECT_NEAR(st.volume, exact, 1e-2 * exact);
}

TEST(SweptEnvelope, TranslatedBoxIsTheHullOfItsEndPositions) {
  const Eigen::Vector3d size(1.0, 0.6, 0.4), d(0.7, 0.5, -0.3);
  const BSplineHypervolume s = translated_box(size, d);
  SweptEnvelopeOptions options;
  const SweptEnvelope superset = swept_envelope_superset({s}, options);
  EXPECT_EQ(superset.stats.rank_deficient_triangles, 0);
  EXPECT_GT(superset.stats.cap_face_triangles, 0);
  EXPECT_GT(superset.stats.edge_sweep_triangles, 0);
  const TrimmedBoundary trimmed = trim_superset(
      superset.mesh, superset.times,
      [&](std::size_t t, const Eigen::Vector3d& b) {
        const auto& tri = superset.mesh.triangles[t];
        std::array<double, 4> p{};
        for (int j = 0; j < 3; ++j) {
          const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(j)]);
          for (int k = 0; k < 3; ++k) p[static_cast<std::size_t>(k)] += b[j] * superset.mesh.parameters[v][k];
          p[3] += b[j] * superset.times[v];
        }
        const Eigen::VectorXd x = s.evaluate(p);
        return Eigen::Vector3d(x[0], x[1], x[2]);
      },
      [&](const Eigen::Vector3d& x) { return std::optional<bool>(in_translated_box_hull(x, size, d)); });
  const SupersetTrimmingStats& st = trimmed.stats;
  std::cerr << "refine " << st.seconds_refine << " classify " << st.seconds_classify << " checks " << st.seconds_checks << " pieces " << st.pieces << " refined " << st.refined_triangles << " superset " << superset.stats.seconds_total << "\n";
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

}  // namespace
}  // namespace volspline
