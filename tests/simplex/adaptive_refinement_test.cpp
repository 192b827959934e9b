#include "volspline/simplex/adaptive_refinement.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "volspline/construct/volume_data_examples.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

std::vector<Eigen::Vector3d> refinement_test_points(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Vector3d> points(n);
  for (auto& p : points) p = Eigen::Vector3d(u(random), u(random), u(random));
  return points;
}

// A bump: detail in one corner, smooth elsewhere.
double refinement_test_bump(const Eigen::Vector3d& x) { return std::exp(-12 * (x - Eigen::Vector3d(0.4, 0.3, -0.2)).squaredNorm()); }

TEST(AdaptiveRefinement, TheErrorNeverIncreasesAndTheStopIsReported) {
  const VolumeData data = sampled_volume_data(refinement_test_points(2500, 21), "f", refinement_test_bump);
  VolumeFitOptions options;
  options.degree = 2;
  options.domain.primary_knots = 30;
  options.refinement.error = 1e-3;
  options.refinement.max_tetrahedra = 400;
  const VolumeFit fit = fit_volume_data(data, options);
  const AdaptiveRefinementReport& r = fit.statistics.refinement;
  ASSERT_GE(r.rounds.size(), 2u);
  for (std::size_t i = 1; i < r.rounds.size(); ++i) {
    if (r.rounds[i].undone) continue;
    EXPECT_LE(r.rounds[i].field_mean_square, r.rounds[i - 1].field_mean_square) << "round " << i;
    EXPECT_EQ(r.rounds[i].tetrahedra, r.rounds[i - 1].tetrahedra + 3 * r.rounds[i].split);
  }
  // Refinement helped, and the result's errors are those of the last kept round.
  EXPECT_LT(mean_normalised_field_error(fit.statistics.errors), 0.5 * r.rounds.front().field_mean_square);
  EXPECT_LE(fit.volume.domain().tetrahedra.size(), 400u);
  EXPECT_EQ(fit.statistics.domain_tetrahedra, fit.volume.domain().tetrahedra.size());
  EXPECT_NE(r.stop, RefinementStop::NotRequested);
  // What the report says of the tetrahedra above ε, recomputed from the result.
  const TetrahedronFitErrors local = tetrahedron_fit_errors(fit.volume, data);
  std::size_t above = 0;
  for (double e : local.rms) above += e > 1e-3;
  EXPECT_EQ(above, r.above);
  if (r.stop == RefinementStop::Converged) {
    EXPECT_EQ(above, 0u);
  }
  // The geometry is still the identity: refinement keeps eq. 10's geometric part exact.
  EXPECT_LE(std::sqrt(fit.statistics.errors.geometric_max), 1e-9);
}

TEST(AdaptiveRefinement, PerTetrahedronErrorsAreThoseOfTheirPoints) {
  const VolumeData data = sampled_volume_data(refinement_test_points(1200, 22), "f", refinement_test_bump);
  VolumeFitOptions options;
  options.domain.primary_knots = 25;
  const VolumeFit fit = fit_volume_data(data, options);
  const TetrahedronFitErrors local = tetrahedron_fit_errors(fit.volume, data);
  DmsSplineEvaluator evaluator(fit.volume);
  const double range = data.attributes.maxCoeff() - data.attributes.minCoeff();
  std::vector<double> squares(local.rms.size(), 0);
  std::vector<std::size_t> counts(local.rms.size(), 0);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const DmsSplinePoint p = evaluator.evaluate(data.points[i]);
    if (!p.inside) continue;
    const double e = (p.value[3] - data.attributes(static_cast<Eigen::Index>(i), 0)) / range;
    squares[static_cast<std::size_t>(p.tetrahedron)] += e * e;
    ++counts[static_cast<std::size_t>(p.tetrahedron)];
  }
  for (std::size_t t = 0; t < local.rms.size(); ++t) {
    EXPECT_EQ(local.points[t], counts[t]);
    if (counts[t] > 0) {
      EXPECT_NEAR(local.rms[t], std::sqrt(squares[t] / static_cast<double>(counts[t])), 1e-12);
    }
  }
}

TEST(AdaptiveRefinement, TheTetrahedronBudgetStopsIt) {
  const VolumeData data = sampled_volume_data(refinement_test_points(2000, 23), "f", refinement_test_bump);
  VolumeFitOptions options;
  options.domain.primary_knots = 30;
  options.refinement.error = 1e-9;  // unreachable
  options.refinement.max_tetrahedra = 0;
  VolumeFitOptions unrefined = options;
  unrefined.refinement.error = 0;
  const VolumeFit unbounded_start = fit_volume_data(data, unrefined);
  options.refinement.max_tetrahedra = unbounded_start.statistics.domain_tetrahedra + 30;
  const VolumeFit fit = fit_volume_data(data, options);
  EXPECT_LE(fit.volume.domain().tetrahedra.size(), options.refinement.max_tetrahedra);
  EXPECT_GT(fit.volume.domain().tetrahedra.size(), unbounded_start.statistics.domain_tetrahedra);
  EXPECT_TRUE(fit.statistics.refinement.stop == RefinementStop::TetrahedronBudget ||
              fit.statistics.refinement.stop == RefinementStop::ErrorIncreased)
      << refinement_stop_text(fit.statistics.refinement.stop);
  EXPECT_GT(fit.statistics.refinement.above, 0u);
}

}  // namespace
}  // namespace volspline
