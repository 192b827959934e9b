// The swept envelope against analytic answers: a box translated along a segment sweeps the convex
// hull of its two end positions.
#include "volspline/extract/swept_envelope.h"

#include <gtest/gtest.h>

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
