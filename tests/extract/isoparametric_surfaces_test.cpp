#include "volspline/extract/isoparametric_surfaces.h"

#include <random>

#include <gtest/gtest.h>

#include "support/test_splines.h"
#include "volspline/mesh/parts.h"
#include "volspline/core/error.h"
#include "volspline/extract/face_tessellation.h"

namespace volspline {
namespace {

TEST(IsoparametricValues, SpanTheDomainWithBothEndsOrTakeTheMiddle) {
  const KnotVector k(2, {-1, -1, -1, 0, 3, 3, 3});
  EXPECT_EQ(isoparametric_values(k, 1), std::vector<double>{1.0});
  EXPECT_EQ(isoparametric_values(k, 3), (std::vector<double>{-1.0, 1.0, 3.0}));
  EXPECT_THROW(isoparametric_values(k, 0), InvalidInput);
}

TEST(IsoparametricSurface, VerticesAreTheVolumeAtTheirParametersWithTheFixedValue) {
  std::mt19937 rng(11);
  for (const bool rational : {false, true}) {
    const BSplineVolume v = test_support::random_spline<3>(rng, {2, 3, 1}, 3, 3, rational);
    for (int d = 0; d < 3; ++d) {
      const double value = 0.3 * v.domain_min(d) + 0.7 * v.domain_max(d);
      const TriangleMesh s = isoparametric_surface(v, d, value, {.resolution = 6});
      const int a = (d + 1) % 3, b = (d + 2) % 3;
      const std::size_t na = face_samples(v.knot_vector(a), 6).size(), nb = face_samples(v.knot_vector(b), 6).size();
      EXPECT_EQ(s.num_vertices(), na * nb);
      EXPECT_EQ(s.num_triangles(), 2 * (na - 1) * (nb - 1));
      for (std::size_t i = 0; i < s.num_vertices(); ++i) {
        const Eigen::Vector3d& t = s.parameters[i];
        EXPECT_EQ(t[d], value);
        EXPECT_LE((v.evaluate({t[0], t[1], t[2]}) - s.positions[i]).norm(), 1e-12);
      }
      for (const int part : s.parts) EXPECT_EQ(part, static_cast<int>(Part::IsoU) + d);
    }
  }
}

TEST(IsoparametricSurface, EndSurfacesOfAFamilyAreTheBoundaryFaces) {
  std::mt19937 rng(3);
  const BSplineVolume v = test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, false);
  const TriangleMesh family = isoparametric_family(v, 2, 4, {.resolution = 5});
  const TriangleMesh faces = tessellate_faces(v, {.resolution = 5, .weld_coincident = false});
  // Every vertex of the family with w at an end is a vertex of the w = min or w = max face.
  std::size_t matched = 0;
  for (std::size_t i = 0; i < family.num_vertices(); ++i) {
    const double w = family.parameters[i][2];
    if (w != v.domain_min(2) && w != v.domain_max(2)) continue;
    for (std::size_t j = 0; j < faces.num_vertices(); ++j)
      if (faces.parameters[j] == family.parameters[i]) {
        EXPECT_LE((faces.positions[j] - family.positions[i]).norm(), 1e-12);
        ++matched;
        break;
      }
  }
  EXPECT_EQ(matched, 2 * family.num_vertices() / 4);
}

TEST(IsoparametricSurfacesThrough, ThreeSurfacesEachHoldingOneParameter) {
  std::mt19937 rng(8);
  const BSplineVolume v = test_support::random_spline<3>(rng, {3, 2, 2}, 2, 3, true);
  const std::array<double, 3> t{0.25 * v.domain_min(0) + 0.75 * v.domain_max(0), 0.5 * (v.domain_min(1) + v.domain_max(1)),
                                v.domain_min(2)};
  const TriangleMesh m = isoparametric_surfaces_through(v, t, {.resolution = 4});
  std::array<int, 3> counts{};
  for (std::size_t f = 0; f < m.num_triangles(); ++f) {
    const int d = m.parts[f] - static_cast<int>(Part::IsoU);
    ASSERT_GE(d, 0);
    ASSERT_LE(d, 2);
    ++counts[static_cast<std::size_t>(d)];
    for (const int i : m.triangles[f]) EXPECT_EQ(m.parameters[static_cast<std::size_t>(i)][d], t[static_cast<std::size_t>(d)]);
  }
  for (const int c : counts) EXPECT_GT(c, 0);
}

TEST(IsoparametricSurface, RejectsValuesOutsideTheDomainAndBadDirections) {
  std::mt19937 rng(1);
  const BSplineVolume v = test_support::random_spline<3>(rng, {1, 1, 1}, 1, 3, false);
  EXPECT_THROW(isoparametric_surface(v, 0, v.domain_max(0) + 1e-9), InvalidInput);
  EXPECT_THROW(isoparametric_surface(v, 3, v.domain_min(0)), InvalidInput);
  EXPECT_THROW(isoparametric_surface(v, 1, v.domain_min(1), {.resolution = 0}), InvalidInput);
  EXPECT_THROW(isoparametric_family(v, 0, 0), InvalidInput);
}

}  // namespace
}  // namespace volspline
