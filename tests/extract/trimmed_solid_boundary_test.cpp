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
