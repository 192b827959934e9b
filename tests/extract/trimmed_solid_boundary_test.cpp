// The true boundary of a folded trivariate solid: Fig. 6a's cube whose middle control point is
// pulled out through the top face keeps the bulge the fold makes above the face (the superset's
// J = 0 sheet and the folded top face inside the solid go).
#include "volspline/extract/trimmed_solid_boundary.h"

#include <random>

#include <gtest/gtest.h>

#include "volspline/analysis/point_in_image.h"
#include "volspline/construct/swept_examples.h"

namespace volspline {
namespace {

TEST(TrimmedSolidBoundary, FoldedCubeKeepsItsBulge) {
  const BSplineVolume cube = folded_cube();
  const TrimmedSolidBoundary b = trimmed_solid_boundary({cube});
  const SupersetTrimmingStats& st = b.stats;
  EXPECT_TRUE(st.closed) << st.open_at;
  EXPECT_TRUE(st.oriented);
  EXPECT_TRUE(st.self_intersection_free) << st.self_intersecting_pairs;
  EXPECT_EQ(st.components, 1);
  EXPECT_EQ(b.volumes.size(), b.mesh.num_vertices());
  // The highest point of the image, from a dense sampling of V, against the mesh's.
  double top = -1;
  const int n = 40;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) {
        const Eigen::VectorXd x = cube.evaluate({static_cast<double>(i) / n, static_cast<double>(j) / n, static_cast<double>(k) / n});
        top = std::max(top, x[2]);
      }
  ASSERT_GT(top, 0.5 + 0.01) << "the example's bulge";
  // Every vertex but the crease points and the crossings placed by bisection lies on its sheet:
  // V at its (u, v, w) is the vertex, to Newton's tolerance (and the clamping of crossings
  // to 1e-6 of a grid edge from its ends).
  std::int64_t off_sheet = 0;
  for (std::size_t v = 0; v < b.mesh.num_vertices(); ++v) {
    const Eigen::Vector3d& p = b.mesh.parameters[v];
    const Eigen::VectorXd x = cube.evaluate({p.x(), p.y(), p.z()});
    off_sheet += (Eigen::Vector3d(x[0], x[1], x[2]) - b.mesh.positions[v]).norm() > 1e-7;
  }
  EXPECT_GT(st.crossings_on_sheets, 0);
  EXPECT_LE(off_sheet, st.crease_vertices + st.crossings_off_superset);
  double mesh_top = -1;
  for (const auto& x : b.mesh.positions) mesh_top = std::max(mesh_top, x.z());
  EXPECT_NEAR(mesh_top, top, 0.01);
  // The solid is the cube [-1/2, 1/2]^3 (its faces are the cube's, and it has degree 1 there)
  // and the bulge above z = 1/2: its volume by Monte Carlo with the certified membership test.
  const SplineImage<3> image({cube});
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> xy(-0.5, 0.5), z(0.5, top);
  const int samples = 20000;
  int hits = 0;
  for (int s = 0; s < samples; ++s) hits += image.classify({xy(rng), xy(rng), z(rng)}) != ImageMembership::Outside;
  const double box = top - 0.5;
  const double p = static_cast<double>(hits) / samples;
  const double bulge = box * p, sigma = box * std::sqrt(p * (1 - p) / samples);
  ASSERT_GT(bulge, 10 * sigma);
  EXPECT_NEAR(st.volume - 1, bulge, 4 * sigma + 0.1 * bulge) << "bulge " << bulge << " +- " << sigma;
}

}  // namespace
}  // namespace volspline
