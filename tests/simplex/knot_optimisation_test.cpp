#include "volspline/simplex/knot_optimisation.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "support/random_points.h"
#include "support/truth_error.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/dms_spline_evaluator.h"
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
  options.knots.move_primary_knots = false;
  options.knots.held_out = false;  // judged at the data, where the error then never rises
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
  // With move_primary_knots off the primary knots do not move; the domain is the same.
  EXPECT_EQ(optimised.volume.domain().points, fixed.volume.domain().points);
  for (std::size_t v = 0; v < optimised.volume.domain().points.size(); ++v)
    EXPECT_EQ(optimised.volume.knots().cloud(static_cast<int>(v))[0], fixed.volume.knots().cloud(static_cast<int>(v))[0]);
  // The geometry is still the identity after the refit.
  EXPECT_LE(std::sqrt(optimised.statistics.errors.geometric_max), 1e-9);
  if (r.vertices_moved > 0 && r.undone_sweeps == 0) {
    EXPECT_LT(r.after, r.before);
  }
}

TEST(KnotOptimisation, SweepsAreJudgedOnTheHeldOutEighthOfThePoints) {
  const VolumeData data = sampled_volume_data(random_points_in_box(2500, 31), "f", knot_test_front);
  VolumeFitOptions options;
  // Faired: unfaired, these scattered fits ring next to ∂Ω where no sample is, and that, not the
  // knots, decides the error against the front (0.151 in mean square with fixed knots, against
  // 8.4e-3 faired; measured 2026-12-07).
  options.fit.fairing = 0.1;
  options.domain.primary_knots = 40;
  const VolumeFit fixed = fit_volume_data(data, options);
  options.knots.enabled = true;
  options.knots.placement_rounds = 0;
  const VolumeFit held = fit_volume_data(data, options);
  options.knots.held_out = false;
  const VolumeFit at_data = fit_volume_data(data, options);
  const KnotOptimisationReport& r = held.statistics.knot_optimisation;
  ASSERT_TRUE(r.judged_on_held_out);
  EXPECT_FALSE(at_data.statistics.knot_optimisation.judged_on_held_out);
  // The error before is that of the given knots fitted to the other seven eighths, computed here
  // independently.
  const VolumeData training = every_nth_point(data, kKnotHoldOut, kKnotHoldOut / 2, false);
  const VolumeData held_out = every_nth_point(data, kKnotHoldOut, kKnotHoldOut / 2, true);
  EXPECT_EQ(training.size() + held_out.size(), data.size());
  EXPECT_EQ(held_out.size(), (data.size() + kKnotHoldOut - 1 - kKnotHoldOut / 2) / kKnotHoldOut);
  // (fitted with its own prior, then refitted as every sweep is, from that fit).
  DmsSplineVolume given = fixed.volume;
  fit_control_vectors(given, training, options.fit);
  ControlVectorFitOptions refit = options.fit;
  refit.prior_from_volume = true;
  fit_control_vectors(given, training, refit);
  EXPECT_NEAR(r.held_out_before, mean_normalised_field_error(volume_fit_errors(given, held_out)), 1e-12 * r.held_out_before);
  // Sweeps were kept here, each lowering the error at the held-out points.
  EXPECT_GT(r.vertices_moved, 0u);
  ASSERT_GT(r.kept_sweeps, 0);
  EXPECT_LT(r.held_out_after, r.held_out_before);
  EXPECT_NE(held.volume.knots().knots, fixed.volume.knots().knots);
  EXPECT_NEAR(r.before, mean_normalised_field_error(fixed.statistics.errors), 1e-15);
  // What is kept was fitted to all the data at the end, as reported.
  EXPECT_NEAR(r.after, mean_normalised_field_error(held.statistics.errors), 1e-15);
  EXPECT_EQ(held.statistics.errors.fitted_points, fixed.statistics.errors.fitted_points);
  EXPECT_NO_THROW(validate_knot_clouds(held.volume.domain(), held.volume.knots()));
  EXPECT_LE(std::sqrt(held.statistics.errors.geometric_max), 1e-9);
  // Against the front itself the kept sweeps lower the error (measured: 8.37e-3 fixed, 7.14e-3
  // judged on held-out data, 7.07e-3 judged at the data).
  const std::vector<Eigen::Vector3d> probes = random_points_in_box(20000, 77);
  const double fixed_truth = test_support::truth_mean_square(fixed.volume, "f", knot_test_front, probes);
  const double held_truth = test_support::truth_mean_square(held.volume, "f", knot_test_front, probes);
  const double data_truth = test_support::truth_mean_square(at_data.volume, "f", knot_test_front, probes);
  RecordProperty("truth_fixed_held_out_at_data", std::to_string(fixed_truth) + " " + std::to_string(held_truth) + " " + std::to_string(data_truth));
  EXPECT_LT(held_truth, fixed_truth);
  // Deterministic.
  options.knots.held_out = true;
  const VolumeFit again = fit_volume_data(data, options);
  EXPECT_EQ(again.volume.knots().knots, held.volume.knots().knots);
  EXPECT_EQ(again.statistics.knot_optimisation.held_out_after, r.held_out_after);
}

// Grid samples of the cube [0, 1]^3, n per side.
std::vector<Eigen::Vector3d> knot_test_grid(int n) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) out.emplace_back(i / (n - 1.0), j / (n - 1.0), k / (n - 1.0));
  return out;
}

double knot_test_domain_volume(const TetrahedralMesh& domain) {
  double sum = 0;
  for (const auto& t : domain.tetrahedra) {
    const auto& p = domain.points;
    const Eigen::Vector3d a = p[static_cast<std::size_t>(t[0])];
    sum += (p[static_cast<std::size_t>(t[1])] - a).cross(p[static_cast<std::size_t>(t[2])] - a).dot(p[static_cast<std::size_t>(t[3])] - a) / 6;
  }
  return sum;
}

TEST(KnotOptimisation, PrimaryKnotsMoveOnlyWhereTheDomainStaysTheSame) {
  const VolumeData data = sampled_volume_data(knot_test_grid(14), "f", knot_test_front);
  VolumeFitOptions options;
  options.degree = 2;
  options.domain.primary_knots = 60;
  options.knots.enabled = true;
  options.knots.placement_rounds = 0;
  options.knots.held_out = false;  // every sweep that lowers the error at the data is kept
  options.knots.move_primary_knots = false;
  const VolumeFit sub_knots_only = fit_volume_data(data, options);
  options.knots.move_primary_knots = true;
  const VolumeFit optimised = fit_volume_data(data, options);
  const KnotOptimisationReport& r = optimised.statistics.knot_optimisation;
  ASSERT_GT(r.primary_knots_moved, 0u);
  EXPECT_LE(r.after, r.before);
  const TetrahedralMesh& before = sub_knots_only.volume.domain();
  const TetrahedralMesh& after = optimised.volume.domain();
  ASSERT_EQ(before.tetrahedra, after.tetrahedra);
  ASSERT_EQ(before.points.size(), after.points.size());
  // Ω is the cube before and after: the same volume, every vertex on a face of the cube keeps
  // that coordinate exactly (it moved within the face or along the edge), corners stay, and
  // every data point is still fitted.
  EXPECT_NEAR(knot_test_domain_volume(after), 1.0, 1e-12);
  std::size_t moved_inside = 0, moved_on_faces = 0, moved_on_edges = 0;
  for (std::size_t v = 0; v < before.points.size(); ++v) {
    int on_faces = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double c = before.points[v][axis];
      if (c == 0 || c == 1) {
        ++on_faces;
        EXPECT_EQ(after.points[v][axis], c) << "vertex " << v << " axis " << axis;
      }
    }
    if (on_faces == 3) {
      EXPECT_EQ(after.points[v], before.points[v]);
    }
    if (after.points[v] != before.points[v]) (on_faces == 0 ? moved_inside : on_faces == 1 ? moved_on_faces : moved_on_edges)++;
    EXPECT_EQ(optimised.volume.knots().cloud(static_cast<int>(v))[0], after.points[v]);
  }
  EXPECT_LE(moved_inside + moved_on_faces + moved_on_edges, r.primary_knots_moved);  // the report counts each sweep
  EXPECT_GT(moved_inside, 0u);
  EXPECT_GT(moved_on_faces, 0u);
  EXPECT_EQ(optimised.statistics.errors.fitted_points, data.size());
  EXPECT_NO_THROW(validate_knot_clouds(after, optimised.volume.knots()));
  EXPECT_LE(std::sqrt(optimised.statistics.errors.geometric_max), 1e-9);
  // Every collocation row at the grid (faces, edges and corners of Ω included) sums to 1.
  DmsSplineEvaluator evaluator(optimised.volume);
  double worst_sum = 0;
  for (const Eigen::Vector3d& x : data.points) {
    double sum = 0;
    evaluator.for_each_collocation_weight(x, [&](int, double value) { sum += value; });
    worst_sum = std::max(worst_sum, std::abs(sum - 1));
  }
  EXPECT_LE(worst_sum, 1e-12);
  // The moved knots still span every polynomial of degree <= n: a quadratic is reproduced.
  const auto quadratic = [](const Eigen::Vector3d& x) { return 1 + x.x() - 2 * x.y() * x.z() + 0.5 * x.x() * x.x() + x.y() * x.z(); };
  const VolumeData polynomial = sampled_volume_data(knot_test_grid(14), "f", quadratic);
  DmsSplineVolume reproduced(after, optimised.volume.knots(), optimised.volume.sharing(), {"f"});
  const VolumeFitErrors errors = fit_control_vectors(reproduced, polynomial, {});
  EXPECT_LE(errors.attributes[0].max_abs, 1e-10);
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

// The issue asks for a fit that is the same for the same input: placement, the local step and
// refinement, run on one thread and on all, give the same control vectors, knots and domain,
// bit for bit.
TEST(KnotOptimisation, TheWholeFitIsTheSameOnOneThreadAndMany) {
  const VolumeData data = sampled_volume_data(random_points_in_box(1500, 7), "f", knot_test_front);
  VolumeFitOptions options;
  options.degree = 2;
  options.domain.primary_knots = 30;
  options.knots.enabled = true;
  options.knots.placement_rounds = 2;
  options.knots.sweeps = 1;
  options.refinement.error = 1e-3;
  options.refinement.max_rounds = 2;
  const auto run = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    return fit_volume_data(data, options);
  };
  const VolumeFit one = run(1), many = run(8);
  // Each of the three ran: placement rounds, clouds moved by the local step, a refinement round.
  EXPECT_GT(one.statistics.knot_placement.rounds, 0);
  EXPECT_GT(one.statistics.knot_optimisation.vertices_moved, 0u);
  EXPECT_GT(one.statistics.refinement.rounds.size(), 1u);
  EXPECT_EQ(one.volume.domain().points, many.volume.domain().points);
  EXPECT_EQ(one.volume.domain().tetrahedra, many.volume.domain().tetrahedra);
  ASSERT_EQ(one.volume.control_vectors().rows(), many.volume.control_vectors().rows());
  EXPECT_TRUE((one.volume.control_vectors().array() == many.volume.control_vectors().array()).all());
  EXPECT_EQ(one.volume.knots().knots, many.volume.knots().knots);
}

}  // namespace
}  // namespace volspline
