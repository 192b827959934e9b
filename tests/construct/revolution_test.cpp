// Volumes of revolution (Lasser 1994, Theorem 2): distances to the axis and axial heights are
// those of the profile, full turns close, Lasser's single 180-degree segment is the same solid.
#include "volspline/construct/revolution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/spline/iso_restriction.h"

namespace volspline {
namespace {

using test_support::random_parameter;
using test_support::random_spline;

struct AxisFrame {
  Eigen::Vector3d a, n, e1, e2;  // e1, e2, n right-handed
  explicit AxisFrame(Eigen::Vector3d point, Eigen::Vector3d direction) : a(point), n(direction.normalized()) {
    e1 = n.unitOrthogonal();
    e2 = n.cross(e1);
  }
  double height(const Eigen::Vector3d& p) const { return n.dot(p - a); }
  double radius(const Eigen::Vector3d& p) const { return (p - a - n * height(p)).norm(); }
  double angle(const Eigen::Vector3d& p) const { return std::atan2(e2.dot(p - a), e1.dot(p - a)); }
};

// The counter-clockwise angle in [0, 2 pi) from q to p about the axis.
double turn(const AxisFrame& f, const Eigen::Vector3d& q, const Eigen::Vector3d& p) {
  double d = f.angle(p) - f.angle(q);
  while (d < 0) d += 2 * std::numbers::pi;
  while (d >= 2 * std::numbers::pi) d -= 2 * std::numbers::pi;
  return d;
}

class Revolution : public ::testing::TestWithParam<std::tuple<bool, double>> {};

TEST_P(Revolution, PreservesDistanceToTheAxisAndHeight) {
  const auto [rational, angle] = GetParam();
  std::mt19937 rng(21);
  for (int trial = 0; trial < 4; ++trial) {
    const auto F = random_spline<2>(rng, {2, 3}, 3, 3, rational, trial % 2 == 0, 2, rational && trial == 1);
    const AxisFrame frame(Eigen::Vector3d(0.3, -0.4, 0.2), Eigen::Vector3d(1.0, 2.0, -0.5));
    const auto V = revolve(F, frame.a, Eigen::Vector3d(1.0, 2.0, -0.5), angle);
    EXPECT_EQ(V.degrees()[2], 2);
    EXPECT_EQ(V.knot_vector(2).num_spans(), static_cast<int>(std::ceil(angle / 90.0)));
    for (double w : V.weights()) EXPECT_GE(w, 0.0);
    for (int i = 0; i < 60; ++i) {
      const auto uv = random_parameter(rng, F);
      const double w = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      const Eigen::Vector3d q = F.evaluate(uv), p = V.evaluate({uv[0], uv[1], w});
      const double scale = 4.0;
      EXPECT_NEAR(frame.radius(p), frame.radius(q), 1e-12 * scale);
      EXPECT_NEAR(frame.height(p), frame.height(q), 1e-12 * scale);
      if (frame.radius(q) > 1e-6 && angle < 360) {
        EXPECT_LE(turn(frame, q, p), angle * std::numbers::pi / 180 + 1e-9);
      }
    }
    // V(u, v, 0) = F exactly (M_0 = I); V(u, v, 1) is F turned by the whole angle.
    for (int i = 0; i < 20; ++i) {
      const auto uv = random_parameter(rng, F);
      const Eigen::Vector3d q = F.evaluate(uv);
      EXPECT_LT((V.evaluate({uv[0], uv[1], 0.0}) - q).norm(), 1e-14 * 4);
      const Eigen::Vector3d end = V.evaluate({uv[0], uv[1], 1.0});
      if (frame.radius(q) > 1e-3) {
        const double expected = angle == 360 ? 0.0 : angle * std::numbers::pi / 180;
        double got = turn(frame, q, end);
        if (angle == 360 && got > std::numbers::pi) got -= 2 * std::numbers::pi;
        EXPECT_NEAR(got, expected, 1e-11);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Angles, Revolution,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(30.0, 90.0, 120.0, 180.0, 250.0, 360.0)));

TEST(Revolution, FullTurnCloses) {
  std::mt19937 rng(4);
  const auto F = random_spline<2>(rng, {2, 2}, 3, 3, true);
  const auto V = revolve(F, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 1), 360.0);
  EXPECT_EQ(V.knot_vector(2).num_spans(), 4);
  const auto first = restrict_to_iso(V, 2, 0.0), last = restrict_to_iso(V, 2, 1.0);
  EXPECT_EQ(first.homogeneous(), last.homogeneous());  // the last control points are copies
  for (int i = 0; i < 100; ++i) {
    const auto uv = random_parameter(rng, F);
    EXPECT_LT((V.evaluate({uv[0], uv[1], 0.0}) - V.evaluate({uv[0], uv[1], 1.0})).norm(), 1e-13);
  }
}

TEST(Revolution, SingleSegmentHasPointsAtInfinityAndMatchesRevolve) {
  std::mt19937 rng(8);
  const auto F = random_spline<2>(rng, {1, 2}, 2, 3, true);
  const Eigen::Vector3d a(0.5, 0.5, -1.0), n(0.0, 0.0, 2.0);
  const AxisFrame frame(a, n);
  const auto single = revolve_single_segment(F, a, n, 180.0);
  const auto multi = revolve(F, a, n, 180.0);
  EXPECT_TRUE(single.knot_vector(2).is_bezier());
  const int layer = F.num_control_points_total();
  for (int i = 0; i < layer; ++i) {
    EXPECT_EQ(single.weights()[static_cast<std::size_t>(layer + i)], 0.0);  // M_1 at alpha = 180
    EXPECT_GT(single.weights()[static_cast<std::size_t>(i)], 0.0);
  }
  // The two parameterise the same half turn differently: match points by angle, not by w.
  // The angle as a function of w is the same for every profile point (one matrix M(w)).
  const auto uv0 = random_parameter(rng, F);
  const Eigen::Vector3d q0 = F.evaluate(uv0);
  ASSERT_GT(frame.radius(q0), 1e-3);
  for (double w : {0.05, 0.3, 0.5, 0.77, 0.95}) {
    const double target = turn(frame, q0, single.evaluate({uv0[0], uv0[1], w}));
    double lo = 0.0, hi = 1.0;  // the angle grows monotonically with w
    for (int it = 0; it < 80; ++it) {
      const double mid = (lo + hi) / 2;
      (turn(frame, q0, multi.evaluate({uv0[0], uv0[1], mid})) < target ? lo : hi) = mid;
    }
    for (int i = 0; i < 20; ++i) {
      const auto uv = random_parameter(rng, F);
      EXPECT_LT((single.evaluate({uv[0], uv[1], w}) - multi.evaluate({uv[0], uv[1], lo})).norm(), 1e-12 * 4);
    }
  }
  // Smaller angles: positive middle weights cos(alpha / 2) times the profile's.
  const auto quarter = revolve_single_segment(F, a, n, 90.0);
  EXPECT_NEAR(quarter.weights()[static_cast<std::size_t>(layer)], F.weights()[0] * std::sqrt(0.5), 1e-15);
}

TEST(Revolution, BadInput) {
  std::mt19937 rng(2);
  const auto F = random_spline<2>(rng, {1, 1}, 1, 3, false);
  auto where = [](auto f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return e.where();
    }
    return std::string("no error");
  };
  const Eigen::Vector3d o = Eigen::Vector3d::Zero(), z(0, 0, 1);
  EXPECT_EQ(where([&] { revolve(F, o, Eigen::Vector3d::Zero(), 90.0); }), "axis_direction");
  EXPECT_EQ(where([&] { revolve(F, o, Eigen::Vector3d(0, std::nan(""), 1), 90.0); }), "axis_direction");
  EXPECT_EQ(where([&] { revolve(F, Eigen::Vector3d(0, 0, INFINITY), z, 90.0); }), "axis_point");
  EXPECT_EQ(where([&] { revolve(F, o, z, 0.0); }), "angle");
  EXPECT_EQ(where([&] { revolve(F, o, z, -10.0); }), "angle");
  EXPECT_EQ(where([&] { revolve(F, o, z, 360.001); }), "angle");
  EXPECT_EQ(where([&] { revolve(F, o, z, std::nan("")); }), "angle");
  EXPECT_EQ(where([&] { revolve_single_segment(F, o, z, 180.5); }), "angle");
  EXPECT_EQ(where([&] { revolve_single_segment(F, o, z, 0.0); }), "angle");
  EXPECT_EQ(where([&] { revolve(random_spline<2>(rng, {1, 1}, 1, 2, false), o, z, 90.0); }), "profile");
  EXPECT_EQ(where([&] { revolve(F, o, z, 360.0); }), "no error");
  EXPECT_EQ(where([&] { revolve_single_segment(F, o, z, 180.0); }), "no error");
}

}  // namespace
}  // namespace volspline
