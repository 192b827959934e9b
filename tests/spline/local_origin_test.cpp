// Far from the origin (issue 16): a solid whose control points sit at 1e6, 1e12 or 1e15 (either
// sign, on one axis or all) has the same derivatives, Jacobian, mass properties and meshes as the
// same solid at 0, because every computation works relative to the spline's local origin
// (TensorSpline::local_origin). The reference is the solid at 0 made from the placed one by an
// exact subtraction (fl(x + O) − O is exact: Sterbenz), so both describe the same solid and any
// difference is the computation's; positions may differ by a few ulp(|O|).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/test_splines.h"
#include "volspline/analysis/jacobian_validity.h"
#include "volspline/analysis/mass_properties.h"
#include "volspline/analysis/scalar_fields.h"
#include "volspline/construct/primitives.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/extract/planar_slices.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {
namespace {

// `solid` moved by `offset` (rounded as a file would hold it), and the reference: the moved
// control points minus the offset, exactly.
std::pair<BSplineVolume, BSplineVolume> placed_and_reference(const BSplineVolume& solid, const Eigen::Vector3d& offset) {
  std::vector<double> placed = solid.points(), reference = solid.points();
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const bool direction = solid.is_rational() && solid.weights()[i / 3] == 0.0;
    if (direction) continue;
    placed[i] = solid.points()[i] + offset[static_cast<long>(i % 3)];
    reference[i] = placed[i] - offset[static_cast<long>(i % 3)];
  }
  return {BSplineVolume(solid.knot_vectors(), 3, placed, solid.weights()), BSplineVolume(solid.knot_vectors(), 3, reference, solid.weights())};
}

struct NamedSolid {
  std::string name;
  BSplineVolume volume;
};

std::vector<NamedSolid> solids() {
  // A cube refined into a cubic B-spline with interior knots (its control points are not all
  // dyadic), a random polynomial B-spline volume, the rational ball and cylinder of `make`.
  BSplineVolume cube = box(Eigen::Vector3d(1, 1, 1));
  for (int d = 0; d < 3; ++d) cube = elevate_degree(cube, d, 2);
  cube = insert_knot(cube, 0, 0.3);
  cube = insert_knot(cube, 1, 0.55);
  std::mt19937 rng(16);
  return {{"cube", cube},
          {"random", test_support::random_spline<3>(rng, {2, 3, 2}, 2, 3, false)},
          {"ball", ball(1.0)},
          {"cylinder", cylinder(0.5, 2.0, 0.2)}};
}

std::vector<Eigen::Vector3d> offsets() {
  return {{1e6, 1e6, 1e6}, {1e12, -1e12, 1e12}, {1e15, 1e15, 1e15}, {-1e15, -1e15, -1e15}, {1e15, 0, 0}, {0, -1e12, 1e15}};
}

// The size of the solid: its largest control point coordinate at 0.
double size_of(const BSplineVolume& v) {
  double s = 0;
  for (double x : v.points()) s = std::max(s, std::abs(x));
  return s;
}

TEST(LocalOrigin, IsZeroNearTheOriginAndTheBoxCentreFarFromIt) {
  const BSplineVolume unit = box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.5, 0.5));
  EXPECT_EQ(unit.local_origin(), std::vector<double>({0, 0, 0}));
  const BSplineVolume far = box(Eigen::Vector3d(1, 2, 4), Eigen::Vector3d(1e15, 0.5, -1e12));
  EXPECT_EQ(far.local_origin(), std::vector<double>({1e15, 0, -1e12}));
  const BSplineVolume moved = far.translated_to_local_origin();
  EXPECT_EQ(moved.local_origin(), std::vector<double>({0, 0, 0}));
  for (std::size_t i = 0; i < far.points().size(); ++i)
    EXPECT_EQ(moved.points()[i] + far.local_origin()[i % 3], far.points()[i]);
}

TEST(LocalOrigin, DerivativesAndPositionsDoNotDependOnThePlacement) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const NamedSolid& s : solids()) {
    for (const Eigen::Vector3d& offset : offsets()) {
      const auto [placed, reference] = placed_and_reference(s.volume, offset);
      const double size = size_of(reference);
      const double ulp = std::nextafter(offset.cwiseAbs().maxCoeff(), HUGE_VAL) - offset.cwiseAbs().maxCoeff();
      std::array<std::vector<double>, 3> samples;
      for (int d = 0; d < 3; ++d)
        for (int i = 0; i < 4; ++i)
          samples[static_cast<std::size_t>(d)].push_back(placed.domain_min(d) + (placed.domain_max(d) - placed.domain_min(d)) * u(rng));
      // Scattered points with derivatives up to order 2, and the grid evaluation of order 1.
      for (int i = 0; i < 4; ++i) {
        const std::array<double, 3> t{samples[0][static_cast<std::size_t>(i)], samples[1][static_cast<std::size_t>(i)],
                                      samples[2][static_cast<std::size_t>(i)]};
        const std::vector<double> a = placed.evaluate_derivatives(t, 2), b = reference.evaluate_derivatives(t, 2);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(a[static_cast<std::size_t>(c)] - offset[c], b[static_cast<std::size_t>(c)], 4 * ulp + 1e-12 * size)
              << s.name << " at offset " << offset.transpose();
        for (std::size_t j = 3; j < a.size(); ++j)
          EXPECT_NEAR(a[j], b[j], 1e-12 * std::max(1.0, std::abs(b[j])) * size) << s.name << " at offset " << offset.transpose();
      }
      const std::vector<double> ga = placed.evaluate_grid(samples, 1), gb = reference.evaluate_grid(samples, 1);
      const std::size_t positions = 3 * 64;
      for (std::size_t j = 0; j < ga.size(); ++j) {
        if (j < positions) EXPECT_NEAR(ga[j] - offset[static_cast<long>(j % 3)], gb[j], 4 * ulp + 1e-12 * size);
        else EXPECT_NEAR(ga[j], gb[j], 1e-12 * size) << s.name << " at offset " << offset.transpose();
      }
      // The Jacobian as `view --color jacobian` samples it.
      std::vector<Eigen::Vector3d> parameters;
      for (int i = 0; i < 4; ++i) parameters.emplace_back(samples[0][static_cast<std::size_t>(i)], samples[1][static_cast<std::size_t>(3 - i)], samples[2][static_cast<std::size_t>(i)]);
      const auto ja = evaluate_scalar_field(placed, scalar_field_named("jacobian"), parameters);
      const auto jb = evaluate_scalar_field(reference, scalar_field_named("jacobian"), parameters);
      for (std::size_t i = 0; i < ja.size(); ++i) EXPECT_NEAR(ja[i], jb[i], 1e-12 * size * size * size) << s.name;
    }
  }
}

TEST(LocalOrigin, MassPropertiesDoNotDependOnThePlacement) {
  // (Three of the offsets: adaptive integration of the rational solids is the slowest part.)
  const std::vector<Eigen::Vector3d> some{{1e12, -1e12, 1e12}, {-1e15, -1e15, -1e15}, {0, -1e12, 1e15}};
  for (const NamedSolid& s : solids()) {
    for (const Eigen::Vector3d& offset : some) {
      const auto [placed, at_zero] = placed_and_reference(s.volume, offset);
      // A rational solid is integrated adaptively: a looser target keeps the test short; both
      // runs make the same refinement decisions on the same (shifted) solid.
      MassPropertiesOptions options;
      options.relative_tolerance = 1e-9;
      options.max_quadrature_points = 400'000;
      const MassProperties a = mass_properties(placed, options), b = mass_properties(at_zero, options);
      const double size = size_of(at_zero);
      EXPECT_NEAR(a.volume, b.volume, 1e-12 * b.volume) << s.name << " at offset " << offset.transpose();
      EXPECT_NEAR(a.signed_volume, b.signed_volume, 1e-12 * b.volume) << s.name;
      EXPECT_LT((a.inertia - b.inertia).norm(), 1e-12 * b.inertia.norm()) << s.name << " at offset " << offset.transpose();
      const double ulp = std::nextafter(offset.cwiseAbs().maxCoeff(), HUGE_VAL) - offset.cwiseAbs().maxCoeff();
      EXPECT_LT((a.centroid - offset - b.centroid).cwiseAbs().maxCoeff(), 2 * ulp + 1e-12 * size) << s.name;
    }
  }
}

TEST(LocalOrigin, JacobianCertificatesDoNotDependOnThePlacement) {
  for (const NamedSolid& s : solids()) {
    for (const Eigen::Vector3d& offset : offsets()) {
      const auto [placed, reference] = placed_and_reference(s.volume, offset);
      const JacobianValidity a = check_jacobian(placed), b = check_jacobian(reference);
      EXPECT_EQ(a.verdict, b.verdict) << s.name << " at offset " << offset.transpose();
      const double size = size_of(reference), scale = size * size * size;
      EXPECT_NEAR(a.lower, b.lower, 1e-10 * scale) << s.name << " at offset " << offset.transpose();
      EXPECT_NEAR(a.upper, b.upper, 1e-10 * scale) << s.name << " at offset " << offset.transpose();
    }
  }
}

TEST(LocalOrigin, MeshesAreTheSolidAtZeroMovedWithinRounding) {
  for (const NamedSolid& s : solids()) {
    for (const Eigen::Vector3d& offset : offsets()) {
      const auto [placed, reference] = placed_and_reference(s.volume, offset);
      const double ulp = std::nextafter(offset.cwiseAbs().maxCoeff(), HUGE_VAL) - offset.cwiseAbs().maxCoeff();
      const double size = size_of(reference);
      FaceTessellationOptions options;
      options.resolution = 6;
      const TriangleMesh a = tessellate_faces(placed, options), b = tessellate_faces(reference, options);
      ASSERT_EQ(a.num_vertices(), b.num_vertices()) << s.name << " at offset " << offset.transpose();
      ASSERT_EQ(a.triangles, b.triangles) << s.name;
      for (std::size_t v = 0; v < a.num_vertices(); ++v)
        EXPECT_LT((a.positions[v] - offset - b.positions[v]).cwiseAbs().maxCoeff(), 4 * ulp + 1e-12 * size) << s.name;
      // A slice x = c through the middle, c a multiple of 1/8 (so c + offset is exact at every
      // offset): the same polygon, moved.
      const auto [lo, hi] = sampled_bounding_box(reference);
      const double c = std::round(4 * (lo.x() + hi.x())) / 8;
      const Plane plane{Eigen::Vector3d(1, 0, 0), c}, moved{Eigen::Vector3d(1, 0, 0), c + offset.x()};
      const SliceOptions coarse{.resolution = 10};
      const TriangleMesh sa = planar_slice(placed, moved, coarse), sb = planar_slice(reference, plane, coarse);
      EXPECT_GT(sb.num_triangles(), 0u) << s.name;
      // Samples lying exactly on the plane may be classified on either side (the arithmetic is
      // the same solid's, shifted), so compare what is sliced: the area and the extent.
      const auto area = [](const TriangleMesh& m) {
        double total = 0;
        for (const auto& t : m.triangles)
          total += 0.5 * (m.positions[static_cast<std::size_t>(t[1])] - m.positions[static_cast<std::size_t>(t[0])])
                             .cross(m.positions[static_cast<std::size_t>(t[2])] - m.positions[static_cast<std::size_t>(t[0])])
                             .norm();
        return total;
      };
      TriangleMesh local = sa;
      for (Eigen::Vector3d& p : local.positions) p -= offset;
      // (Far out the vertices are rounded to ulp(|offset|), which changes the area of small
      // triangles; compare areas where that rounding is below 1e-9 of the size.)
      if (ulp <= 1e-9 * size) {
        EXPECT_NEAR(area(local), area(sb), 1e-9 * area(sb)) << s.name << " at offset " << offset.transpose();
      }
      const auto [la, ha] = local.bounding_box();
      const auto [lb, hb] = sb.bounding_box();
      EXPECT_LT((la - lb).cwiseAbs().maxCoeff(), 4 * ulp + 1e-9 * size) << s.name;
      EXPECT_LT((ha - hb).cwiseAbs().maxCoeff(), 4 * ulp + 1e-9 * size) << s.name;
    }
  }
}

}  // namespace
}  // namespace volspline
