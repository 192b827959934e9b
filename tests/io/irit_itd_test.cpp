// IRIT data files: hand-written files in IRIT's conventions (orders, weight-first premultiplied
// rational points, u fastest) evaluate to the shapes they describe, written files read back
// exactly, and bad tokens are reported with file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "support/exchange_support.h"
#include "volspline/core/error.h"
#include "volspline/io/irit_itd.h"

namespace volspline {
namespace {

TEST(IritItd, RationalQuarterCircleUsesOrdersAndWeightFirstPremultipliedPoints) {
  // (1, 0), (1, 1) with weight sqrt(2)/2 written as (w, w x, w y), (0, 1): a quarter of the unit circle.
  const Model model = parse_irit_itd(R"(# a comment
[OBJECT QUARTER
    [CURVE BSPLINE 3 3 P2
        [KV 0 0 0 1 1 1]
        [1 1 0]
        [0.70710678118654757 0.70710678118654757 0.70710678118654757]
        [1 0 1]
    ]
])",
                                     "q.itd");
  ASSERT_EQ(model.objects.size(), 1u);
  EXPECT_EQ(model.objects[0].name, "QUARTER");
  const auto& c = std::get<BSplineCurve>(model.objects[0].spline);
  EXPECT_EQ(c.degrees()[0], 2);
  ASSERT_TRUE(c.is_rational());
  for (double t = 0; t <= 1.0; t += 1.0 / 64) EXPECT_NEAR(c.evaluate({t}).norm(), 1.0, 1e-15);
  EXPECT_NEAR((c.evaluate({0.5}) - Eigen::Vector2d(std::sqrt(0.5), std::sqrt(0.5))).norm(), 0.0, 1e-15);
}

TEST(IritItd, TrivariateListsControlPointsWithUFastest) {
  // The trilinear map (u, v, w) -> (u, 2 v, 3 w) + (1, 0, 0): its control point (i, j, k) is at
  // (1 + i, 2 j, 3 k), listed i fastest, then j, then k. Attributes and nested objects are skipped.
  std::string text = "[OBJECT [COLOR 4] [RGB \"255,0,0\"] OUTER\n [OBJECT BOX\n  [TRIVAR BSPLINE 2 2 2 2 2 2 E3\n";
  text += "   [KV 0 0 1 1]\n   [KV 0 0 1 1]\n   [KV 0 0 1 1]\n";
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) text += "   [" + std::to_string(1 + i) + " " + std::to_string(2 * j) + " " + std::to_string(3 * k) + "]\n";
  text += "  ]\n ]\n [TRIVAR BEZIER 2 2 3 E1 [0] [0] [0] [0] [1] [1] [1] [1] [2] [2] [2] [2]]\n]\n";
  const Model model = parse_irit_itd(text, "box.itd");
  ASSERT_EQ(model.objects.size(), 2u);
  EXPECT_EQ(model.objects[0].name, "BOX");
  EXPECT_EQ(model.objects[1].name, "OUTER");
  const auto& box = std::get<BSplineVolume>(model.objects[0].spline);
  std::mt19937 rng(1);
  for (int n = 0; n < 50; ++n) {
    const auto t = test_support::random_parameter(rng, box);
    EXPECT_NEAR((box.evaluate(t) - Eigen::Vector3d(1 + t[0], 2 * t[1], 3 * t[2])).norm(), 0.0, 1e-15);
  }
  // The Bézier trivariate of orders (2, 2, 3) whose values 0, 1, 2 in w give f = 2 w.
  const auto& bezier = std::get<BSplineVolume>(model.objects[1].spline);
  EXPECT_TRUE(model.objects[1].bezier);
  EXPECT_EQ(bezier.degrees(), (BSplineVolume::Index{1, 1, 2}));
  EXPECT_NEAR(bezier.evaluate({0.3, 0.6, 0.25})[0], 0.5, 1e-15);
}

TEST(IritItd, RoundTripOfCurvesSurfacesAndVolumesIsExact) {
  std::mt19937 rng(2);
  for (const int dimension : {1, 2, 3}) {
    Model model = test_support::random_exchange_model(rng, dimension);
    model.objects[2].name = "";
    const std::string text = irit_itd_text(model);
    EXPECT_NE(text.find("[TRIVAR BSPLINE"), std::string::npos);
    EXPECT_NE(text.find("[SURFACE BSPLINE"), std::string::npos);
    EXPECT_NE(text.find("[CURVE BSPLINE"), std::string::npos);
    EXPECT_NE(text.find(" P" + std::to_string(dimension) + "\n"), std::string::npos);
    const Model back = parse_irit_itd(text, "r.itd");
    EXPECT_EQ(test_support::max_model_difference(model, back, rng, false), 0.0);
    EXPECT_EQ(back.objects[0].name, "curve");
    EXPECT_EQ(back.objects[2].name, "");
  }
}

TEST(IritItd, PointsAtInfinitySurviveAsWeightZeroHomogeneousPoints) {
  std::mt19937 rng(3);
  Model model{{ModelObject{"inf", false, test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, true, true, 1, true), nullptr}}, nullptr};
  const Model back = parse_irit_itd(irit_itd_text(model), "inf.itd");
  EXPECT_EQ(std::get<BSplineVolume>(back.objects[0].spline).homogeneous(), std::get<BSplineVolume>(model.objects[0].spline).homogeneous());
}

std::string irit_error_of(const std::string& text) {
  try {
    parse_irit_itd(text, "bad.itd");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(IritItd, BadTokensNameFileLineAndExpectation) {
  const std::string good = "[OBJECT C\n[CURVE BSPLINE 2 2 E2\n[KV 0 0 1 1]\n[0 0]\n[1 1]\n]\n]\n";
  EXPECT_EQ(irit_error_of(good), "no error");
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return irit_error_of(text);
  };
  EXPECT_EQ(edit("2 2 E2", "2 x E2"), "bad.itd: line 2: expected the order (degree + 1, from 2 to 65) in u, got 'x'");
  EXPECT_EQ(edit("E2", "Q2"), "bad.itd: line 2: expected the point type E1..E9 or P1..P9, got 'Q2'");
  EXPECT_EQ(edit("[KV 0 0 1 1]", "[KVP 0 0 1 1]"), "bad.itd: line 3: expected KV (periodic knot vectors, KVP, are not supported), got 'KVP'");
  EXPECT_EQ(edit("[KV 0 0 1 1]", "[KV 0 0 1]"), "bad.itd: line 3: expected the 4 knots of u (count 2 + order 2), not 3 then, got ']'");
  EXPECT_EQ(edit("[KV 0 0 1 1]", "[KV 0 1 0 1]"), "bad.itd: line 3: knots must not decrease: 0 follows 1 (knot [2] of u)");
  EXPECT_EQ(edit("[1 1]", "[1 1 1]"), "bad.itd: line 5: expected ']' closing control point 1 after its 2 numbers (point type E2), got '1'");
  EXPECT_EQ(edit("[1 1]", "[1 nan]"), "bad.itd: line 5: expected a coordinate (a finite number) of control point 1 (2 numbers for E2), got 'nan'");
  EXPECT_EQ(irit_error_of(good.substr(0, good.size() - 4)), "bad.itd: line 6: expected ']' closing the CURVE after its 2 control points, got the end of the file");
  EXPECT_EQ(edit("CURVE BSPLINE", "POLYGON BSPLINE"),
            "bad.itd: line 2: expected OBJECT, CURVE, SURFACE or TRIVAR (only B-spline and Bezier curves, surfaces and trivariates are read), got 'POLYGON'");
  EXPECT_EQ(edit("2 2 E2", "2 3 E2"), "bad.itd: line 2: expected an order of at most the number of control points (2), got '3'");
  EXPECT_EQ(edit("[CURVE BSPLINE 2 2 E2", "[CURVE BSPLINE 200000 2 E2"),
            "bad.itd: line 3: expected the 200002 knots of u (count 200000 + order 2), not 4 then, got ']'");
  EXPECT_EQ(irit_error_of("\n[TRIVAR BEZIER 50 50 50 E1 [0] [1]]"), "bad.itd: line 2: the header asks for more control points than the file holds");
  EXPECT_EQ(irit_error_of("# nothing\n"), "bad.itd: line 2: expected at least one [CURVE ...], [SURFACE ...] or [TRIVAR ...], got none");
  EXPECT_EQ(edit("[1 1]", "[1 -1 1]").rfind("bad.itd", 0), 0u);
  // Negative weights: the homogeneous point (w, w x) with w < 0.
  EXPECT_EQ(irit_error_of("[CURVE BSPLINE 2 2 P1\n[KV 0 0 1 1]\n[1 0]\n[-1 1]\n]"), "bad.itd: line 4: a homogeneous weight is negative: -1 (weights[1])");
}

TEST(IritItd, MoreThanNineCoordinatesCannotBeWritten) {
  std::mt19937 rng(4);
  Model model{{ModelObject{"", false, test_support::random_spline<1>(rng, {2}, 2, 10, false), nullptr}}, nullptr};
  EXPECT_THROW(irit_itd_text(model), InvalidInput);
}

}  // namespace
}  // namespace volspline
