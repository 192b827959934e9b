// Attributes carried through knot insertion, degree elevation and Bézier extraction: an
// attribute whose control values are a coordinate of the control points is that coordinate as a
// function (same basis, same weights), so after every operation its control values must still be
// that coordinate of the new control points, and its value at any parameter the coordinate of the
// point there — for rational objects and points at infinity too.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/io/model_refinement.h"

namespace volspline {
namespace {

constexpr double kTolerance = 1e-12;

// `spline` as a model object with attributes "x" and "last" equal to its first and last coordinates.
template <int D>
ModelObject object_with_coordinate_attributes(const TensorSpline<D>& spline) {
  ModelObject object{"part", false, spline, nullptr};
  const auto k = static_cast<std::size_t>(spline.dimension());
  std::vector<double> first, last;
  for (std::size_t i = 0; i < spline.points().size(); i += k) {
    first.push_back(spline.points()[i]);
    last.push_back(spline.points()[i + k - 1]);
  }
  object.attributes["x"] = first;
  object.attributes["last"] = last;
  return object;
}

// The attributes of `object` are still its first and last coordinates, control value by control
// value and at random parameters.
template <int D>
void expect_attributes_follow_coordinates(const ModelObject& object, std::mt19937& rng, const std::string& what) {
  const auto& spline = std::get<TensorSpline<D>>(object.spline);
  const auto k = static_cast<std::size_t>(spline.dimension());
  const double scale = test_support::coefficient_scale(spline);
  const auto& x = object.attributes.at("x");
  const auto& last = object.attributes.at("last");
  ASSERT_EQ(x.size() * k, spline.points().size()) << what;
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(x[i], spline.points()[i * k], kTolerance * scale) << what << ", control point " << i;
    EXPECT_NEAR(last[i], spline.points()[i * k + k - 1], kTolerance * scale) << what << ", control point " << i;
  }
  for (int trial = 0; trial < 5; ++trial) {
    const auto t = test_support::random_parameter(rng, spline);
    const Eigen::VectorXd point = spline.evaluate(t);
    const std::vector<double> at(t.begin(), t.end());
    EXPECT_NEAR(evaluate_attribute(object, "x", at), point[0], kTolerance * scale) << what;
    EXPECT_NEAR(evaluate_attribute(object, "last", at), point[static_cast<Eigen::Index>(k) - 1], kTolerance * scale) << what;
  }
}

template <int D>
void check_every_operation(const TensorSpline<D>& spline, std::mt19937& rng, const std::string& what) {
  const ModelObject object = object_with_coordinate_attributes(spline);
  std::vector<double> knots;
  for (int d = 0; d < D; ++d) {
    knots = {spline.domain_min(d) + 0.3 * (spline.domain_max(d) - spline.domain_min(d)),
             spline.domain_min(d) + 0.71 * (spline.domain_max(d) - spline.domain_min(d))};
    const ModelObject inserted = refine_object(object, {RefinementStep::insertion(d, knots)});
    EXPECT_EQ(std::get<TensorSpline<D>>(inserted.spline).knot_vector(d).knots().size(), spline.knot_vector(d).knots().size() + 2);
    expect_attributes_follow_coordinates<D>(inserted, rng, what + ", knots inserted in direction " + std::to_string(d));
    const ModelObject elevated = refine_object(object, {RefinementStep::degree_elevation(d, 2)});
    EXPECT_EQ(std::get<TensorSpline<D>>(elevated.spline).knot_vector(d).degree(), spline.knot_vector(d).degree() + 2);
    expect_attributes_follow_coordinates<D>(elevated, rng, what + ", degree raised in direction " + std::to_string(d));
  }
  const auto pieces = bezier_objects(object, {RefinementStep::insertion(0, knots), RefinementStep::degree_elevation(D - 1, 1)});
  ASSERT_GT(pieces.size(), 1u) << what;
  for (std::size_t c = 0; c < pieces.size(); ++c) {
    EXPECT_TRUE(pieces[c].bezier);
    EXPECT_EQ(pieces[c].name, "part cell " + std::to_string(c));
    for (const KnotVector& kv : std::get<TensorSpline<D>>(pieces[c].spline).knot_vectors()) {
      EXPECT_TRUE(kv.is_bezier());
      EXPECT_EQ(kv.domain_min(), 0.0);
      EXPECT_EQ(kv.domain_max(), 1.0);
    }
    expect_attributes_follow_coordinates<D>(pieces[c], rng, what + ", Bézier piece " + std::to_string(c));
  }
}

TEST(ModelRefinement, AttributesEqualToACoordinateStayEqualThroughEveryOperation) {
  std::mt19937 rng(2024);
  for (const bool rational : {false, true}) {
    const std::string kind = rational ? "rational" : "polynomial";
    check_every_operation(test_support::random_spline<1>(rng, {3}, 3, 2, rational), rng, kind + " curve");
    check_every_operation(test_support::random_spline<2>(rng, {2, 3}, 2, 3, rational), rng, kind + " surface");
    check_every_operation(test_support::random_spline<3>(rng, {2, 1, 3}, 2, 3, rational), rng, kind + " volume");
  }
  // Points at infinity: the attribute joins the direction (d, a, 0) like the coordinates do.
  check_every_operation(test_support::random_spline<3>(rng, {2, 2, 2}, 2, 3, true, true, 1, true), rng,
                        "volume with a point at infinity");
}

TEST(ModelRefinement, WithoutStepsTheObjectIsUnchanged) {
  std::mt19937 rng(5);
  ModelObject object = object_with_coordinate_attributes(test_support::random_spline<3>(rng, {2, 2, 2}, 1, 3, true));
  object.bezier = true;
  object.metadata = {{"material", "steel"}};
  const ModelObject same = refine_object(object);
  EXPECT_EQ(std::get<BSplineVolume>(same.spline).points(), std::get<BSplineVolume>(object.spline).points());
  EXPECT_EQ(same.attributes, object.attributes);
  EXPECT_EQ(same.metadata, object.metadata);
  EXPECT_EQ(same.name, object.name);
  // A Bézier object stays one only while it is a single span.
  EXPECT_TRUE(same.bezier);
  const auto& volume = std::get<BSplineVolume>(object.spline);
  const double middle = 0.5 * (volume.domain_min(1) + volume.domain_max(1));
  EXPECT_FALSE(refine_object(object, {RefinementStep::insertion(1, {middle})}).bezier);
}

TEST(ModelRefinement, RejectsADirectionTheObjectDoesNotHave) {
  std::mt19937 rng(9);
  const ModelObject surface{"", false, test_support::random_spline<2>(rng, {2, 2}, 1, 3, false), nullptr};
  try {
    refine_object(surface, {RefinementStep::degree_elevation(2, 1)});
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("direction 2 does not exist for a bspline_surface"), std::string::npos) << e.what();
  }
  ModelObject bad = surface;
  bad.attributes["short"] = {1.0};
  try {
    bezier_objects(bad);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where().rfind("attributes.short", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace volspline
