// The simplex_spline_volume object of model files: bit-exact round trips, and every error located
// at its JSON path.
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "support/simplex_domains.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"

namespace volspline {
namespace {

using nlohmann::json;

Model simplex_model(DmsControlSharing sharing, int degree) {
  DmsSplineVolume v = test_support::cube_simplex_volume(degree, sharing);
  v.add_attribute("temperature");
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (Eigen::Index r = 0; r < v.control_vectors().rows(); ++r)
    for (Eigen::Index c = 0; c < v.control_vectors().cols(); ++c) v.control_vectors()(r, c) += u(rng) / 3;
  Model m;
  m.objects.push_back(ModelObject{"cube", false, std::move(v), json{{"source", "test"}}});
  return m;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(SimplexSplineJson, RoundTripsBitForBit) {
  for (const auto sharing : {DmsControlSharing::Shared, DmsControlSharing::PerTetrahedron}) {
    const Model model = simplex_model(sharing, 2);
    const std::string text = model_to_json(model);
    const Model read = parse_model(text, "m.json");
    ASSERT_EQ(read.objects.size(), 1u);
    ASSERT_TRUE(is_simplex_spline_volume(read.objects[0]));
    EXPECT_EQ(object_type_name(read.objects[0]), "simplex_spline_volume");
    EXPECT_EQ(read.objects[0].name, "cube");
    const auto& a = std::get<DmsSplineVolume>(model.objects[0].spline);
    const auto& b = std::get<DmsSplineVolume>(read.objects[0].spline);
    EXPECT_EQ(b.degree(), 2);
    EXPECT_EQ(b.sharing(), sharing);
    EXPECT_EQ(b.domain().tetrahedra, a.domain().tetrahedra);
    EXPECT_EQ(b.attribute_names(), (std::vector<std::string>{"density", "temperature"}));
    ASSERT_EQ(b.knots().knots.size(), a.knots().knots.size());
    for (std::size_t i = 0; i < a.knots().knots.size(); ++i) EXPECT_EQ(a.knots().knots[i], b.knots().knots[i]);
    EXPECT_TRUE(same_bits(a.control_vectors(), b.control_vectors()));
    EXPECT_EQ(model_to_json(read), text);
  }
}

// The message and location of the error parse_model gives for the model with one change.
std::string simplex_json_error_of(const std::function<void(json&)>& change) {
  json doc = json::parse(model_to_json(simplex_model(DmsControlSharing::Shared, 2)));
  change(doc["objects"][0]);
  try {
    parse_model(doc.dump(), "m.json");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SimplexSplineJson, ErrorsNameTheJsonPath) {
  EXPECT_NE(simplex_json_error_of([](json& o) { o["degree"] = 6; }).find("m.json: objects[0].degree: expected an integer from 0 to 5"), std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o.erase("knot_clouds"); }).find("objects[0]: missing key \"knot_clouds\""), std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["tetrahedra"][2][1] = 1000; }).find("objects[0].tetrahedra[2][1]: expected a point index"), std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { std::swap(o["tetrahedra"][3][0], o["tetrahedra"][3][1]); }).find("objects[0].tetrahedra[3]"),
            std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["knot_clouds"][4].erase(0); }).find("objects[0].knot_clouds[4]: expected an array of 2 sub-knots"),
            std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["control_points"].erase(0); }).find("objects[0].control_points: expected an array of"),
            std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["control_points"][3][1] = "a"; }).find("objects[0].control_points[3][1]: expected a number"),
            std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["attributes"]["density"].erase(0); }).find("objects[0].attributes.density: expected an array of"),
            std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["attributes"]["x"] = o["attributes"]["density"]; }).find("objects[0].attributes"), std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["control"] = "both"; }).find("objects[0].control: expected \"shared\""), std::string::npos);
  EXPECT_NE(simplex_json_error_of([](json& o) { o["colour"] = 1; }).find("objects[0].colour: unknown key"), std::string::npos);
  // A boundary vertex's sub-knot moved inside Ω (§3.2 wants it outside).
  EXPECT_NE(simplex_json_error_of([](json& o) { o["knot_clouds"][0][0] = json::array({0.01, 0.01, 0.01}); }).find("objects[0].tetrahedra["),
            std::string::npos);
}

}  // namespace
}  // namespace volspline
