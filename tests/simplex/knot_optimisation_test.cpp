#include "volspline/simplex/knot_optimisation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "support/random_points.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {
namespace {

using test_support::random_points_in_box;

// A steep front across the cube: what moving knots can follow.
double knot_test_front(const Eigen::Vector3d& x) { return std::tanh(12 * (x.x() + 0.3 * x.y() - 0.6)); }

TEST(KnotOptimisation, KeepsTheCloudsValidAndNeverRaisesTheError) {
  const VolumeData data = sampled_volume_data(random_points_in_box(2500, 31), "f", knot_test_front);
  VolumeFitOptions options;
  options.degree = 2;
  options.domain.primary_knots = 40;
  const VolumeFit fixed = fit_volume_data(data, options);
  options.knots.enabled = true;
  options.knots.placement_rounds = 0;  // the local step alone (the placement moves primary knots)
  const VolumeFit optimised = fit_volume_data(data, options);
  const KnotOptimisationReport& r = optimised.statistics.knot_optimisation;
  EXPECT_GT(r.vertices_tried, 0u);
  EXPECT_LE(r.after, r.before);
  EXPECT_NEAR(r.before, mean_normalised_field_error(fixed.statistics.errors), 1e-12);
  EXPECT_NEAR(r.after, mean_normalised_field_error(optimised.statistics.errors), 1e-15);
  // The clouds satisfy every condition of §3.2 (eq. 3 among them), checked in full.
  EXPECT_NO_THROW(validate_knot_clouds(optimised.volume.domain(), optimised.volume.knots()));
  std::vector<std::vector<int>> rings(optimised.volume.domain().points.size());
  for (std::size_t t = 0; t < optimised.volume.domain().tetrahedra.size(); ++t)
    for (int v : optimised.volume.domain().tetrahedra[t]) rings[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));
  for (const auto& ring : rings) EXPECT_TRUE(knot_ring_is_valid(optimised.volume.domain(), optimised.volume.knots(), ring));
  // Primary knots do not move; the domain is the same.
  EXPECT_EQ(optimised.volume.domain().points, fixed.volume.domain().points);
  for (std::size_t v = 0; v < optimised.volume.domain().points.size(); ++v)
    EXPECT_EQ(optimised.volume.knots().cloud(static_cast<int>(v))[0], fixed.volume.knots().cloud(static_cast<int>(v))[0]);
  // The geometry is still the identity after the refit.
  EXPECT_LE(std::sqrt(optimised.statistics.errors.geometric_max), 1e-9);
  if (r.vertices_moved > 0 && r.undone_sweeps == 0) {
    EXPECT_LT(r.after, r.before);
  }
}

TEST(KnotOptimisation, TheRingCheckRefusesAnInvertedKnotTetrahedron) {
  TetrahedralMesh domain;
  domain.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  domain.tetrahedra = {{0, 1, 2, 3}};
  KnotClouds clouds = generate_knot_clouds(domain, 1);
  EXPECT_TRUE(knot_ring_is_valid(domain, clouds, {0}));
  // Vertex 0's sub-knot beyond the opposite face: [p_1, q_0, r_0, s_0] turns over.
  clouds.knots[1] = Eigen::Vector3d(0.6, 0.6, 0.6);
  EXPECT_FALSE(knot_ring_is_valid(domain, clouds, {0}));
  EXPECT_THROW(validate_knot_clouds(domain, clouds), InvalidInput);
}

}  // namespace
}  // namespace volspline
