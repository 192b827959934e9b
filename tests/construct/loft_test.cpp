// Ruled volumes and lofts (Lasser 1994, eq. 7) and the compatibility step they rely on.
#include "volspline/construct/loft.h"

#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "support/geometry_checks.h"
#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/iso_restriction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

// The parameter of `s` mapped onto [0, 1]^2, as make_compatible maps the domain.
std::array<double, 3> unit(const BSplineSurface& s, const std::array<double, 2>& uv, double w) {
  return {(uv[0] - s.domain_min(0)) / (s.domain_max(0) - s.domain_min(0)), (uv[1] - s.domain_min(1)) / (s.domain_max(1) - s.domain_min(1)), w};
}

// Sections with different degrees and knots, each shifted along z so that they are apart.
std::vector<BSplineSurface> random_sections(std::mt19937& rng, int n, bool rational) {
  std::vector<BSplineSurface> s;
  for (int k = 0; k < n; ++k) {
    const auto f = random_spline<2>(rng, {1 + k % 3, 3 - k % 2}, 1 + k % 3, 3, rational && k % 2 == 0, k % 2 == 1);
    s.push_back(transform_affine(f, Eigen::Matrix3d::Identity() * 0.3, Eigen::Vector3d(0, 0, 2.0 * k)));
  }
  return s;
}

TEST(Loft, MakeCompatibleKeepsGeometry) {
  std::mt19937 rng(31);
  for (bool rational : {false, true}) {
    auto sections = random_sections(rng, 4, rational);
    const auto original = sections;
    make_compatible(sections);
    for (std::size_t k = 0; k < sections.size(); ++k) {
      EXPECT_EQ(sections[k].knot_vectors(), sections[0].knot_vectors());
      EXPECT_EQ(sections[k].is_rational(), rational);
      EXPECT_EQ(sections[k].domain_min(0), 0.0);
      EXPECT_EQ(sections[k].domain_max(1), 1.0);
      for (int i = 0; i < 40; ++i) {
        const auto uv = random_parameter(rng, original[k]);
        const auto t = unit(original[k], uv, 0);
        EXPECT_LT((sections[k].evaluate({t[0], t[1]}) - original[k].evaluate(uv)).norm(), 1e-12 * 8);
      }
    }
  }
}

// Rational sections whose weight functions agree (affine images of one surface, some with a knot
// inserted): lofting in homogeneous space then interpolates equal weights, which stay positive.
std::vector<BSplineSurface> sections_with_common_weights(std::mt19937& rng, int n) {
  const auto base = random_spline<2>(rng, {2, 3}, 2, 3, true, true, 2, true);
  std::vector<BSplineSurface> s;
  std::uniform_real_distribution<double> entry(-0.3, 0.3);
  for (int k = 0; k < n; ++k) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) += entry(rng);
    auto f = transform_affine(base, A, Eigen::Vector3d(0, 0, 3.0 * k));
    if (k % 2 == 1) f = insert_knot(f, 0, 0.5 * (f.domain_min(0) + f.domain_max(0)));
    s.push_back(f);
  }
  return s;
}

TEST(Loft, InterpolatesEverySection) {
  std::mt19937 rng(32);
  for (int kind : {0, 1, 2})
    for (int degree : {1, 2, 3, 7})
      for (auto param : {LoftParameterization::ChordLength, LoftParameterization::Centripetal}) {
        // 0: polynomial; 1: rational and polynomial mixed (degree 1 only: its control weights
        // are the sections' own, so they stay positive); 2: rational with common weights
        if (kind == 1 && degree > 1) continue;
        const auto sections = kind == 2 ? sections_with_common_weights(rng, 5) : random_sections(rng, 5, kind == 1);
        const auto V = loft(sections, degree, param);
        EXPECT_EQ(V.degrees()[2], std::min(degree, 4));
        auto compatible = sections;
        make_compatible(compatible);
        const auto t = loft_parameters(compatible, param);
        ASSERT_EQ(t.size(), 5u);
        EXPECT_EQ(t.front(), 0.0);
        EXPECT_EQ(t.back(), 1.0);
        for (std::size_t k = 0; k < sections.size(); ++k)
          for (int i = 0; i < 30; ++i) {
            const auto uv = random_parameter(rng, sections[k]);
            EXPECT_LT((V.evaluate(unit(sections[k], uv, t[k])) - sections[k].evaluate(uv)).norm(), 1e-12 * 10)
                << "section " << k << " degree " << degree;
          }
      }
}

TEST(Loft, RuledVolumeIsLinearInW) {
  std::mt19937 rng(33);
  const auto sections = random_sections(rng, 2, false);
  const auto V = ruled_volume(sections[0], sections[1]);
  EXPECT_EQ(V.degrees()[2], 1);
  for (int i = 0; i < 50; ++i) {
    const auto uv = random_parameter(rng, sections[0]);
    const auto t0 = unit(sections[0], uv, 0.0);
    const double w = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const auto d = V.evaluate_derivatives({t0[0], t0[1], w}, 2);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(d[9 * 3 + static_cast<std::size_t>(c)], 0.0);  // (0,0,2): last of order 2
    EXPECT_LT((V.evaluate(t0) - sections[0].evaluate(uv)).norm(), 1e-12 * 10);
    const auto uv1 = random_parameter(rng, sections[1]);
    EXPECT_LT((V.evaluate(unit(sections[1], uv1, 1.0)) - sections[1].evaluate(uv1)).norm(), 1e-12 * 10);
  }
}

TEST(Loft, RationalRuledVolumeHasStraightWLines) {
  std::mt19937 rng(34);
  const auto a = random_spline<2>(rng, {2, 2}, 2, 3, true), b = transform_affine(random_spline<2>(rng, {1, 3}, 2, 3, true), Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 5));
  const auto V = ruled_volume(a, b);
  for (int i = 0; i < 40; ++i) {
    const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng), v = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const Eigen::Vector3d p0 = V.evaluate({u, v, 0.0}), p1 = V.evaluate({u, v, 1.0}), p = V.evaluate({u, v, 0.37});
    EXPECT_LT((p - p0).cross(p1 - p0).norm(), 1e-12 * 100);  // on the segment's line
    EXPECT_GT((p - p0).dot(p1 - p0), 0.0);
    EXPECT_GT((p1 - p).dot(p1 - p0), 0.0);
  }
}

TEST(Loft, ReproducesARuledVolumeFromItsSections) {
  std::mt19937 rng(35);
  const auto sections = random_sections(rng, 2, false);
  const auto ruled = ruled_volume(sections[0], sections[1]);
  std::vector<BSplineSurface> samples;
  for (double w : {0.0, 0.2, 0.45, 0.7, 1.0}) samples.push_back(restrict_to_iso(ruled, 2, w));
  for (auto param : {LoftParameterization::ChordLength, LoftParameterization::Centripetal}) {
    const auto lofted = loft(samples, 3, param);
    if (param == LoftParameterization::ChordLength) {
      test_support::expect_same_geometry(ruled, lofted, rng);  // chord lengths recover w exactly
    } else {
      // centripetal parameters differ from w, but the loft is still the same solid: every
      // section lies in it, and the w-lines are the same straight segments
      for (int i = 0; i < 20; ++i) {
        const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng), v = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const Eigen::Vector3d p0 = ruled.evaluate({u, v, 0.0}), p1 = ruled.evaluate({u, v, 1.0}), p = lofted.evaluate({u, v, 0.6});
        EXPECT_LT((p - p0).cross(p1 - p0).norm(), 1e-11);
      }
    }
  }
}

TEST(Loft, BadInput) {
  std::mt19937 rng(36);
  const auto sections = random_sections(rng, 3, false);
  auto where = [](auto f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return e.where();
    }
    return std::string("no error");
  };
  EXPECT_EQ(where([&] { loft({sections[0]}, 3); }), "sections");
  EXPECT_EQ(where([&] { loft({}, 3); }), "sections");
  EXPECT_EQ(where([&] { loft(sections, 0); }), "degree");
  EXPECT_EQ(where([&] { loft({sections[0], sections[1], sections[1]}, 2); }), "sections[2]");
  const auto flat = random_spline<2>(rng, {1, 1}, 1, 2, false);
  EXPECT_EQ(where([&] { loft({sections[0], flat}, 1); }), "sections[1]");
  EXPECT_EQ(where([&] { ruled_volume(sections[0], flat); }), "sections[1]");
  // Weights 2, 0.5, 2 interpolated by a quadratic need a negative middle control weight.
  std::vector<BSplineSurface> uneven;
  for (int k = 0; k < 3; ++k) {
    const double w = k == 1 ? 0.5 : 2.0;
    const KnotVector k1 = KnotVector::bezier(1);
    uneven.emplace_back(std::array<KnotVector, 2>{k1, k1}, 3, std::vector<double>{0, 0, 1.0 * k, 1, 0, 1.0 * k, 0, 1, 1.0 * k, 1, 1, 1.0 * k},
                        std::vector<double>{w, w, w, w});
  }
  EXPECT_EQ(where([&] { loft(uneven, 2); }), "sections");
  EXPECT_EQ(where([&] { loft(uneven, 1); }), "no error");
  auto incompatible = sections;
  EXPECT_EQ(where([&] { loft_parameters(incompatible); }), "sections[1]");
}

}  // namespace
}  // namespace volspline
