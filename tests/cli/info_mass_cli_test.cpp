// volspline info MODEL --mass [--json]: volume, centroid and inertia of every volume, checked
// against analytic values (a box and the exact half cylinder shell with points at infinity).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "support/temporary_directory.h"
#include "volspline/construct/example_solids.h"
#include "support/cli_runner.h"
#include "volspline/io/model_file.h"

namespace volspline {
namespace {

constexpr double kPi = std::numbers::pi;

using Result = test_support::CliResult;
using test_support::run_cli;

/// The box [x0, x0 + a] x [y0, y0 + b] x [z0, z0 + c] as a trilinear volume.
BSplineVolume box(double x0, double y0, double z0, double a, double b, double c) {
  std::vector<double> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) p.insert(p.end(), {x0 + a * i, y0 + b * j, z0 + c * k});
  return BSplineVolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, std::move(p));
}

BSplineSurface square() {
  return BSplineSurface({KnotVector::bezier(1), KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
}

class InfoMass : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string write(const Model& m) {
    const auto p = tmp.path() / "model.json";
    write_model(m, p);
    return p.string();
  }
};

void expect_close(const nlohmann::json& got, double expected, double tolerance, const std::string& what) {
  ASSERT_TRUE(got.is_number()) << what << ": " << got.dump();
  EXPECT_NEAR(got.get<double>(), expected, tolerance) << what;
}

TEST_F(InfoMass, JsonReportsVolumeCentroidAndInertiaOfBoxAndHalfCylinderShell) {
  const double a = 2.0, b = 3.0, c = 0.5;
  const double ri = 1.0, ro = 2.0, h = 1.5;
  Model m;
  m.objects.push_back({"box", false, box(1.0, -1.0, 4.0, a, b, c), nullptr});
  m.objects.push_back({"shell", false, half_cylinder_shell(ri, ro, h), nullptr});
  m.objects.push_back({"square", false, square(), nullptr});
  const auto r = run_cli("info --mass --json " + write(m), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["objects"].size(), 3u);

  // the box: volume abc, centroid its centre, inertia (m/12) diag(b^2 + c^2, a^2 + c^2, a^2 + b^2)
  const auto& o = j["objects"][0];
  const double mb = a * b * c;
  expect_close(o["volume"], mb, 1e-14 * mb, "box volume");
  const double centre[3] = {1.0 + a / 2, -1.0 + b / 2, 4.0 + c / 2};
  for (int i = 0; i < 3; ++i) expect_close(o["centroid"][i], centre[i], 1e-14 * 5, "box centroid");
  const double diag[3] = {mb / 12 * (b * b + c * c), mb / 12 * (a * a + c * c), mb / 12 * (a * a + b * b)};
  for (int r0 = 0; r0 < 3; ++r0)
    for (int c0 = 0; c0 < 3; ++c0) expect_close(o["inertia"][r0][c0], r0 == c0 ? diag[r0] : 0.0, 1e-13 * diag[2], "box inertia");

  // the half cylinder shell (rational, with points at infinity)
  const auto& s = j["objects"][1];
  const double area = kPi / 2 * (ro * ro - ri * ri), ms = area * h;
  const double cy = 4 * (ro * ro * ro - ri * ri * ri) / (3 * kPi * (ro * ro - ri * ri));
  expect_close(s["volume"], ms, 1e-12 * ms, "shell volume");
  expect_close(s["centroid"][0], 0.0, 1e-12, "shell centroid x");
  expect_close(s["centroid"][1], cy, 1e-12 * cy, "shell centroid y");
  expect_close(s["centroid"][2], h / 2, 1e-12, "shell centroid z");
  const double x2 = h * kPi * (std::pow(ro, 4) - std::pow(ri, 4)) / 8, z2 = area * h * h * h / 3;
  const double I[3] = {x2 + z2 - ms * (cy * cy + h * h / 4), x2 + z2 - ms * h * h / 4, 2 * x2 - ms * cy * cy};
  for (int r0 = 0; r0 < 3; ++r0)
    for (int c0 = 0; c0 < 3; ++c0) expect_close(s["inertia"][r0][c0], r0 == c0 ? I[r0] : 0.0, 1e-12 * I[2], "shell inertia");
  EXPECT_TRUE(s["mass_quadrature"]["converged"].get<bool>());
  EXPECT_LE(s["mass_quadrature"]["estimated_relative_error"].get<double>(), 1e-13);

  // not a volume: no mass keys
  const auto& q = j["objects"][2];
  EXPECT_FALSE(q.contains("volume"));
  EXPECT_FALSE(q.contains("centroid"));
  EXPECT_FALSE(q.contains("inertia"));
}

TEST_F(InfoMass, WithoutMassTheKeysAreAbsent) {
  Model m;
  m.objects.push_back({"", false, box(0, 0, 0, 1, 1, 1), nullptr});
  const auto r = run_cli("info --json " + write(m), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(r.out)["objects"][0].contains("volume"));
}

TEST_F(InfoMass, TextNamesEachQuantityAndSaysWhenAnObjectHasNone) {
  Model m;
  m.objects.push_back({"", false, box(0, 0, 0, 2, 1, 1), nullptr});
  m.objects.push_back({"", false, square(), nullptr});
  const auto r = run_cli("info --mass " + write(m), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto at = r.out.find("  volume          ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(at + 18)), 2.0, 1e-14) << r.out;
  EXPECT_NE(r.out.find("  centroid        (1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inertia (about the centroid)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("only volumes in R^3 have mass properties"), std::string::npos) << r.out;
}

TEST_F(InfoMass, LeftHandedAndFoldedVolumes) {
  // mirrored box: same positive volume; folded: x(u) = 4u - 3u^2 counts [1, 4/3] twice
  std::vector<double> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (double x : {0.0, 2.0, 1.0}) p.insert(p.end(), {x, 1.0 * j, 1.0 * k});
  Model m;
  m.objects.push_back({"", false, box(0, 0, 0, -2, 1, 1), nullptr});
  m.objects.push_back({"", false, BSplineVolume({KnotVector::bezier(2), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, p), nullptr});
  const auto path = write(m);
  const auto r = run_cli("info --mass --json " + path, tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  expect_close(j["objects"][0]["volume"], 2.0, 2e-14, "mirrored volume");
  expect_close(j["objects"][0]["mass_quadrature"]["signed_volume"], -2.0, 2e-14, "mirrored signed volume");
  expect_close(j["objects"][1]["volume"], 5.0 / 3.0, 1e-12, "folded volume");
  EXPECT_EQ(j["objects"][1]["mass_quadrature"]["folded_cells"].get<int>(), 1);
  const auto text = run_cli("info --mass " + path, tmp.path());
  EXPECT_NE(text.out.find("folds over itself"), std::string::npos) << text.out;
}

}  // namespace
}  // namespace volspline
