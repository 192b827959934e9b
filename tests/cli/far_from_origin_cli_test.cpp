// Far from the origin through the command line (issue 16): a solid at offsets 1e6, 1e12, 1e15 and
// -1e15 gives the same derivatives (`eval --derivatives`), volume, inertia (`info --mass`),
// Jacobian bounds (`jacobian`) and Jacobian colouring (`view --color jacobian`) as at 0, and
// positions (and the centroid) moved by the offset. The control points are dyadic, so the moved
// file holds exactly the moved solid. The mechanism and its library tests:
// tests/spline/local_origin_test.cpp.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/primitives.h"
#include "volspline/io/model_formats.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {
namespace {

// A box [0,1]x[0,2]x[0,1] of degree (2, 2, 1) with a knot at u = 0.5, moved by `offset` (all of its control
// points are multiples of 1/8, so the move is exact at every offset used), rational with dyadic
// weights when asked.
Model dyadic_solid(double offset, bool rational) {
  BSplineVolume v = box(Eigen::Vector3d(1, 2, 1), Eigen::Vector3d(0.5, 1, 0.5));
  v = elevate_degree(elevate_degree(v, 0, 1), 1, 1);
  v = insert_knot(v, 0, 0.5);
  std::vector<double> points = v.points(), weights;
  for (double& x : points) x += offset;
  if (rational)
    for (int i = 0; i < v.num_control_points_total(); ++i) weights.push_back(i % 3 == 1 ? 0.75 : 1.0);
  Model model;
  model.objects.push_back({"solid", false, BSplineVolume(v.knot_vectors(), 3, points, weights), nullptr});
  return model;
}

std::vector<double> numbers_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> values;
  for (double x; in >> x;) values.push_back(x);
  return values;
}

TEST(FarFromOriginCli, EveryCommandGivesTheAnswersOfTheSolidAtZero) {
  test_support::TemporaryDirectory dir;
  for (const bool rational : {false, true}) {
    const auto at_zero = dir.path() / "zero.json";
    write_model_file(dyadic_solid(0, rational), at_zero);
    const auto run = [&](const std::string& args) {
      const auto r = test_support::run_cli(args, dir.path());
      EXPECT_EQ(r.code, 0) << args << ": " << r.err;
      return r.out;
    };
    const std::string points = " --at 0.3,0.4,0.5 --at 0.75,0.125,1 --at 0,1,0.9";
    const std::vector<double> eval0 = numbers_of(run("eval " + at_zero.string() + " --derivatives" + points));
    const nlohmann::json mass0 = nlohmann::json::parse(run("info --mass --json " + at_zero.string()))["objects"][0];
    const nlohmann::json jacobian0 = nlohmann::json::parse(run("jacobian --json " + at_zero.string()))["objects"][0];
    const std::string view0 = run("view " + at_zero.string() + " -o " + (dir.path() / "v0.png").string() + " --size 160,120 --color jacobian");
    for (const double offset : {1e6, 1e12, 1e15, -1e15}) {
      const auto moved = dir.path() / "moved.json";
      write_model_file(dyadic_solid(offset, rational), moved);
      const double ulp = std::nextafter(std::abs(offset), HUGE_VAL) - std::abs(offset);
      const std::vector<double> eval = numbers_of(run("eval " + moved.string() + " --derivatives" + points));
      ASSERT_EQ(eval.size(), eval0.size());
      for (std::size_t i = 0; i < eval.size(); ++i) {
        const bool position = i % 12 < 3;  // x y z, then the nine partials
        if (position) EXPECT_NEAR(eval[i] - offset, eval0[i], 4 * ulp) << offset << " " << i;
        else EXPECT_NEAR(eval[i], eval0[i], 1e-12) << offset << " " << i << " rational " << rational;
      }
      const nlohmann::json mass = nlohmann::json::parse(run("info --mass --json " + moved.string()))["objects"][0];
      EXPECT_NEAR(mass["volume"].get<double>(), mass0["volume"].get<double>(), 1e-12) << offset;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mass["centroid"][c].get<double>() - offset, mass0["centroid"][c].get<double>(), 4 * ulp) << offset;
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(mass["inertia"][c][d].get<double>(), mass0["inertia"][c][d].get<double>(), 1e-12) << offset;
      }
      const nlohmann::json jacobian = nlohmann::json::parse(run("jacobian --json " + moved.string()))["objects"][0];
      EXPECT_EQ(jacobian["verdict"], jacobian0["verdict"]) << offset;
      EXPECT_NEAR(jacobian["lower"].get<double>(), jacobian0["lower"].get<double>(), 1e-10) << offset;
      EXPECT_NEAR(jacobian["upper"].get<double>(), jacobian0["upper"].get<double>(), 1e-10) << offset;
      // The colour bar's range, printed on the summary line ("jacobian in [a, b]").
      const std::string view = run("view " + moved.string() + " -o " + (dir.path() / "v.png").string() + " --size 160,120 --color jacobian");
      EXPECT_EQ(view.substr(view.find("jacobian in")), view0.substr(view0.find("jacobian in"))) << offset;
    }
  }
}

}  // namespace
}  // namespace volspline
