#include "volspline/spline/bezier_extraction.h"

#include <gtest/gtest.h>

#include "support/geometry_checks.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::expect_same_geometry;
using test_support::random_spline;

template <int D>
void check_pieces(const TensorSpline<D>& s, std::mt19937& rng) {
  const auto pieces = bezier_pieces(s);
  std::size_t cells = 1;
  for (int d = 0; d < D; ++d) cells *= static_cast<std::size_t>(s.knot_vector(d).num_spans());
  ASSERT_EQ(pieces.size(), cells);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& piece = pieces[i];
    // cell order: first direction fastest
    std::size_t rest = i;
    for (int d = 0; d < D; ++d) {
      const auto breaks = s.knot_vector(d).breakpoints();
      const std::size_t cell = rest % (breaks.size() - 1);
      rest /= breaks.size() - 1;
      EXPECT_TRUE(piece.knot_vector(d).is_bezier());
      EXPECT_EQ(piece.domain_min(d), breaks[cell]);
      EXPECT_EQ(piece.domain_max(d), breaks[cell + 1]);
    }
    expect_same_geometry(s, piece, rng, 15);
  }
}

template <int D>
void check_split(const TensorSpline<D>& s, std::mt19937& rng) {
  for (int d = 0; d < D; ++d) {
    std::uniform_real_distribution<double> u(s.domain_min(d), s.domain_max(d));
    for (double t : {u(rng), s.knot_vector(d).breakpoints()[1]}) {
      const auto [left, right] = split(s, d, t);
      EXPECT_EQ(left.domain_max(d), t);
      EXPECT_EQ(right.domain_min(d), t);
      EXPECT_EQ(left.domain_min(d), s.domain_min(d));
      EXPECT_EQ(right.domain_max(d), s.domain_max(d));
      expect_same_geometry(s, left, rng, 20);
      expect_same_geometry(s, right, rng, 20);
    }
  }
}

TEST(BezierExtraction, PiecesReproduceTheSpline) {
  std::mt19937 rng(30);
  check_pieces(random_spline<1>(rng, {3}, 4, 2, true, false, 2, true), rng);
  check_pieces(random_spline<1>(rng, {3}, 4, 2, false, true, 3), rng);
  check_pieces(random_spline<2>(rng, {2, 3}, 3, 3, false), rng);
  check_pieces(random_spline<3>(rng, {3, 3, 3}, 3, 3, false), rng);
  check_pieces(random_spline<3>(rng, {2, 1, 2}, 2, 3, true, false, 2, true), rng);
  check_pieces(random_spline<4>(rng, {1, 1, 2, 1}, 2, 2, false), rng);
}

TEST(Split, HalvesReproduceTheSpline) {
  std::mt19937 rng(31);
  check_split(random_spline<1>(rng, {3}, 3, 2, false, false), rng);
  check_split(random_spline<2>(rng, {2, 3}, 3, 3, true, true, 2, true), rng);
  check_split(random_spline<3>(rng, {3, 2, 2}, 3, 3, false), rng);
  check_split(random_spline<4>(rng, {1, 2, 1, 2}, 2, 2, true), rng);
}

TEST(Split, RejectsParametersAtOrOutsideTheEnds) {
  std::mt19937 rng(32);
  const auto s = random_spline<2>(rng, {2, 2}, 2, 3, false);
  EXPECT_THROW(split(s, 0, s.domain_min(0)), InvalidInput);
  EXPECT_THROW(split(s, 1, s.domain_max(1) + 1), InvalidInput);
}

}  // namespace
}  // namespace volspline
