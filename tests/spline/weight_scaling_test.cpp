// Weights far from 1 (issue 16: every weight 4.9e-324, the least subnormal, which the formats
// allow) mean what they mean mathematically: a rational spline is unchanged when all its
// homogeneous coefficients are scaled by one factor. TensorSpline brings the largest weight into
// [2^-32, 2^32] by an exact power of two (tensor_spline.cpp), so every reader and every command
// sees the same geometry as for weights near 1: checked here for the constructors, the JSON,
// G+Smo, IRIT and VTU readers, and eval, info --mass, faces, view and convert.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/core/error.h"
#include "volspline/io/gismo_xml.h"
#include "volspline/io/irit_itd.h"
#include "volspline/io/model_file.h"
#include "volspline/io/vtk_xml.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {
namespace {

// A rational quadratic x linear x linear volume with a point at infinity: weights 1, 0, 1 along u.
BSplineVolume weighted_reference_volume(double scale) {
  std::vector<double> points, weights;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const double w = i == 1 ? 0.0 : (j ? 0.75 : 1.0) * (k ? 0.5 : 1.0);
        // The weight-0 point is a direction, scaled with the weights (the homogeneous coefficient).
        const double s = i == 1 ? scale : 1.0;
        points.insert(points.end(), {s * (i == 1 ? 0.0 : i == 0 ? 1.0 : -1.0), s * (i == 1 ? 1.0 : 0.0) + j * (i != 1), s * 0.0 + k * (i != 1)});
        weights.push_back(w * scale);
      }
  return BSplineVolume({KnotVector::bezier(2), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, points, weights);
}

TEST(WeightScaling, ScaledWeightsGiveTheSameSplineBitForBit) {
  const BSplineVolume original = weighted_reference_volume(1.0);
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  for (const double scale : {0x1p-1000, 0x1p-40, 0x1p40, 0x1p1000}) {
    const BSplineVolume scaled = weighted_reference_volume(scale);
    EXPECT_EQ(scaled.weights(), original.weights()) << scale;
    EXPECT_EQ(scaled.homogeneous(), original.homogeneous()) << scale;
    const BSplineVolume homogeneous = [&] {
      std::vector<double> h = original.homogeneous();
      for (double& x : h) x *= scale;
      return BSplineVolume::from_homogeneous(original.knot_vectors(), 3, true, h);
    }();
    EXPECT_EQ(homogeneous.homogeneous(), original.homogeneous()) << scale;
    for (int i = 0; i < 20; ++i) {
      const std::array<double, 3> p{t(rng), t(rng), t(rng)};
      EXPECT_EQ(scaled.evaluate_derivatives(p, 2), original.evaluate_derivatives(p, 2));
    }
  }
  // Weights in the usual range are kept as given (round trips of ordinary files stay exact).
  const BSplineCurve c({KnotVector::bezier(2)}, 1, {0, 1, 2}, {0x1p-32, 0.5, 0x1p-33});
  EXPECT_EQ(c.weights(), (std::vector<double>{0x1p-32, 0.5, 0x1p-33}));
  // Subnormal weights: scaled up exactly.
  const BSplineCurve d({KnotVector::bezier(1)}, 1, {0, 1}, {4.9e-324, 2 * 4.9e-324});
  EXPECT_EQ(d.weights(), (std::vector<double>{0.5, 1.0}));  // the largest, 2^-1073, becomes 1
  EXPECT_DOUBLE_EQ(d.evaluate({0.5})[0], 2.0 / 3.0);
}

TEST(WeightScaling, NoWeightsAllZeroOrNegativeAndNoDirectionTooLongForTheWeights) {
  EXPECT_THROW(BSplineCurve({KnotVector::bezier(1)}, 1, {0, 1}, {0.0, 0.0}), InvalidInput);
  EXPECT_THROW(BSplineCurve({KnotVector::bezier(1)}, 1, {0, 1}, {-4.9e-324, 1.0}), InvalidInput);
  // A point at infinity whose direction overflows once the weights are brought near 1.
  try {
    BSplineCurve({KnotVector::bezier(2)}, 1, {0, 1e300, 2}, {4.9e-324, 0.0, 4.9e-324});
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "control_points[1][0]");
    EXPECT_NE(e.message().find("point at infinity"), std::string::npos);
  }
}

// The unit cube, trilinear, every weight `weight` (written as text: the number as the file has it).
std::string weighted_cube_json(const std::string& weight) {
  std::string points, weights;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        points += std::string(points.empty() ? "" : ",") + "[" + std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k) + "]";
        weights += std::string(weights.empty() ? "" : ",") + weight;
      }
  return R"({"volspline":1,"objects":[{"type":"bezier_volume","degree":[1,1,1],"control_points":[)" + points +
         R"(],"weights":[)" + weights + "]}]}";
}

std::string weighted_cube_gismo(const std::string& weight) {
  std::string w;
  for (int i = 0; i < 8; ++i) w += weight + " ";
  const std::string kv = R"(<Basis type="BSplineBasis"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>)";
  return R"(<?xml version="1.0"?><xml><Geometry type="TensorNurbs3"><Basis type="TensorNurbsBasis3"><Basis type="TensorBSplineBasis3">)" + kv +
         kv + kv + "</Basis><weights>" + w + R"(</weights></Basis><coefs geoDim="3">0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1</coefs></Geometry></xml>)";
}

std::string weighted_cube_irit(const std::string& weight) {
  // P3 points: the weight, then the coordinates multiplied by it (0 or the weight itself).
  std::string text = "[OBJECT cube\n[TRIVAR BEZIER 2 2 2 P3\n";
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        text += "[" + weight + " " + (i ? weight : "0") + " " + (j ? weight : "0") + " " + (k ? weight : "0") + "]\n";
  return text + "]\n]\n";
}

TEST(WeightScaling, EveryReaderGivesTheUnitCubeForDenormalAndHugeWeights) {
  BSplineVolume cube({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3,
                     {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1});
  for (const std::string w : {"4.9e-324", "1e-310", "1e-200", "1e300"}) {
    std::vector<Model> models;
    models.push_back(parse_model(weighted_cube_json(w), "c.json"));
    models.push_back(parse_gismo_xml(weighted_cube_gismo(w), "c.xml"));
    models.push_back(parse_irit_itd(weighted_cube_irit(w), "c.itd"));
    models.push_back(parse_vtu(vtu_text(models.front()), "c.vtu"));
    for (const Model& m : models) {
      const auto& v = std::get<BSplineVolume>(m.objects.at(0).spline);
      for (const double x : v.weights()) EXPECT_TRUE(x >= 1.0 && x < 2.0) << w << " " << x;
      for (const std::array<double, 3> p : {std::array<double, 3>{0.25, 0.5, 0.75}, {0, 0, 0}, {1, 1, 1}, {0.1, 0.9, 0.3}}) {
        const std::vector<double> a = v.evaluate_derivatives(p, 1), b = cube.evaluate_derivatives(p, 1);
        for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-14) << w << " " << i;
      }
    }
  }
}

TEST(WeightScalingCli, EveryCommandTreatsDenormalWeightsAsTheScaleInvariantTheyAre) {
  test_support::TemporaryDirectory tmp;
  const auto run = [&](const std::string& args) { return test_support::run_cli(args, tmp.path()); };
  std::ofstream(tmp.path() / "tiny.json") << weighted_cube_json("4.9e-324");
  std::ofstream(tmp.path() / "one.json") << weighted_cube_json("1");
  std::ofstream(tmp.path() / "tiny.xml") << weighted_cube_gismo("4.9e-324");
  std::ofstream(tmp.path() / "tiny.itd") << weighted_cube_irit("4.9e-324");
  const std::string one = (tmp.path() / "one.json").string();
  const auto reference = run("eval " + one + " --grid 3,3,3 --derivatives");
  ASSERT_EQ(reference.code, 0) << reference.err;
  for (const char* name : {"tiny.json", "tiny.xml", "tiny.itd"}) {
    const std::string f = (tmp.path() / name).string();
    const auto e = run("eval " + f + " --grid 3,3,3 --derivatives");
    EXPECT_EQ(e.code, 0) << name << e.err;
    EXPECT_EQ(e.out, reference.out) << name;
    const auto info = run("info --mass --json " + f);
    ASSERT_EQ(info.code, 0) << name << info.err;
    EXPECT_NEAR(nlohmann::json::parse(info.out)["objects"][0]["volume"].get<double>(), 1.0, 1e-14) << name;
    EXPECT_EQ(run("faces " + f + " -o " + (tmp.path() / "f.ply").string()).code, 0) << name;
    EXPECT_EQ(run("view " + f + " -o " + (tmp.path() / "v.png").string() + " --resolution 4").code, 0) << name;
    const std::string converted = (tmp.path() / (std::string(name) + ".json")).string();
    ASSERT_EQ(run("convert " + f + " -o " + converted).code, 0) << name;
    EXPECT_EQ(run("eval " + converted + " --grid 3,3,3 --derivatives").out, reference.out) << name;
  }
}

}  // namespace
}  // namespace volspline
