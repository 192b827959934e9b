// Translation volumes (Lasser 1994, Theorem 1) for random B-spline surfaces and curves.
#include "volspline/construct/translation.h"

#include <gtest/gtest.h>

#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

struct Case {
  bool rational_surface, rational_curve, zero_weight, clamped;
};

class Translation : public ::testing::TestWithParam<Case> {};

TEST_P(Translation, IsTheSurfacePlusTheCurve) {
  const Case c = GetParam();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    const auto F = random_spline<2>(rng, {2, 3}, 3, 3, c.rational_surface, c.clamped, 2, c.zero_weight);
    auto K = random_spline<1>(rng, {3}, 4, 3, c.rational_curve, c.clamped, 2, c.zero_weight);
    // Move K so that it starts at F(u_min, v_min): Theorem 1's precondition F(0,0) = K(0).
    const Eigen::VectorXd shift = F.evaluate({F.domain_min(0), F.domain_min(1)}) - K.evaluate({K.domain_min(0)});
    K = transform_affine(K, Eigen::Matrix3d::Identity(), shift);
    const auto V = translation_volume(F, K);
    EXPECT_EQ(V.is_rational(), c.rational_surface || c.rational_curve);
    const double scale = 4.0;
    for (int i = 0; i < 50; ++i) {
      const auto uv = random_parameter(rng, F);
      const auto w = random_parameter(rng, K);
      // V(u, v, w_min) = F(u, v)
      EXPECT_LT((V.evaluate({uv[0], uv[1], K.domain_min(0)}) - F.evaluate(uv)).norm(), 1e-12 * scale);
      // V(u_min, v_min, w) = K(w)
      EXPECT_LT((V.evaluate({F.domain_min(0), F.domain_min(1), w[0]}) - K.evaluate(w)).norm(), 1e-12 * scale);
      // and everywhere V = F + K - K(w_min): every u and v iso-surface is congruent (Remark)
      const Eigen::VectorXd expected = F.evaluate(uv) + K.evaluate(w) - K.evaluate({K.domain_min(0)});
      EXPECT_LT((V.evaluate({uv[0], uv[1], w[0]}) - expected).norm(), 1e-12 * scale);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, Translation,
                         ::testing::Values(Case{false, false, false, true}, Case{true, false, false, true}, Case{false, true, false, true},
                                           Case{true, true, false, true}, Case{true, true, true, true}, Case{true, true, false, false},
                                           Case{false, false, false, false}));

TEST(Translation, CurveNotStartingOnTheSurfaceIsTranslated) {
  std::mt19937 rng(5);
  const auto F = random_spline<2>(rng, {2, 2}, 2, 3, true);
  const auto K = random_spline<1>(rng, {2}, 3, 3, true);
  const auto V = translation_volume(F, K);
  const Eigen::VectorXd offset = F.evaluate({F.domain_min(0), F.domain_min(1)}) - K.evaluate({K.domain_min(0)});
  for (double w : {0.1, 0.5, 0.9}) {
    const double t = K.domain_min(0) + w * (K.domain_max(0) - K.domain_min(0));
    EXPECT_LT((V.evaluate({F.domain_min(0), F.domain_min(1), t}) - (K.evaluate({t}) + offset)).norm(), 1e-12 * 4);
  }
}

TEST(Translation, ExtrudeIsLinearAlongTheVector) {
  std::mt19937 rng(9);
  const auto F = random_spline<2>(rng, {3, 2}, 3, 3, true, true, 2, true);
  const Eigen::Vector3d T(0.5, -1.0, 2.0);
  const auto V = extrude(F, T);
  EXPECT_EQ(V.degrees()[2], 1);
  for (int i = 0; i < 30; ++i) {
    const auto uv = random_parameter(rng, F);
    for (double w : {0.0, 0.3, 1.0})
      EXPECT_LT((V.evaluate({uv[0], uv[1], w}) - (F.evaluate(uv) + w * T)).norm(), 1e-12 * 4);
  }
}

TEST(Translation, BadInput) {
  std::mt19937 rng(1);
  const auto F = random_spline<2>(rng, {1, 1}, 1, 3, false);
  const auto K2 = random_spline<1>(rng, {1}, 1, 2, false);
  try {
    translation_volume(F, K2);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "path");
  }
  EXPECT_THROW(extrude(F, Eigen::Vector3d::Zero()), InvalidInput);
  EXPECT_THROW(extrude(F, Eigen::Vector3d(std::nan(""), 0, 0)), InvalidInput);
  EXPECT_THROW(extrude(random_spline<2>(rng, {1, 1}, 1, 2, false), Eigen::Vector3d(1, 0, 0)), InvalidInput);
}

}  // namespace
}  // namespace volspline
