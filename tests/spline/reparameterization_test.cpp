// Affine reparameterisation: V'(phi(t)) = V(t) with phi the affine map of the domain onto [a, b],
// and every first partial in the mapped direction scaled by the inverse factor (chain rule).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/spline/reparameterization.h"

namespace volspline {
namespace {

using test_support::coefficient_scale;
using test_support::random_parameter;
using test_support::random_spline;

template <int D>
void expect_affine_reparameterisation(const TensorSpline<D>& s, int direction, double a, double b, std::mt19937& rng) {
  const TensorSpline<D> r = reparameterize(s, direction, a, b);
  EXPECT_EQ(r.domain_min(direction), a);
  EXPECT_EQ(r.domain_max(direction), b);
  const double a0 = s.domain_min(direction), b0 = s.domain_max(direction);
  const double factor = (b - a) / (b0 - a0);
  const double scale = coefficient_scale(s);
  const auto first = derivative_multi_indices<D>(1);
  for (int trial = 0; trial < 40; ++trial) {
    auto t = random_parameter(rng, s);
    auto mapped = t;
    mapped[static_cast<std::size_t>(direction)] = a + (t[static_cast<std::size_t>(direction)] - a0) * factor;
    const auto original = s.evaluate_derivatives(t, 1);
    const auto moved = r.evaluate_derivatives(mapped, 1);
    ASSERT_EQ(original.size(), moved.size());
    const std::size_t k = static_cast<std::size_t>(s.dimension());
    for (std::size_t m = 0; m < first.size(); ++m) {
      // d/dt' = (dt/dt') d/dt in the mapped direction only.
      const double chain = first[m][static_cast<std::size_t>(direction)] == 1 ? 1.0 / factor : 1.0;
      for (std::size_t c = 0; c < k; ++c) {
        const double expected = original[m * k + c] * chain;
        ASSERT_NEAR(moved[m * k + c], expected, 1e-12 * scale * (1 + std::abs(expected)) / std::min(1.0, factor))
            << "derivative " << m << " coordinate " << c;
      }
    }
  }
  // Affine knot maps leave the B-spline basis unchanged, so the control points stay as they are.
  ASSERT_EQ(r.points().size(), s.points().size());
  for (std::size_t i = 0; i < s.points().size(); ++i) EXPECT_NEAR(r.points()[i], s.points()[i], 4e-16 * scale);
  EXPECT_EQ(r.weights().size(), s.weights().size());
}

TEST(Reparameterization, EveryDirectionOfCurvesSurfacesVolumesAndHypervolumes) {
  std::mt19937 rng(41);
  for (const bool rational : {false, true}) {
    for (const bool clamped : {true, false}) {
      const auto curve = random_spline<1>(rng, {3}, 4, 2, rational, clamped);
      expect_affine_reparameterisation(curve, 0, -7.0, 0.5, rng);
      const auto surface = random_spline<2>(rng, {2, 3}, 3, 3, rational, clamped);
      for (int d = 0; d < 2; ++d) expect_affine_reparameterisation(surface, d, 10.0, 1000.0, rng);
      const auto volume = random_spline<3>(rng, {2, 1, 3}, 3, 3, rational, clamped);
      for (int d = 0; d < 3; ++d) expect_affine_reparameterisation(volume, d, 0.25, 0.3, rng);
      const auto hyper = random_spline<4>(rng, {1, 2, 1, 2}, 2, 3, rational, clamped);
      for (int d = 0; d < 4; ++d) expect_affine_reparameterisation(hyper, d, -1.0, 1.0, rng);
    }
  }
}

TEST(Reparameterization, UnitBoxMapsEveryDomainOntoZeroOne) {
  std::mt19937 rng(7);
  const auto volume = random_spline<3>(rng, {3, 2, 2}, 3, 3, true, false);
  const auto unit = reparameterize_to_unit_box(volume);
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(unit.domain_min(d), 0.0);
    EXPECT_EQ(unit.domain_max(d), 1.0);
  }
  const double scale = coefficient_scale(volume);
  for (int trial = 0; trial < 50; ++trial) {
    const auto t = random_parameter(rng, volume);
    std::array<double, 3> s{};
    for (int d = 0; d < 3; ++d)
      s[static_cast<std::size_t>(d)] = (t[static_cast<std::size_t>(d)] - volume.domain_min(d)) / (volume.domain_max(d) - volume.domain_min(d));
    const auto x = volume.evaluate(t), y = unit.evaluate(s);
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(x[c], y[c], 1e-12 * scale);
  }
  // The domain corners map exactly: the ends are not computed, they are set.
  const auto corner = volume.evaluate({volume.domain_max(0), volume.domain_min(1), volume.domain_max(2)});
  const auto mapped = unit.evaluate({1.0, 0.0, 1.0});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(corner[c], mapped[c], 1e-13 * scale);
}

TEST(Reparameterization, RejectsEmptyReversedAndNonFiniteIntervalsAndUnknownDirections) {
  std::mt19937 rng(3);
  const auto volume = random_spline<3>(rng, {2, 2, 2}, 2, 3, false);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(reparameterize(volume, 0, 1.0, 1.0), InvalidInput);
  EXPECT_THROW(reparameterize(volume, 1, 2.0, 1.0), InvalidInput);
  EXPECT_THROW(reparameterize(volume, 2, 0.0, inf), InvalidInput);
  EXPECT_THROW(reparameterize(volume, 2, nan, 1.0), InvalidInput);
  EXPECT_THROW(reparameterize(volume, 3, 0.0, 1.0), InvalidInput);
  EXPECT_THROW(reparameterize(volume, -1, 0.0, 1.0), InvalidInput);
}

}  // namespace
}  // namespace volspline
