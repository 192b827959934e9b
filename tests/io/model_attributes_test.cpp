// Per-control-point attributes in model files: read and written bit for bit, evaluated with the
// basis and the weights of the geometry, and rejected with their JSON path when malformed.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "support/exchange_support.h"
#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"
#include "volspline/spline/attribute_spline.h"

namespace volspline {
namespace {

std::string message_of(const std::string& text) {
  try {
    parse_model(text, "model.json");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

const char* kCurve = R"({"volspline": 1, "objects": [{"type": "bezier_curve", "degree": [2],
  "control_points": [[0, 0], [1, 2], [2, 0]], "weights": [1, 0.5, 1], ATTRIBUTES}]})";

std::string curve_with(const std::string& attributes) {
  std::string text = kCurve;
  text.replace(text.find("ATTRIBUTES"), 10, attributes);
  return text;
}

TEST(ModelAttributes, RoundTripEveryBitIncludingSubnormalsAndNegativeZero) {
  std::mt19937 rng(11);
  Model model = test_support::random_exchange_model(rng);
  model.objects[0].attributes["odd"] = std::vector<double>(model.objects[0].attributes["temperature"].size(), -0.0);
  model.objects[0].attributes["odd"][0] = 5e-324;
  model.objects[0].attributes["odd"][1] = 0.1;
  model.objects[0].attributes["name with \"quotes\""] = model.objects[0].attributes["temperature"];
  const Model back = parse_model(model_to_json(model), "m.json");
  ASSERT_EQ(back.objects.size(), model.objects.size());
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    ASSERT_EQ(back.objects[i].attributes.size(), model.objects[i].attributes.size());
    for (const auto& [name, values] : model.objects[i].attributes) {
      const auto& read = back.objects[i].attributes.at(name);
      ASSERT_EQ(read.size(), values.size());
      EXPECT_EQ(std::memcmp(read.data(), values.data(), values.size() * sizeof(double)), 0) << name;
    }
  }
  EXPECT_EQ(model_to_json(back), model_to_json(model));
}

TEST(ModelAttributes, FilesWithoutAttributesAreWrittenAsBefore) {
  std::mt19937 rng(12);
  Model model = test_support::random_exchange_model(rng);
  for (auto& object : model.objects) object.attributes.clear();
  EXPECT_EQ(model_to_json(model).find("attributes"), std::string::npos);
}

// An attribute is one more coordinate of the homogeneous control points (w x, w a, w): giving
// it the x coordinates of the control points must reproduce x(t) exactly, rational or not.
TEST(ModelAttributes, AnAttributeEqualToACoordinateEvaluatesToThatCoordinate) {
  std::mt19937 rng(13);
  for (const bool rational : {false, true}) {
    for (const bool zero_weight : {false, true}) {
      if (zero_weight && !rational) continue;
      const auto spline = test_support::random_spline<3>(rng, {2, 3, 2}, 3, 3, rational, true, 2, zero_weight);
      ModelObject object{"", false, spline, nullptr};
      std::vector<double> x;
      for (int i = 0; i < spline.num_control_points_total(); ++i) x.push_back(spline.points()[3 * static_cast<std::size_t>(i)]);
      object.attributes["x"] = x;
      for (int s = 0; s < 100; ++s) {
        const auto t = test_support::random_parameter(rng, spline);
        EXPECT_NEAR(evaluate_attribute(object, "x", {t[0], t[1], t[2]}), spline.evaluate(t)[0], 1e-12);
      }
    }
  }
}

TEST(ModelAttributes, AConstantAttributeIsConstantEvenWhenRational) {
  // Partition of unity of the rational basis: sum_i N_i w_i c / sum_i N_i w_i = c.
  std::mt19937 rng(14);
  const auto spline = test_support::random_spline<2>(rng, {3, 2}, 4, 2, true, false);
  ModelObject object{"", false, spline, nullptr};
  object.attributes["c"] = std::vector<double>(static_cast<std::size_t>(spline.num_control_points_total()), 2.5);
  for (int s = 0; s < 100; ++s) {
    const auto t = test_support::random_parameter(rng, spline);
    EXPECT_NEAR(evaluate_attribute(object, "c", {t[0], t[1]}), 2.5, 1e-13);
  }
}

TEST(ModelAttributes, SplitCoordinatesUndoesAppendCoordinates) {
  std::mt19937 rng(15);
  const auto spline = test_support::random_spline<3>(rng, {2, 1, 2}, 2, 3, true);
  const std::vector<double> field(static_cast<std::size_t>(spline.num_control_points_total()), 1.25);
  const auto [geometry, fields] = split_coordinates(append_coordinates(spline, {field}), 3);
  EXPECT_EQ(geometry.points(), spline.points());
  EXPECT_EQ(geometry.weights(), spline.weights());
  ASSERT_EQ(fields.size(), 1u);
  EXPECT_EQ(fields[0], field);
}

TEST(ModelAttributes, ParsedFromAFileAndEvaluated) {
  const Model model = parse_model(curve_with(R"("attributes": {"t": [1, 1, 3]})"), "model.json");
  // a(1/2) = (1 * 1/4 + 0.5 * 1 * 1/2 + 3 * 1/4) / (1/4 + 0.5 / 2 + 1/4) = 1.25 / 0.75.
  EXPECT_NEAR(evaluate_attribute(model.objects[0], "t", {0.5}), 1.25 / 0.75, 1e-15);
}

TEST(ModelAttributes, MalformedAttributesNameTheirJsonPath) {
  EXPECT_EQ(message_of(curve_with(R"("attributes": {"t": [1, 2]})")),
            "model.json: objects[0].attributes.t: expected an array of 3 numbers (one per control point), got an array of 2 elements");
  EXPECT_EQ(message_of(curve_with(R"("attributes": {"t": [1, "2", 3]})")),
            "model.json: objects[0].attributes.t[1]: expected a number, got the string \"2\"");
  EXPECT_EQ(message_of(curve_with(R"("attributes": {"t": [1, 1e999, 3]})")),
            "model.json: objects[0].attributes.t[1]: expected a finite number, got 1e999 (beyond the range of a double)");
  EXPECT_EQ(message_of(curve_with(R"("attributes": [1, 2, 3])")),
            "model.json: objects[0].attributes: expected an object of named arrays of numbers (one number per control point), got an array of 3 elements");
  EXPECT_EQ(message_of(curve_with(R"("attributes": {"": [1, 2, 3]})")),
            "model.json: objects[0].attributes[\"\"]: expected a nonempty attribute name, got \"\"");
}

TEST(ModelAttributes, EvaluatingAMissingAttributeOrOutsideTheDomainThrows) {
  const Model model = parse_model(curve_with(R"("attributes": {"t": [1, 1, 3]})"), "model.json");
  EXPECT_THROW(evaluate_attribute(model.objects[0], "u", {0.5}), InvalidInput);
  EXPECT_THROW(evaluate_attribute(model.objects[0], "t", {1.5}), InvalidInput);
  EXPECT_THROW(evaluate_attribute(model.objects[0], "t", {0.5, 0.5}), InvalidInput);
  ModelObject wrong = model.objects[0];
  wrong.attributes["t"].push_back(1.0);
  EXPECT_THROW(model_to_json(Model{{wrong}, nullptr}), InvalidInput);
  wrong.attributes["t"] = {1.0, NAN, 2.0};
  EXPECT_THROW(model_to_json(Model{{wrong}, nullptr}), InvalidInput);
}

}  // namespace
}  // namespace volspline
