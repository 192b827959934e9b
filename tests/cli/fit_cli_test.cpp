// `volspline fit`: volume data in, a simplex spline volume out that `eval`, `xray`, `view` and
// `convert` open; the statistics file has the paper's Table 1 columns; bad input exits with 2,
// naming the file, with nothing written.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/model_file.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

class FitCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }
  test_support::CliResult run(const std::string& args) const { return test_support::run_cli(args, tmp.path()); }

  void SetUp() override {
    // A linear field (reproduced exactly by any degree) and a second attribute, on a grid.
    std::ofstream csv(path("data.csv"));
    csv.precision(17);
    csv << "temperature,x,y,z,other\n";
    for (int k = 0; k < 8; ++k)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          const double x = i / 7.0, y = j / 7.0, z = k / 7.0;
          csv << 1 + 2 * x - y + 0.5 * z << "," << x << "," << y << "," << z << "," << x * y << "\n";
        }
  }
};

TEST_F(FitCli, FitsAndTheResultOpensInEvalXrayViewAndConvert) {
  auto r = run("fit " + path("data.csv") + " -o " + path("f.json") + " --degree 2 --attributes temperature --primary-knots 40 --stats " +
               path("s.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("temperature"), std::string::npos) << r.out;
  const Model m = read_model(path("f.json"));
  const auto& v = std::get<DmsSplineVolume>(m.objects.at(0).spline);
  EXPECT_EQ(v.attribute_names(), std::vector<std::string>{"temperature"});
  std::ifstream stats_file(path("s.json"));
  const auto stats = nlohmann::json::parse(stats_file);
  for (const char* key : {"data_points", "domain_tetrahedra", "control_points", "knots", "geometric_error", "field_errors", "seconds"})
    EXPECT_TRUE(stats.contains(key)) << key;
  EXPECT_EQ(stats["data_points"].get<int>(), 512);
  EXPECT_EQ(stats["control_points"].get<int>(), v.control_vector_count());
  EXPECT_EQ(stats["domain_tetrahedra"].get<std::size_t>(), v.domain().tetrahedra.size());
  EXPECT_LE(stats["field_errors"][0]["max_abs"].get<double>(), 1e-10);  // a linear field
  EXPECT_EQ(stats["field_errors"][0]["data_min"].get<double>(), 0.0);  // 1 + 2·0 − 1 + 0
  EXPECT_EQ(stats["outside_points"].get<int>(), 0);  // the grid's hull is the cube, all in Ω

  r = run("eval " + path("f.json") + " --at 0.3,0.4,0.5 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["points"][0][3].get<double>(), 1 + 0.6 - 0.4 + 0.25, 1e-10);
  r = run("convert " + path("f.json") + " -o " + path("f.vtu"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("xray " + path("f.json") + " -o " + path("x.png") + " --size 32,24");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("view " + path("f.json") + " -o " + path("v.png") + " --iso-attribute temperature:1.5 --size 48,36");
  ASSERT_EQ(r.code, 0) << r.err;

  // A generated data set.
  r = run("fit marschner-lobb:6 -o " + path("ml.json") + " --degree 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("rho"), std::string::npos) << r.out;
}

TEST_F(FitCli, SeveralAttributesGetTableOnesFieldErrorTheirMean) {
  // Table 1 gives one field error per data set: with several attributes, their mean normalised
  // mean square (what placement and refinement minimise), beside each attribute's own.
  // (--attributes as a user types it, with spaces after the comma.)
  const auto r = run("fit " + path("data.csv") + " --attributes 'temperature, other' --degree 1 --primary-knots 30 --stats " + path("s.json") +
                     " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("mean over 2 attributes"), std::string::npos) << r.out;
  std::ifstream stats_file(path("s.json"));
  const auto stats = nlohmann::json::parse(stats_file);
  ASSERT_EQ(stats["field_errors"].size(), 2u);
  const double a = stats["field_errors"][0]["normalised_mean_square"].get<double>();
  const double b = stats["field_errors"][1]["normalised_mean_square"].get<double>();
  EXPECT_GT(a + b, 0.0);  // x y is not linear, so degree 1 does not reproduce it
  EXPECT_DOUBLE_EQ(stats["field_normalised_mean_square"].get<double>(), (a + b) / 2);
}

TEST_F(FitCli, BadInputExitsWithTwoNamingTheProblem) {
  std::ofstream(path("nan.csv")) << "x,y,z,d\n0,0,0,1\n1,0,0,nan\n";
  std::ofstream(path("noz.csv")) << "x,y,d\n0,0,1\n";
  const auto expect_bad = [&](const std::string& args, const std::string& named) {
    std::filesystem::remove(path("o.json"));
    const auto r = run(args + " -o " + path("o.json"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("o.json"))) << args;
  };
  expect_bad("fit " + path("nan.csv"), "nan.csv: line 3: column 'd'");
  expect_bad("fit " + path("noz.csv"), "no column z");
  expect_bad("fit " + path("absent.csv"), "absent.csv");
  expect_bad("fit " + path("data.csv") + " --attributes pressure", "--attributes");
  expect_bad("fit " + path("data.csv") + " --degree 9", "--degree");
  expect_bad("fit " + path("data.csv") + " --degree 3 --primary-knots 200", "too few");
  expect_bad("fit marschner-lobb:x", "marschner-lobb:N");
  expect_bad("fit " + path("data.csv") + " --knots moving", "--knots");
  expect_bad("fit " + path("data.csv") + " --knots place --placement-rounds 11", "--placement-rounds");
  expect_bad("fit " + path("data.csv") + " --knots place --spacing-ratio 0.5", "--spacing-ratio");
  expect_bad("fit " + path("data.csv") + " --knots optimise --knot-sweeps 0", "--knot-sweeps");
  expect_bad("fit " + path("data.csv") + " --error -1", "--error");
  expect_bad("fit " + path("data.csv") + " --max-tetrahedra -5", "--max-tetrahedra");
  expect_bad("fit " + path("data.csv") + " --fairing -0.1", "--fairing");
  expect_bad("fit " + path("data.csv") + " --fairing inf", "--fairing");
  expect_bad("fit " + path("data.csv") + " --jump -1", "--jump");
  expect_bad("fit " + path("data.csv") + " --primary-knots-layout grid", "--primary-knots-layout");
  expect_bad("fit two-material:9:0.37 --jump 2", "--jump: the jump 2.000000 splits the data into 1 regions");
  expect_bad("fit two-material:9:x", "two-material:N:TILT");
}

TEST_F(FitCli, AJumpFittedWithAlignedKnotsBeatsTheTensorProductSideBySide) {
  // docs/fitting.md, "Sharp features": the two-material field on a tilted plane, fitted with
  // --jump and, in the same run, by the tensor product with no more coefficients. At the data the
  // piecewise linear field is reproduced; against the true field what is left is the interface's
  // position between the samples.
  const auto r = run("fit two-material:13:0.37 --jump 0.3 --baselines --stats " + path("s.json") + " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(path("s.json")));
  ASSERT_TRUE(s.contains("sharp_features"));
  EXPECT_EQ(s["sharp_features"]["region_points"].size(), 2u);
  const auto& rows = s["baselines"];
  ASSERT_EQ(rows[1]["method"], "tensor-product least squares (degree 2)");
  EXPECT_LE(rows[1]["coefficients"].get<int>(), rows[0]["coefficients"].get<int>());
  EXPECT_LT(rows[0]["data_mean_square"].get<double>(), 1e-6 * rows[1]["data_mean_square"].get<double>());
  EXPECT_LT(rows[0]["truth_mean_square"].get<double>(), 0.2 * rows[1]["truth_mean_square"].get<double>());
}

TEST_F(FitCli, RefinementAndKnotOptimisationAreReportedInTheStatistics) {
  // The linear field is fitted exactly: refinement converges at once, knot optimisation has
  // nothing above its threshold to gain, and the picture is written.
  const auto r = run("fit " + path("data.csv") + " --attributes other --error 1e-3 --max-tetrahedra 200 --knots optimise --png " +
                     path("fit.png") + " --stats " + path("s.json") + " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("fit.png")));
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(path("s.json")));
  ASSERT_TRUE(s.contains("adaptive_refinement"));
  EXPECT_EQ(s["adaptive_refinement"]["error_bound"], 1e-3);
  EXPECT_FALSE(s["adaptive_refinement"]["state"].get<std::string>().empty());
  EXPECT_LE(s["domain_tetrahedra"].get<int>(), 200);
  const auto& rounds = s["adaptive_refinement"]["rounds"];
  for (std::size_t i = 1; i < rounds.size(); ++i)
    if (!rounds[i]["undone"].get<bool>()) {
      EXPECT_LE(rounds[i]["field_normalised_mean_square"].get<double>(), rounds[i - 1]["field_normalised_mean_square"].get<double>());
    }
  EXPECT_LE(s["knot_optimisation"]["field_normalised_mean_square_after"].get<double>(),
            s["knot_optimisation"]["field_normalised_mean_square_before"].get<double>());
  EXPECT_LE(s["knot_optimisation"]["primary_knots_moved"].get<int>(), s["knot_optimisation"]["vertices_moved"].get<int>());
  // The placement ran its rounds (3 by default) and never made the held-out error worse.
  ASSERT_TRUE(s.contains("knot_placement"));
  EXPECT_GE(s["knot_placement"]["rounds"].get<int>(), 1);
  EXPECT_TRUE(s["knot_placement"].contains("rounds_failed"));
  EXPECT_LE(s["knot_placement"]["held_out_field_normalised_mean_square_after"].get<double>(),
            s["knot_placement"]["held_out_field_normalised_mean_square_before"].get<double>());
  // A budget that stops the refinement is said on stderr.
  if (s["adaptive_refinement"]["state"].get<std::string>().rfind("converged", 0) != 0) {
    EXPECT_NE(r.err.find("adaptive refinement"), std::string::npos) << r.err;
  }
}

TEST_F(FitCli, KnotSweepsAndFixedPrimaryKnotsReachTheLocalStep) {
  // `other` = xy is quadratic: degree 1 leaves errors for the local step to lower. A degree-1 DMS
  // spline is the piecewise linear interpolant at the primary knots whatever the sub-knots, so
  // only moving primary knots can lower it.
  // Judged at the data first, then (below) on the held-out eighth of the points.
  for (const bool fixed : {false, true}) {
    const auto r = run("fit " + path("data.csv") + " --degree 1 --attributes other --primary-knots 40 --knots optimise --placement-rounds 0 "
                       "--knot-sweeps 3 --judge-local-step-at-data" + std::string(fixed ? " --fixed-primary-knots" : "") + " --stats " + path("s.json") + " -o " + path("m.json"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("(judged at the data)"), std::string::npos) << r.out;
    const nlohmann::json k = nlohmann::json::parse(std::ifstream(path("s.json")))["knot_optimisation"];
    EXPECT_FALSE(k["judged_on_held_out"].get<bool>());
    EXPECT_LE(k["sweeps"].get<int>(), 3);
    const double before = k["field_normalised_mean_square_before"].get<double>(), after = k["field_normalised_mean_square_after"].get<double>();
    if (fixed) {
      EXPECT_EQ(k["primary_knots_moved"].get<int>(), 0);
      EXPECT_NEAR(after, before, 1e-12 * before);
    } else {
      EXPECT_GT(k["primary_knots_moved"].get<int>(), 0);
      EXPECT_LE(k["primary_knots_moved"].get<int>(), k["vertices_moved"].get<int>());
      EXPECT_GT(k["sweeps_kept"].get<int>(), 0);
      EXPECT_LT(after, 0.95 * before);
    }
  }
  // By default the sweeps are judged on the held-out eighth of the points, and a sweep that
  // raises the error there is undone (the fit given stays).
  const auto r = run("fit " + path("data.csv") + " --degree 1 --attributes other --primary-knots 40 --knots optimise --placement-rounds 0 "
                     "--knot-sweeps 3 --stats " + path("s.json") + " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("at the held-out eighth of the points"), std::string::npos) << r.out;
  const nlohmann::json k = nlohmann::json::parse(std::ifstream(path("s.json")))["knot_optimisation"];
  EXPECT_TRUE(k["judged_on_held_out"].get<bool>());
  const double held_before = k["held_out_field_normalised_mean_square_before"].get<double>();
  const double held_after = k["held_out_field_normalised_mean_square_after"].get<double>();
  EXPECT_GT(held_before, 0);
  EXPECT_LE(held_after, held_before);
  // Measured: with each move checked at its ring's held-out points, the three sweeps are kept
  // and lower the error at the 64 held-out points by a tenth (2.07e-4 -> 1.86e-4).
  const int kept = k["sweeps_kept"].get<int>();
  EXPECT_NE(r.out.find("(" + std::to_string(kept) + " kept)"), std::string::npos) << r.out;
  ASSERT_GT(kept, 0);
  EXPECT_LT(held_after, 0.95 * held_before);
  EXPECT_LT(k["field_normalised_mean_square_after"].get<double>(), k["field_normalised_mean_square_before"].get<double>());
}

TEST_F(FitCli, BaselinesAreFittedToTheSameDataAndCompared) {
  // The linear temperature on an 8^3 grid: every method but nearest reproduces it; the table has
  // one row per method, and generated data is also measured against its true field.
  auto r = run("fit " + path("data.csv") + " --attributes temperature --baselines --stats " + path("s.json") + " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(path("s.json")));
  const auto& rows = s["baselines"];
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[1]["method"], "tensor-product least squares (degree 2)");
  for (int m = 0; m < 3; ++m) EXPECT_LT(rows[m]["data_max_abs"].get<double>(), 1e-9) << rows[m]["method"];
  EXPECT_TRUE(rows[0]["truth_mean_square"].is_null());
  EXPECT_NE(r.out.find("trilinear interpolation"), std::string::npos);
  r = run("fit marschner-lobb:7 --degree 1 --baselines --stats " + path("ml.json") + " -o " + path("ml-model.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json ml = nlohmann::json::parse(std::ifstream(path("ml.json")));
  for (const auto& row : ml["baselines"]) EXPECT_GT(row["truth_mean_square"].get<double>(), 0.0) << row["method"];
}

// Points in a ball, few primary knots: the domain (their Delaunay tetrahedra) misses some data.
// The command says so on stderr with the count, the statistics carry it, and the baselines are
// measured at the points the simplex spline fits (the tensor product's row counts no other).
TEST_F(FitCli, DataOutsideTheDomainIsReportedAndLeftOutOfEveryMethodsErrors) {
  std::ofstream csv(path("ball.csv"));
  csv.precision(17);
  csv << "x,y,z,f\n";
  unsigned state = 12345;
  auto next = [&] {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) & 0xffff) / 65535.0 * 2 - 1;
  };
  int written = 0;
  while (written < 600) {
    const double x = next(), y = next(), z = next();
    if (x * x + y * y + z * z > 1) continue;
    csv << x << "," << y << "," << z << "," << x + y * z << "\n";
    ++written;
  }
  csv.close();
  const auto r = run("fit " + path("ball.csv") + " --degree 1 --primary-knots 30 --baselines --stats " + path("s.json") + " -o " + path("m.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(path("s.json")));
  const auto outside = s["outside_points"].get<int>();
  ASSERT_GT(outside, 0);
  EXPECT_NE(r.err.find("warning: " + std::to_string(outside) + " of 600 data points"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("lie outside the domain"), std::string::npos) << r.err;
  // The simplex spline's row is its fit's own error (over the points it fits), and the tensor
  // product, measured at the same points, keeps its error there below its largest anywhere.
  const auto& rows = s["baselines"];
  ASSERT_GE(rows.size(), 2u);
  EXPECT_NEAR(rows[0]["data_mean_square"].get<double>(), s["field_errors"][0]["mean_square"].get<double>(), 1e-12);
  EXPECT_NEAR(rows[0]["data_max_abs"].get<double>(), s["field_errors"][0]["max_abs"].get<double>(), 1e-12);
  for (const auto& row : rows) EXPECT_EQ(row["data_points"].get<int>(), 600 - outside) << row["method"];
}

}  // namespace
}  // namespace volspline
