#include "volspline/extract/face_tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/test_splines.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

BSplineVolume bent_box(bool left_handed) {
  const KnotVector ku = KnotVector::uniform_clamped(3, 3), kv = KnotVector::uniform_clamped(2, 2), kw = KnotVector::bezier(1);
  std::vector<double> pts;
  for (int k = 0; k < kw.num_basis(); ++k)
    for (int j = 0; j < kv.num_basis(); ++j)
      for (int i = 0; i < ku.num_basis(); ++i) {
        const double x = i / (ku.num_basis() - 1.0) * 4.0;
        pts.push_back(x);
        pts.push_back((left_handed ? -1.0 : 1.0) * j / (kv.num_basis() - 1.0));
        pts.push_back(k + 0.15 * x * x);
      }
  return BSplineVolume({ku, kv, kw}, 3, pts);
}

TEST(FaceTessellation, ValidVolumeGivesAClosedConsistentlyOrientedSurface) {
  for (bool left : {false, true}) {
    const auto mesh = tessellate_faces(bent_box(left), {.resolution = 8});
    const auto stats = edge_statistics(mesh);
    EXPECT_TRUE(stats.closed());
    EXPECT_EQ(stats.boundary_edges, 0u);
    EXPECT_EQ(stats.nonmanifold_edges, 0u);
    EXPECT_EQ(stats.inconsistently_oriented_edges, 0u);
    EXPECT_GT(enclosed_volume(mesh), 0.0);
    // Euler characteristic of a sphere
    EXPECT_EQ(static_cast<long>(mesh.num_vertices()) - static_cast<long>(stats.edges) + static_cast<long>(mesh.num_triangles()), 2);
    for (int p : mesh.parts) {
      EXPECT_GE(p, 0);
      EXPECT_LE(p, 5);
    }
  }
}

TEST(FaceTessellation, EnclosedVolumeConvergesToTheSolidsVolume) {
  // The bent box is x in [0,4], y in [0,1], z in [0.15 x^2, 0.15 x^2 + 1]: volume 4.
  const auto coarse = tessellate_faces(bent_box(false), {.resolution = 4});
  const auto fine = tessellate_faces(bent_box(false), {.resolution = 32});
  EXPECT_NEAR(enclosed_volume(fine), 4.0, 1e-3);
  EXPECT_LT(std::abs(enclosed_volume(fine) - 4.0), std::abs(enclosed_volume(coarse) - 4.0) + 1e-12);
}

TEST(FaceTessellation, VerticesLieOnTheirFaces) {
  const auto v = bent_box(false);
  const auto mesh = tessellate_faces(v, {.resolution = 5, .weld_coincident = false});
  for (std::size_t i = 0; i < mesh.num_vertices(); ++i) {
    const auto& t = mesh.parameters[i];
    const auto x = v.evaluate({t[0], t[1], t[2]});
    EXPECT_LT((x - mesh.positions[i]).norm(), 1e-14);
    const bool on_boundary = t[0] == 0 || t[0] == 1 || t[1] == 0 || t[1] == 1 || t[2] == 0 || t[2] == 1;
    EXPECT_TRUE(on_boundary);
  }
}

TEST(FaceTessellation, SamplesIncludeBreakpoints) {
  const KnotVector kv(2, {0, 0, 0, 0.3, 0.3, 0.71, 1, 1, 1});
  const auto s = face_samples(kv, 4);
  for (double b : kv.breakpoints()) EXPECT_TRUE(std::find(s.begin(), s.end(), b) != s.end());
  EXPECT_TRUE(std::is_sorted(s.begin(), s.end()));
}

}  // namespace
}  // namespace volspline
