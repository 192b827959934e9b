#include "volspline/io/model_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/test_splines.h"
#include "support/temporary_directory.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_volumes.h"

namespace volspline {
namespace {

using nlohmann::json;
using test_support::random_spline;

// ---------------------------------------------------------------------------------------------
// Helpers

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

template <int D>
void expect_identical(const TensorSpline<D>& a, const TensorSpline<D>& b) {
  ASSERT_EQ(a.dimension(), b.dimension());
  for (int d = 0; d < D; ++d) {
    EXPECT_EQ(a.knot_vector(d).degree(), b.knot_vector(d).degree());
    EXPECT_TRUE(same_bits(a.knot_vector(d).knots(), b.knot_vector(d).knots())) << "knots " << d;
  }
  EXPECT_TRUE(same_bits(a.points(), b.points()));
  EXPECT_TRUE(same_bits(a.weights(), b.weights()));
}

void expect_identical(const SweptSolid& a, const SweptSolid& b) {
  ASSERT_EQ(a.generator.size(), b.generator.size());
  for (std::size_t i = 0; i < a.generator.size(); ++i) expect_identical(a.generator[i], b.generator[i]);
  expect_identical(a.path, b.path);
  for (std::size_t k = 0; k < 3; ++k) expect_identical(a.frame[k], b.frame[k]);
  EXPECT_EQ(a.frame_name, b.frame_name);
  EXPECT_TRUE(same_bits({a.frame_fit_error}, {b.frame_fit_error}));
}

void expect_identical(const DmsSplineVolume& a, const DmsSplineVolume& b) {
  EXPECT_EQ(a.degree(), b.degree());
  EXPECT_EQ(a.sharing(), b.sharing());
  EXPECT_EQ(a.domain().tetrahedra, b.domain().tetrahedra);
  EXPECT_EQ(a.attribute_names(), b.attribute_names());
  ASSERT_EQ(a.knots().knots.size(), b.knots().knots.size());
  for (std::size_t i = 0; i < a.knots().knots.size(); ++i)
    EXPECT_TRUE(same_bits({a.knots().knots[i].x(), a.knots().knots[i].y(), a.knots().knots[i].z()},
                          {b.knots().knots[i].x(), b.knots().knots[i].y(), b.knots().knots[i].z()}));
  const Eigen::MatrixXd &ca = a.control_vectors(), &cb = b.control_vectors();
  EXPECT_TRUE(same_bits(std::vector<double>(ca.data(), ca.data() + ca.size()), std::vector<double>(cb.data(), cb.data() + cb.size())));
}

void expect_identical(const Model& a, const Model& b) {
  ASSERT_EQ(a.objects.size(), b.objects.size());
  EXPECT_EQ(a.metadata, b.metadata);
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const ModelObject& x = a.objects[i];
    const ModelObject& y = b.objects[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.metadata, y.metadata);
    EXPECT_EQ(object_type_name(x), object_type_name(y));
    ASSERT_EQ(x.spline.index(), y.spline.index());
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          expect_identical(s, std::get<S>(y.spline));
        },
        x.spline);
  }
}

/// Writes, parses and writes again: the numbers must come back bit for bit, and the second
/// text must equal the first.
Model round_trip(const Model& model) {
  const std::string text = model_to_json(model);
  Model back = parse_model(text, "round-trip.json");
  expect_identical(model, back);
  EXPECT_EQ(model_to_json(back), text);
  return back;
}

/// A random finite double from random bits: any exponent, subnormals and -0.0 included.
double random_finite(std::mt19937_64& rng) {
  while (true) {
    const double x = std::bit_cast<double>(rng());
    if (std::isfinite(x)) return x;
  }
}

/// Parses `text` as "model.json" and returns the InvalidInput's what(); fails if it parses.
std::string model_error_of(const std::string& text) {
  try {
    parse_model(text, "model.json");
  } catch (const InvalidInput& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not InvalidInput: " << e.what();
    return {};
  }
  ADD_FAILURE() << "parsed: " << text;
  return {};
}

/// A valid model with a rational B-spline curve and a trilinear volume, as JSON to mutate.
json valid_document() {
  return json::parse(R"({
    "volspline": 1,
    "objects": [
      { "name": "curve", "type": "bspline_curve", "degree": [2],
        "knots": [[0, 0, 0, 0.5, 1, 1, 1]],
        "control_points": [[0, 0], [1, 1], [2, 0], [3, 1]],
        "weights": [1, 0.5, 2, 1] },
      { "type": "bspline_volume", "degree": [1, 1, 1],
        "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]],
        "control_points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]] }
    ]
  })");
}

/// The error of valid_document() after `change`; checks the "model.json: PATH: " prefix.
template <typename Change>
std::string error_after(Change change, const std::string& path) {
  json doc = valid_document();
  change(doc);
  const std::string what = model_error_of(doc.dump());
  const std::string prefix = path.empty() ? "model.json: " : "model.json: " + path + ": ";
  EXPECT_EQ(what.rfind(prefix, 0), 0u) << "expected the prefix '" << prefix << "' in: " << what;
  return what;
}

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

// ---------------------------------------------------------------------------------------------
// Round trips

TEST(ModelFile, ParsesTheReferenceDocument) {
  const Model model = parse_model(valid_document().dump(), "model.json");
  ASSERT_EQ(model.objects.size(), 2u);
  EXPECT_EQ(model.objects[0].name, "curve");
  EXPECT_EQ(object_type_name(model.objects[0]), "bspline_curve");
  EXPECT_EQ(object_type_name(model.objects[1]), "bspline_volume");
  EXPECT_TRUE(model.objects[0].metadata.is_null());
  EXPECT_TRUE(model.metadata.is_null());
  const auto& curve = std::get<TensorSpline<1>>(model.objects[0].spline);
  EXPECT_EQ(curve.dimension(), 2);
  EXPECT_TRUE(curve.is_rational());
  EXPECT_EQ(curve.weights()[2], 2.0);
  const auto& volume = std::get<TensorSpline<3>>(model.objects[1].spline);
  EXPECT_FALSE(volume.is_rational());
  const auto p = volume.evaluate({0.25, 0.5, 0.75});
  EXPECT_DOUBLE_EQ(p[0], 0.25);
  EXPECT_DOUBLE_EQ(p[1], 0.5);
  EXPECT_DOUBLE_EQ(p[2], 0.75);
}

TEST(ModelFile, RoundTripRandomSplinesBitExact) {
  std::mt19937 rng(20240611);
  Model model;
  for (int trial = 0; trial < 4; ++trial) {
    const bool clamped = trial % 2 == 0;
    model.objects.push_back({"volume " + std::to_string(trial), false,
                             random_spline<3>(rng, {3, 2, 1 + trial % 3}, 3, 3, false, clamped), nullptr});
    model.objects.push_back({"", false, random_spline<3>(rng, {2, 3, 2}, 2, 3, true, clamped, 2, true),
                             json{{"index", trial}, {"tags", {"rational", "weight 0"}}}});
    model.objects.push_back({"surface", false, random_spline<2>(rng, {2, 3}, 3, 3, trial % 2 == 1, clamped), nullptr});
    model.objects.push_back({"curve \"quoted\" \u00e9", false, random_spline<1>(rng, {3}, 4, 1 + trial, true, clamped),
                             json::object()});
  }
  model.metadata = json{{"author", "test"}, {"scale", 0.1}, {"nested", {{"list", {1, 2.5, -0.0, nullptr, true}}}}};
  // The weight-0 point survived construction and comes back as a direction with weight 0.
  const Model back = round_trip(model);
  const auto& rational = std::get<TensorSpline<3>>(back.objects[1].spline);
  EXPECT_EQ(rational.weights()[rational.weights().size() / 2], 0.0);
  EXPECT_EQ(back.objects[3].name, "curve \"quoted\" \u00e9");
  EXPECT_EQ(back.objects[1].metadata["tags"][1], "weight 0");
  EXPECT_TRUE(back.objects[3].metadata.is_object());
  EXPECT_EQ(back.metadata, model.metadata);
}

TEST(ModelFile, RoundTripSpecialDoublesBitExact) {
  std::vector<double> values = {0.1,     1.0 / 3.0,  1e-300, -0.0,    0.0,     5e-324,  -5e-324, DBL_MIN,
                                -DBL_MIN, DBL_MAX,   -DBL_MAX, 1e300,  2.0 / 3, 1e17,    123456789012345678.0,
                                -1.0,    1e-7,       0.30000000000000004, 9007199254740993.0, 1e22};
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) values.push_back(random_finite(rng));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i) values.push_back(unit(rng));
  if (values.size() % 2) values.push_back(0.5);
  // Coordinates beyond 2^200 are refused (docs/model-format.md, "Range of coordinates"): the
  // huge ones are moved into the range by a power of two, bits otherwise kept; the knots below
  // keep every finite double.
  for (double& v : values)
    if (std::abs(v) > 0x1p200) v = std::ldexp(v, -850);
  // A Bézier line segment in R^k whose two control points hold all these numbers.
  const int k = static_cast<int>(values.size() / 2);
  Model model;
  model.objects.push_back({"", true, TensorSpline<1>({KnotVector::bezier(1)}, k, values), nullptr});
  // A rational B-spline curve of degree 2 on random knots (sorted random doubles) with control
  // points and weights from the same pool, weights made positive.
  std::vector<double> knots;
  for (int i = 0; i < 300; ++i) knots.push_back(random_finite(rng));
  knots.insert(knots.end(), {0.1, 1.0 / 3.0, 1e-300, 5e-324, -0.0});
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  const std::size_t n = knots.size() - 3;
  std::vector<double> points(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> weights(n);
  for (std::size_t i = 0; i < n; ++i) weights[i] = std::abs(values[values.size() - 1 - i]);
  for (double& w : weights)
    if (w == 0.0) w = 1.0;
  weights[n / 2] = 0.0;
  model.objects.push_back({"", false, TensorSpline<1>({KnotVector(2, knots)}, 1, points, weights), nullptr});
  const std::string text = model_to_json(model);
  EXPECT_CONTAINS(text, "-0.0");
  const Model back = round_trip(model);
  EXPECT_TRUE(std::signbit(std::get<TensorSpline<1>>(back.objects[0].spline).points()[3]));
}

TEST(ModelFile, BezierTypesAreWrittenOnlyForUnitSingleSpans) {
  ModelObject object{"", true, TensorSpline<2>({KnotVector::bezier(2), KnotVector::bezier(1)}, 3, std::vector<double>(18, 1.0)),
                     nullptr};
  EXPECT_EQ(object_type_name(object), "bezier_surface");
  Model model{{object}, nullptr};
  const std::string text = model_to_json(model);
  EXPECT_CONTAINS(text, "\"type\": \"bezier_surface\"");
  EXPECT_EQ(text.find("knots"), std::string::npos);
  const Model back = round_trip(model);
  EXPECT_TRUE(back.objects[0].bezier);

  object.bezier = false;
  EXPECT_EQ(object_type_name(object), "bspline_surface");
  // bezier = true but the domain is not [0,1]: written with its knots.
  ModelObject shifted{"", true, TensorSpline<1>({KnotVector::bezier(3, 0.0, 2.0)}, 1, {1, 2, 3, 4}), nullptr};
  EXPECT_EQ(object_type_name(shifted), "bspline_curve");
  ModelObject split{"", true, TensorSpline<1>({KnotVector(1, {0, 0, 0.5, 1, 1})}, 1, {1, 2, 3}), nullptr};
  EXPECT_EQ(object_type_name(split), "bspline_curve");
  round_trip(Model{{shifted, split}, nullptr});

  const Model read = parse_model(R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [1, 1, 2],
      "control_points": [[0],[1],[2],[3],[4],[5],[6],[7],[8],[9],[10],[11]]}]})",
                                 "b.json");
  const auto& volume = std::get<TensorSpline<3>>(read.objects[0].spline);
  EXPECT_EQ(volume.knot_vector(2).knots(), (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(object_type_name(read.objects[0]), "bezier_volume");
}

TEST(ModelFile, WriteAndReadFile) {
  test_support::TemporaryDirectory dir;
  std::mt19937 rng(3);
  Model model{{{"v", false, random_spline<3>(rng, {2, 2, 2}, 2, 3, true), json{{"k", "v"}}}}, json{{"top", 1}}};
  write_model(model, dir / "m.json");
  EXPECT_EQ(dir.entries(), 1u);
  expect_identical(model, read_model(dir / "m.json"));
  // One control point per line.
  const std::string text = read_file(dir / "m.json");
  EXPECT_CONTAINS(text, "\"control_points\": [\n");
}

TEST(ModelFile, WriteIntoMissingDirectoryThrowsIoErrorAndLeavesNothing) {
  test_support::TemporaryDirectory dir;
  const Model model = parse_model(valid_document().dump(), "model.json");
  EXPECT_THROW(write_model(model, dir / "missing" / "m.json"), IoError);
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(ModelFile, ReadMissingFileThrowsIoError) {
  test_support::TemporaryDirectory dir;
  try {
    read_model(dir / "absent.json");
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_CONTAINS(e.what(), "absent.json");
  }
}

TEST(ModelFile, ErrorsNameTheFileGivenToReadModel) {
  test_support::TemporaryDirectory dir;
  write_file_atomically(dir / "bad.json", "{\"volspline\": 1, \"objects\": []}");
  try {
    read_model(dir / "bad.json");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind((dir / "bad.json").string() + ": objects: ", 0), 0u) << e.what();
  }
}

TEST(ModelFile, WritingAnInvalidModelThrows) {
  EXPECT_THROW(model_to_json(Model{}), InvalidInput);
  Model model = parse_model(valid_document().dump(), "model.json");
  model.metadata = json::array({1, 2});
  EXPECT_THROW(model_to_json(model), InvalidInput);
  model.metadata = nullptr;
  model.objects[0].name = "bad \xff utf-8";
  EXPECT_THROW(model_to_json(model), InvalidInput);
}

// ---------------------------------------------------------------------------------------------
// Errors: file name, exact JSON path, what was expected and what was found.

TEST(ModelFileErrors, InvalidJsonGivesLineAndColumn) {
  const std::string what = model_error_of("{\n  \"volspline\": 1,\n  \"objects\": [}\n");
  EXPECT_EQ(what.rfind("model.json: line 3, column 15: invalid JSON: ", 0), 0u) << what;
  EXPECT_CONTAINS(model_error_of(""), "model.json: line 1, column 1: invalid JSON");
  EXPECT_CONTAINS(model_error_of("{\"volspline\": 1} x"), "model.json: line 1, column 18: invalid JSON");
  EXPECT_CONTAINS(model_error_of("{\"volspline\": 1,\n\n \"objects\": tru}"), "model.json: line 3, column 16: invalid JSON");
  EXPECT_CONTAINS(model_error_of("{\"a\": \"\xff\"}"), "model.json: line 1, column 8: invalid JSON");
  EXPECT_CONTAINS(model_error_of("// comment\n{}"), "model.json: line 1, column 1: invalid JSON");
  EXPECT_CONTAINS(model_error_of("[1, 2,]"), "line 1, column 7");
}

TEST(ModelFileErrors, TopLevel) {
  EXPECT_CONTAINS(model_error_of("[1, 2]"), "model.json: expected a JSON object with the keys \"volspline\" and \"objects\", got an array of 2 elements");
  error_after([](json& d) { d.erase("volspline"); }, "");
  EXPECT_CONTAINS(error_after([](json& d) { d.erase("volspline"); }, ""), "missing key \"volspline\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["volspline"] = 2; }, "volspline"),
                  "unsupported format version 2: this reader supports version 1");
  EXPECT_CONTAINS(error_after([](json& d) { d["volspline"] = "1"; }, "volspline"), "got the string \"1\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["volspline"] = 1.0; }, "volspline"), "as an integer");
  EXPECT_CONTAINS(error_after([](json& d) { d["volspline"] = -1; }, "volspline"), "unsupported format version -1");
  EXPECT_CONTAINS(error_after([](json& d) { d.erase("objects"); }, ""), "missing key \"objects\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"] = json::array(); }, "objects"),
                  "expected a nonempty array of objects (curves, surfaces and volumes), got an empty array");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"] = json::object(); }, "objects"), "got an empty object");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1] = 5; }, "objects[1]"), "expected an object");
  EXPECT_CONTAINS(error_after([](json& d) { d["metadata"] = "text"; }, "metadata"), "expected a JSON object, got the string");
}

TEST(ModelFileErrors, UnknownKeysAreRejectedExceptUnderMetadata) {
  EXPECT_CONTAINS(error_after([](json& d) { d["colour"] = "red"; }, "colour"), "unknown key \"colour\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["Degree"] = 1; }, "objects[1].Degree"), "unknown key \"Degree\"");
  error_after([](json& d) { d["objects"][0]["my key"] = 1; }, "objects[0][\"my key\"]");
  // Anything goes under metadata, at both levels.
  json doc = valid_document();
  doc["metadata"] = {{"colour", "red"}, {"deep", {{"a", {1, {{"b", nullptr}}}}}}};
  doc["objects"][0]["metadata"] = {{"degree", "not checked"}, {"knots", json::array()}};
  const Model model = parse_model(doc.dump(), "model.json");
  EXPECT_EQ(model.metadata["colour"], "red");
  EXPECT_EQ(model.objects[0].metadata["degree"], "not checked");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["metadata"] = json::array(); }, "objects[0].metadata"),
                  "expected a JSON object");
}

TEST(ModelFileErrors, Types) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0].erase("type"); }, "objects[0]"), "missing key \"type\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["type"] = "nurbs"; }, "objects[0].type"),
                  "expected one of bspline_curve, bspline_surface, bspline_volume, bezier_curve, bezier_surface, "
                  "bezier_volume, got the string \"nurbs\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["type"] = 3; }, "objects[0].type"), "got 3");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["name"] = 3; }, "objects[0].name"), "expected a string, got 3");
  // A Bézier type must not have knots.
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["type"] = "bezier_volume"; }, "objects[1].knots"),
                  "a bezier_volume has no \"knots\"");
}

TEST(ModelFileErrors, Degrees) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1].erase("degree"); }, "objects[1]"), "missing key \"degree\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"] = {1, 1}; }, "objects[1].degree"),
                  "expected an array of 3 integers (one degree per direction of a bspline_volume), got an array of 2 elements");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["degree"] = 2; }, "objects[0].degree"),
                  "expected an array of 1 integer (the degree of a bspline_curve), got 2");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][0] = 0; }, "objects[1].degree[0]"),
                  "expected a degree of at least 1, got 0");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][2] = -3; }, "objects[1].degree[2]"), "got -3");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = 1.5; }, "objects[1].degree[1]"),
                  "expected an integer degree, got 1.5");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = "1"; }, "objects[1].degree[1]"), "got the string");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = 10000000000000ull; }, "objects[1].degree[1]"),
                  "expected a degree of at most 64 (the limit of model files), got 10000000000000");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = 65; }, "objects[1].degree[1]"), "at most 64");
}

TEST(ModelFileErrors, HugeDegreesAndCountsAllocateNothing) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = 1000000000; }, "objects[1].degree[1]"),
                  "expected a degree of at most 64");
  // The degree is checked against the knot array before anything is sized by it.
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["degree"][1] = 64; }, "objects[1].knots[1]"),
                  "a knot vector of degree 64 needs at least 130 knots, got 4");
  // Bézier degrees are checked against the number of control points before knots are made.
  EXPECT_CONTAINS(model_error_of(R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [64, 64, 64],
                               "control_points": [[0], [1]]}]})"),
                  "model.json: objects[0].control_points: expected 274625 control points (65 x 65 x 65 from the degrees), got 2");
  // Control-point grids beyond any int are reported, not multiplied out.
  json knots = json::array();
  for (int i = 0; i < 2000; ++i) knots.push_back(i);
  EXPECT_CONTAINS(error_after([&](json& d) { d["objects"][1]["knots"] = {knots, knots, knots}; }, "objects[1].control_points"),
                  "expected 1998 x 1998 x 1998 control points (from the degrees and knots), got 8");
}

TEST(ModelFile, DegreesAboveTheLimitAreNotWritten) {
  ModelObject object{"", true, TensorSpline<1>({KnotVector::bezier(kMaxModelDegree + 1)}, 1,
                                               std::vector<double>(static_cast<std::size_t>(kMaxModelDegree + 2), 1.0)),
                     nullptr};
  try {
    model_to_json(Model{{object}, nullptr});
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "objects[0].degree[0]");
  }
  // The largest allowed degree round-trips.
  object.spline = TensorSpline<1>({KnotVector::bezier(kMaxModelDegree)}, 2,
                                  std::vector<double>(static_cast<std::size_t>(2 * (kMaxModelDegree + 1)), 0.5),
                                  std::vector<double>(static_cast<std::size_t>(kMaxModelDegree + 1), 1.0));
  round_trip(Model{{object}, nullptr});
}

TEST(ModelFileErrors, Knots) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1].erase("knots"); }, "objects[1]"), "missing key \"knots\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["knots"] = {0, 0, 0, 1, 1, 1}; }, "objects[0].knots"),
                  "expected an array of 1 knot vector (an array of numbers), got an array of 6 elements");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["knots"] = {0}; }, "objects[0].knots[0]"),
                  "expected a knot vector (an array of numbers), got 0");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"] = "uniform"; }, "objects[1].knots"),
                  "expected an array of 3 knot vectors (arrays of numbers), got the string \"uniform\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"].erase(2); }, "objects[1].knots"), "got an array of 2 elements");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["knots"][0] = {0, 0, 0, 0.5, 0.2, 1, 1, 1}; }, "objects[0].knots[0][4]"),
                  "knots must not decrease");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"][1] = {0, 0, 0.5, 0.2, 1, 1}; }, "objects[1].knots[1][3]"),
                  "knots must not decrease");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"][2][1] = nullptr; }, "objects[1].knots[2][1]"),
                  "expected a number, got null");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"][2] = {0, 1, 1}; }, "objects[1].knots[2]"),
                  "needs at least 4 knots, got 3");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"][0] = {0, 0, 0, 1}; }, "objects[1].knots[0][2]"),
                  "multiplicity");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["knots"][0] = {0, 1, 1, 2}; }, "objects[1].knots[0]"), "is empty");
}

TEST(ModelFileErrors, ControlPoints) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1].erase("control_points"); }, "objects[1]"),
                  "missing key \"control_points\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"].erase(7); }, "objects[1].control_points"),
                  "expected 8 control points (2 x 2 x 2 from the degrees and knots), got 7");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"] = json::array(); }, "objects[1].control_points"),
                  "got 0");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"] = {{0, 0, 0}}; }, "objects[1].control_points"),
                  "expected 8 control points");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"] = 8; }, "objects[1].control_points"),
                  "expected an array of control points (arrays of numbers), got 8");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"][3] = {1, 1}; }, "objects[1].control_points[3]"),
                  "expected a control point with 3 coordinates (as many as control_points[0]), got an array of 2 elements");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"][0] = json::array(); }, "objects[1].control_points[0]"),
                  "expected a control point (an array of at least one number), got an empty array");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][1]["control_points"][2][1] = "x"; }, "objects[1].control_points[2][1]"),
                  "expected a number, got the string \"x\"");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["control_points"][1] = 1; }, "objects[0].control_points[1]"),
                  "got 1");
}

TEST(ModelFileErrors, NumbersBeyondDoubleAreNotFinite) {
  std::string text = valid_document().dump();
  const auto replace = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  EXPECT_CONTAINS(model_error_of(replace("[3,1]", "[3,1e999]")),
                  "model.json: objects[0].control_points[3][1]: expected a finite number, got 1e999");
  EXPECT_CONTAINS(model_error_of(replace("[0,0,0,0.5", "[0,0,-1E+400,0.5")), "model.json: objects[0].knots[0][2]: expected a finite number, got -1E+400");
  EXPECT_CONTAINS(model_error_of(replace("[1,0.5,2", "[1,1e309,2")), "model.json: objects[0].weights[1]: expected a finite number");
  // In metadata too: the reader never holds an infinity.
  EXPECT_CONTAINS(model_error_of(replace("\"volspline\":1", "\"metadata\": {\"x\": [0, 2e400]}, \"volspline\":1")),
                  "model.json: metadata.x[1]: expected a finite number");
  // Underflow is not an error: 1e-400 reads as 0.
  const Model model = parse_model(replace("[3,1]", "[3,1e-400]"), "model.json");
  EXPECT_EQ(std::get<TensorSpline<1>>(model.objects[0].spline).points()[7], 0.0);
}

TEST(ModelFileErrors, Weights) {
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"][2] = -1; }, "objects[0].weights[2]"),
                  "expected a weight >= 0, got -1");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"].erase(3); }, "objects[0].weights"),
                  "expected an array of 4 weights (one per control point), got an array of 3 elements");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"] = json::array(); }, "objects[0].weights"),
                  "got an empty array");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"] = nullptr; }, "objects[0].weights"), "got null");
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"][1] = true; }, "objects[0].weights[1]"),
                  "expected a number, got true");
  // All weights influencing the start are 0: the rational curve is undefined there.
  EXPECT_CONTAINS(error_after([](json& d) { d["objects"][0]["weights"] = {0, 0, 0, 1}; }, "objects[0].weights"), "are 0");
  // A weight-0 point whose neighbours carry weight is fine.
  json doc = valid_document();
  doc["objects"][0]["weights"] = {1, 0, 1, 1};
  EXPECT_NO_THROW(parse_model(doc.dump(), "model.json"));
}

TEST(ModelFileErrors, DuplicateKeys) {
  EXPECT_CONTAINS(model_error_of(R"({"volspline": 1, "volspline": 1, "objects": []})"),
                  "model.json: volspline: duplicate key \"volspline\"");
  EXPECT_CONTAINS(model_error_of(R"({"volspline": 1, "objects": [{"type": "bezier_curve", "degree": [1], "degree": [2],
                               "control_points": [[0], [1]]}]})"),
                  "model.json: objects[0].degree: duplicate key \"degree\"");
  EXPECT_CONTAINS(model_error_of(R"({"volspline": 1, "metadata": {"a": [{"b": 1, "b": 2}]}, "objects": []})"),
                  "model.json: metadata.a[0].b: duplicate key \"b\"");
}

TEST(ModelFileErrors, DeepNestingIsRejectedWithoutRecursion) {
  std::string deep = R"({"volspline": 1, "metadata": {"x": )" + std::string(100000, '[') + std::string(100000, ']') +
                     R"(}, "objects": []})";
  EXPECT_CONTAINS(model_error_of(deep), "model.json: metadata.x[0][0]");
  EXPECT_CONTAINS(model_error_of(deep), "levels of nested arrays and objects");
  EXPECT_CONTAINS(model_error_of(std::string(1000000, '[')), "model.json: [0][0][0]");
  // 60 levels of metadata are fine and survive a round trip.
  std::string ok = R"({"volspline": 1, "metadata": {"x": )" + std::string(60, '[') + std::string(60, ']') +
                   R"(}, "objects": [{"type": "bezier_curve", "degree": [1], "control_points": [[0], [1]]}]})";
  round_trip(parse_model(ok, "model.json"));
}

TEST(ModelFileErrors, ErrorsCarryWhereAndMessage) {
  json doc = valid_document();
  doc["objects"][1]["knots"][1] = {0, 0, 0.5, 0.2, 1, 1};
  try {
    parse_model(doc.dump(), "model.json");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "model.json: objects[1].knots[1][3]");
    EXPECT_EQ(e.message().rfind("knots must not decrease: 0.2", 0), 0u) << e.message();
    EXPECT_EQ(std::string(e.what()), e.where() + ": " + e.message());
  }
}

// ---------------------------------------------------------------------------------------------
// The example models shipped in examples/.

TEST(ModelFileExamples, EveryExampleParsesAndEvaluates) {
  const std::filesystem::path dir = std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    const Model model = read_model(entry.path());
    ASSERT_FALSE(model.objects.empty());
    for (const ModelObject& object : model.objects) {
      const auto expect_finite_middle = [](const auto& s) {
        typename std::decay_t<decltype(s)>::Parameter t{};
        for (std::size_t d = 0; d < t.size(); ++d) t[d] = 0.5 * (s.domain_min(static_cast<int>(d)) + s.domain_max(static_cast<int>(d)));
        const Eigen::VectorXd p = s.evaluate(t);
        for (Eigen::Index c = 0; c < p.size(); ++c) EXPECT_TRUE(std::isfinite(p[c]));
      };
      if (const auto* swept = std::get_if<SweptSolid>(&object.spline)) {
        for (const auto& patch : swept_patches(*swept)) expect_finite_middle(patch);
      } else if (const auto* simplex = std::get_if<DmsSplineVolume>(&object.spline)) {
        // Read back, it was validated exactly (domain and knot clouds, docs/model-format.md).
        EXPECT_GT(simplex->control_vector_count(), 0);
        EXPECT_TRUE(simplex->control_vectors().allFinite());
      } else {
        visit_spline(object, "test", "", expect_finite_middle);
      }
    }
    // Examples are written in the writer's own layout.
    EXPECT_EQ(model_to_json(model), read_file(entry.path()));
  }
  EXPECT_GE(count, 3);
}

TEST(ModelFileExamples, HalfCircleIsTheUpperUnitSemicircle) {
  const Model model = read_model(std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / "half-circle-curve.json");
  const auto& curve = std::get<TensorSpline<1>>(model.objects.at(0).spline);
  EXPECT_EQ(object_type_name(model.objects[0]), "bezier_curve");
  EXPECT_EQ(curve.weights()[1], 0.0);
  for (int i = 0; i <= 20; ++i) {
    const Eigen::VectorXd p = curve.evaluate({i / 20.0});
    EXPECT_NEAR(p.head<2>().norm(), 1.0, 1e-14);
    EXPECT_GE(p[1], 0.0);
    EXPECT_EQ(p[2], 0.0);
  }
  const Eigen::VectorXd top = curve.evaluate({0.5});
  EXPECT_NEAR(top[0], 0.0, 1e-15);
  EXPECT_NEAR(top[1], 1.0, 1e-15);
}

TEST(ModelFileExamples, QuarterCylinderShellIsExact) {
  const Model model = read_model(std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / "quarter-cylinder-shell.json");
  const auto& shell = std::get<TensorSpline<3>>(model.objects.at(0).spline);
  EXPECT_EQ(shell.degrees(), (TensorSpline<3>::Index{2, 1, 1}));
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 2; ++k) {
        const Eigen::VectorXd p = shell.evaluate({i / 8.0, j / 4.0, k / 2.0});
        EXPECT_NEAR(std::hypot(p[0], p[1]), 1.0 + j / 4.0, 1e-14);
        EXPECT_NEAR(p[2], k / 2.0, 1e-15);
        EXPECT_GE(p[0], -1e-15);
        EXPECT_GE(p[1], -1e-15);
      }
}

TEST(ModelFileExamples, BentVolumeIsATricubicFiveByFiveByFour) {
  const Model model = read_model(std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / "bent-bspline-volume.json");
  const auto& volume = std::get<TensorSpline<3>>(model.objects.at(0).spline);
  EXPECT_EQ(volume.degrees(), (TensorSpline<3>::Index{3, 3, 3}));
  EXPECT_EQ(volume.num_control_points(), (TensorSpline<3>::Index{5, 5, 4}));
  EXPECT_FALSE(volume.is_rational());
  EXPECT_GT(volume.knot_vector(0).num_spans(), 1);
  // Bent upward: the far end lies higher than the middle.
  EXPECT_GT(volume.evaluate({1.0, 0.5, 0.0})[2], volume.evaluate({0.5, 0.5, 0.0})[2] + 0.5);
}

// ---------------------------------------------------------------------------------------------
// Hypervolumes and swept solids.

namespace swept {

using volspline::test_support::random_spline;

json line_curve() {
  return json::parse(R"({"type": "bezier_curve", "degree": [1], "control_points": [[0, 0, 0], [2, 0, 0]]})");
}
json cube_volume() {
  return json::parse(R"({"type": "bezier_volume", "degree": [1, 1, 1],
    "control_points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]]})");
}
json swept_document(json frame) {
  json object = {{"name", "swept"}, {"type", "swept_solid"}, {"generator", json::array({cube_volume(), cube_volume()})},
                 {"path", line_curve()}};
  if (!frame.is_null()) object["frame"] = std::move(frame);
  return {{"volspline", 1}, {"objects", json::array({object, valid_document()["objects"][1]})}};
}

std::string error_in(const json& doc, const std::string& path) {
  const std::string what = model_error_of(doc.dump());
  EXPECT_EQ(what.rfind("model.json: " + path + ": ", 0), 0u) << what;
  return what;
}

}  // namespace swept

TEST(ModelFileSweptSolids, HypervolumesRoundTripBitExact) {
  std::mt19937 rng(21);
  Model model;
  model.objects.push_back({"polynomial", false, random_spline<4>(rng, {2, 1, 1, 3}, 2, 3, false), nullptr});
  model.objects.push_back({"rational", false, random_spline<4>(rng, {1, 2, 1, 2}, 1, 3, true, false), nullptr});
  model.objects[1].attributes["temperature"].assign(static_cast<std::size_t>(std::get<BSplineHypervolume>(model.objects[1].spline).num_control_points_total()), 1.5);
  const Model back = round_trip(model);
  EXPECT_EQ(object_type_name(back.objects[0]), "bspline_hypervolume");
  const auto& rational = std::get<BSplineHypervolume>(back.objects[1].spline);
  std::vector<double> t;
  for (int d = 0; d < 4; ++d) t.push_back(rational.domain_min(d));
  EXPECT_DOUBLE_EQ(evaluate_attribute(back.objects[1], "temperature", t), 1.5);
  // A Bézier hypervolume is read without knots, 2^4 control points, u fastest and t slowest.
  json points = json::array();
  for (int i = 0; i < 16; ++i) points.push_back({i & 1, (i >> 1) & 1, ((i >> 2) & 1) + (i >> 3)});
  const json doc = {{"volspline", 1}, {"objects", json::array({{{"type", "bezier_hypervolume"}, {"degree", {1, 1, 1, 1}}, {"control_points", points}}})}};
  const Model bezier = parse_model(doc.dump(), "m.json");
  EXPECT_EQ(object_type_name(bezier.objects[0]), "bezier_hypervolume");
  const auto& h = std::get<BSplineHypervolume>(bezier.objects[0].spline);
  EXPECT_DOUBLE_EQ(h.evaluate({0.5, 0.5, 0.5, 1.0})[2], 1.5);
  round_trip(bezier);
  json bad = doc;
  bad["objects"][0]["degree"] = {1, 1, 1};
  EXPECT_CONTAINS(model_error_of(bad.dump()), "objects[0].degree: expected an array of 4 integers");
}

TEST(ModelFileSweptSolids, EveryFrameKindReadsAndRoundTripsBitExact) {
  const json curves = {{"curves", json::array({swept::line_curve(), json::parse(R"({"type": "bspline_curve", "degree": [2],
      "knots": [[0, 0, 0, 1, 1, 1]], "control_points": [[0, 1, 0], [0.3, 1, 0], [0, 1, 0]], "weights": [1, 2, 1]})"),
      json::parse(R"({"type": "bezier_curve", "degree": [1], "control_points": [[0, 0, 1], [0, 0, 1]]})")})}};
  const std::vector<json> frames{json(nullptr), json("fixed"), json("rmf"), json("frenet"),
                                 json::parse(R"({"rotate": {"axis": [0, 0, 2], "degrees": -200}})"), curves};
  for (const json& frame : frames) {
    SCOPED_TRACE(frame.dump());
    json doc = swept::swept_document(frame);
    if (frame.is_object() && frame.contains("curves")) doc["objects"][0]["frame"]["curves"][0]["control_points"] = {{1, 0, 0}, {1, 0, 0}};
    if (frame == json("frenet")) doc["objects"][0]["path"] = json::parse(R"({"type": "bezier_curve", "degree": [2],
        "control_points": [[0, 0, 0], [1, 1, 0], [2, 0, 0]]})");
    const Model model = parse_model(doc.dump(), "model.json");
    ASSERT_TRUE(is_swept_solid(model.objects[0]));
    EXPECT_EQ(object_type_name(model.objects[0]), "swept_solid");
    const auto& solid = std::get<SweptSolid>(model.objects[0].spline);
    EXPECT_EQ(solid.generator.size(), 2u);
    EXPECT_EQ(solid.path.domain_min(0), 0.0);
    EXPECT_EQ(solid.path.domain_max(0), 1.0);
    round_trip(model);
  }
}

TEST(ModelFileSweptSolids, MalformedObjectsAreRefusedAtTheirJsonPath) {
  using swept::error_in;
  using swept::swept_document;
  auto with = [](auto change) {
    json doc = swept_document("fixed");
    change(doc["objects"][0]);
    return doc;
  };
  EXPECT_NE(error_in(with([](json& o) { o.erase("generator"); }), "objects[0]").find("missing key \"generator\""), std::string::npos);
  EXPECT_NE(error_in(with([](json& o) { o["generator"] = json::array(); }), "objects[0].generator").find("nonempty array"), std::string::npos);
  EXPECT_NE(error_in(with([](json& o) { o["generator"][1] = swept::line_curve(); }), "objects[0].generator[1].type").find("expected a volume"),
            std::string::npos);
  error_in(with([](json& o) { o["generator"][0]["control_points"][3] = {1, 1}; }), "objects[0].generator[0].control_points[3]");
  error_in(with([](json& o) { o["generator"][0]["metadata"] = json::object(); }), "objects[0].generator[0].metadata");
  EXPECT_NE(error_in(with([](json& o) { o.erase("path"); }), "objects[0]").find("missing key \"path\""), std::string::npos);
  EXPECT_NE(error_in(with([](json& o) { o["path"] = swept::cube_volume(); }), "objects[0].path.type").find("expected a curve"),
            std::string::npos);
  // A 2-D path and a 2-D generator patch.
  EXPECT_NE(error_in(with([](json& o) { o["path"]["control_points"] = {{0, 0}, {1, 0}}; }), "objects[0].path").find("3-dimensional"),
            std::string::npos);
  error_in(with([](json& o) {
    for (auto& p : o["generator"][1]["control_points"]) p.erase(2);
  }), "objects[0].generator[1]");
  EXPECT_NE(error_in(with([](json& o) { o["frame"] = "twisted"; }), "objects[0].frame").find("expected a frame"), std::string::npos);
  error_in(with([](json& o) { o["frame"] = json::parse(R"({"rotate": {"axis": [0, 0], "degrees": 90}})"); }), "objects[0].frame.rotate.axis");
  error_in(with([](json& o) { o["frame"] = json::parse(R"({"rotate": {"axis": [0, 0, 0], "degrees": 90}})"); }), "objects[0].frame.rotate.axis");
  error_in(with([](json& o) { o["frame"] = json::parse(R"({"rotate": {"axis": [0, 0, 1]}})"); }), "objects[0].frame.rotate");
  error_in(with([](json& o) { o["frame"] = json::parse(R"({"rotate": {"axis": [0, 0, 1], "degrees": 9, "speed": 1}})"); }),
           "objects[0].frame.rotate.speed");
  error_in(with([](json& o) { o["frame"] = json{{"curves", json::array({swept::line_curve()})}}; }), "objects[0].frame.curves");
  error_in(with([](json& o) { o["frame_name"] = "rmf"; }), "objects[0].frame_name");
  error_in(with([](json& o) { o["frame"] = json::parse(R"({"rotate": {"axis": [0, 0, 1], "degrees": 1e12}})"); }),
           "objects[0].frame.rotate.degrees");
  // A fitted frame is fitted on reading only for paths of at most 64 spans.
  const std::string long_path = error_in(with([](json& o) {
    json knots = {0, 0};
    json points = json::array();
    for (int i = 0; i <= 65; ++i) points.push_back({i, i % 2, 0});
    for (int i = 1; i < 65; ++i) knots.push_back(i);
    knots.push_back(65);
    knots.push_back(65);
    o["path"] = {{"type", "bspline_curve"}, {"degree", {1}}, {"knots", {knots}}, {"control_points", points}};
    o["frame"] = "rmf";
  }), "objects[0].frame");
  EXPECT_NE(long_path.find("at most 64 knot spans (this one has 65)"), std::string::npos) << long_path;
  error_in(with([](json& o) { o["attributes"] = json::object(); }), "objects[0].attributes");
  // Frame curves whose determinant vanishes: b = n.
  const std::string singular = error_in(with([](json& o) {
    o["frame"] = json{{"curves", json::array({swept::line_curve(), swept::line_curve(), swept::line_curve()})}};
  }), "objects[0].frame");
  EXPECT_NE(singular.find("det R(t)"), std::string::npos) << singular;
}

TEST(ModelFileSweptSolids, VolumeLoopsAndSplineVisitorsHandleSweptSolids) {
  const Model model = parse_model(swept::swept_document("fixed").dump(), "model.json");
  EXPECT_EQ(count_volumes(model), 1u);
  std::vector<std::size_t> visited;
  for_each_volume(model, "model.json", [&](std::size_t i, const ModelObject&, const BSplineVolume&) { visited.push_back(i); });
  EXPECT_EQ(visited, std::vector<std::size_t>{1});
  Model only_swept = model;
  only_swept.objects.pop_back();
  try {
    for_each_volume(only_swept, "model.json", [](std::size_t, const ModelObject&, const BSplineVolume&) {});
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(e.message().find("swept solids and hypervolumes are skipped"), std::string::npos) << e.message();
  }
  try {
    visit_classic_spline(model.objects[0], "VTK", "objects[0]", [](const auto&) {});
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "objects[0]");
    EXPECT_NE(e.message().find("not a swept_solid"), std::string::npos);
  }
  EXPECT_THROW(evaluate_attribute(model.objects[0], "x", {0.5}), InvalidInput);
}

}  // namespace
}  // namespace volspline
