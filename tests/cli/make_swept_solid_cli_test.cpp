// `volspline make swept-solid` end to end: the written swept solid is the library's, fitted frames
// print their error, and bad input exits with 2 naming the file, with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/swept_examples.h"
#include "volspline/io/model_file.h"

namespace volspline {
namespace {

using Eigen::Vector3d;

class MakeSweptSolidCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }

  template <class... S>
  std::string write(const std::string& name, const S&... splines) const {
    Model m;
    (m.objects.push_back({"", false, splines, nullptr}), ...);
    write_model(m, path(name));
    return path(name);
  }

  void SetUp() override {
    const auto quarters = torus_quarter_patches();
    write("torus.json", quarters[0], quarters[1], quarters[2], quarters[3]);
    write("line.json", line_path(Vector3d::Zero(), Vector3d(0, 0, 4)));
    write("arc.json", semicircle_path());
  }

  test_support::CliResult make(const std::string& args) const {
    return test_support::run_cli("make swept-solid " + args + " -o " + path("out.json"), tmp.path());
  }

  void expect_bad(const std::string& args, const std::string& named) const {
    std::filesystem::remove(path("out.json"));
    const auto r = make(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("out.json"))) << args;
  }
};

TEST_F(MakeSweptSolidCli, WritesTheLibrarysSweptSolid) {
  const auto r = make("--generator " + path("torus.json") + " --path " + path("line.json") + " --frame rotate:0,0,1:-135");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("4 generator patch(es), frame rotate"), std::string::npos) << r.out;
  const Model m = read_model(path("out.json"));
  ASSERT_EQ(m.objects.size(), 1u);
  const auto& solid = std::get<SweptSolid>(m.objects[0].spline);
  const SweptSolid expected = make_swept_solid(torus_quarter_patches(), line_path(Vector3d::Zero(), Vector3d(0, 0, 4)),
                                               SweptSolidFrame::rotation(Vector3d::UnitZ(), -135));
  ASSERT_EQ(solid.generator.size(), 4u);
  for (std::size_t p = 0; p < 4; ++p) {
    const auto a = swept_patch(solid, p), b = swept_patch(expected, p);
    for (double t : {0.0, 0.3, 1.0}) EXPECT_LE((a.evaluate({0.7, 0.2, 0.9, t}) - b.evaluate({0.7, 0.2, 0.9, t})).norm(), 1e-13);
  }
}

TEST_F(MakeSweptSolidCli, FittedFramesPrintTheirErrorAndFrameFilesAreUsedAsGiven) {
  const auto r = make("--generator " + path("torus.json") + " --path " + path("arc.json") + " --frame rmf");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("frame fit error"), std::string::npos) << r.out;
  EXPECT_LE(std::get<SweptSolid>(read_model(path("out.json")).objects[0].spline).frame_fit_error, kSweepFrameTolerance);
  // A sheared, scaled frame of other degrees: b = (2, 0, 0), n = (s, 1, 0), t = (0, 0, 1).
  const std::string frame = write("frame.json", line_path(Vector3d(2, 0, 0), Vector3d(2, 0, 0)), line_path(Vector3d(0, 1, 0), Vector3d(1, 1, 0)),
                                  line_path(Vector3d::UnitZ(), Vector3d::UnitZ()));
  const auto f = make("--generator " + path("torus.json") + " --path " + path("line.json") + " --frame " + frame);
  ASSERT_EQ(f.code, 0) << f.err;
  const Model model = read_model(path("out.json"));
  const auto& solid = std::get<SweptSolid>(model.objects[0].spline);
  EXPECT_EQ(solid.frame_name, "curves");
  const Eigen::VectorXd g = solid.generator[0].evaluate({1.0, 0.0, 0.0});
  const Eigen::VectorXd s = swept_patch(solid, 0).evaluate({1.0, 0.0, 0.0, 1.0});
  EXPECT_NEAR(s[0], 2 * g[0] + g[1], 1e-12);
  EXPECT_NEAR(s[1], g[1], 1e-12);
  EXPECT_NEAR(s[2], g[2] + 4.0, 1e-12);
}

TEST_F(MakeSweptSolidCli, BadInputExitsWithTwoNamingTheFile) {
  const std::string g = " --generator " + path("torus.json"), c = " --path " + path("line.json");
  expect_bad("--generator " + path("line.json") + c, "line.json has no volume object");
  expect_bad(g + " --path " + path("torus.json"), "torus.json: objects[0] is not a curve");
  expect_bad(g + " --path " + write("two-paths.json", line_path(Vector3d::Zero(), Vector3d::UnitX()), line_path(Vector3d::Zero(), Vector3d::UnitY())),
             "has 2 curve objects; a path file holds exactly one");
  expect_bad(g + c + " --frame " + path("torus.json"), "torus.json: objects[0] is not a curve");
  expect_bad(g + c + " --frame frenet", "--frame frenet on --path " + path("line.json"));
  // A generator that is no volume: a unit box flattened into the plane z = 0.
  {
    std::vector<double> points;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) points.insert(points.end(), {double(i), double(j), 0.0});
    expect_bad("--generator " + write("flat-box.json", BSplineVolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, points)) + c,
               "flat-box.json: objects[0]: a generator patch must be a volume; this one's Jacobian vanishes identically");
  }
  expect_bad(g + " --path " + write("flat.json", BSplineCurve({KnotVector::bezier(1)}, 2, {0, 0, 1, 1})), "--path " + path("flat.json"));
  expect_bad("--generator " + write("flat-volume.json", BSplineVolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 2,
                                                                      std::vector<double>(16, 0.5))) + c,
             path("flat-volume.json") + ": objects[0]");
  expect_bad(g + c + " --frame twist", "twist");
  expect_bad(g + c + " --frame rotate:0,0:90", "--frame axis");
  expect_bad(g + c + " --frame rotate:0,0,0:90", "nonzero");
  expect_bad(g + c + " --frame " + write("two.json", line_path(Vector3d::UnitX(), Vector3d::UnitX()), line_path(Vector3d::UnitY(), Vector3d::UnitY())),
             "has 2 curve object(s)");
  // b(t) and n(t) parallel at t = 1/2: det R = t - 1/2.
  const std::string singular = write("singular.json", line_path(Vector3d::UnitX(), Vector3d::UnitX()),
                                     line_path(Vector3d(1, -0.5, 0), Vector3d(1, 0.5, 0)), line_path(Vector3d::UnitZ(), Vector3d::UnitZ()));
  expect_bad(g + c + " --frame " + singular, "singular.json");
  expect_bad(g + c + " --frame " + singular, "vanishes at t = 0.5");
  expect_bad(g + " --path " + path("missing.json"), "missing.json");
}

// Commands that work on volumes or splines say why they do not take a swept solid.
TEST_F(MakeSweptSolidCli, OtherCommandsReportOrSkipSweptSolids) {
  const std::string example = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/swept-rotating-box.json";
  const auto info = test_support::run_cli("info " + example, tmp.path());
  EXPECT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("swept_solid"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("frame           rotate"), std::string::npos) << info.out;
  const auto faces = test_support::run_cli("faces " + example + " -o " + path("f.ply"), tmp.path());
  EXPECT_EQ(faces.code, 2);
  EXPECT_NE(faces.err.find("swept solids and hypervolumes are skipped"), std::string::npos) << faces.err;
  const auto eval = test_support::run_cli("eval " + example + " --at 0.5", tmp.path());
  EXPECT_EQ(eval.code, 2);
  EXPECT_NE(eval.err.find("not on a swept solid"), std::string::npos) << eval.err;
  const auto vtu = test_support::run_cli("convert " + example + " -o " + path("s.vtu"), tmp.path());
  EXPECT_EQ(vtu.code, 2);
  EXPECT_NE(vtu.err.find("objects[0]: VTK holds curves, surfaces and volumes, not a swept_solid"), std::string::npos) << vtu.err;
  EXPECT_FALSE(std::filesystem::exists(path("s.vtu")));
  // A plain change of format passes the swept solid through; refining it is refused.
  EXPECT_EQ(test_support::run_cli("convert " + example + " -o " + path("s.json"), tmp.path()).code, 0);
  const auto refined = test_support::run_cli("convert " + example + " -o " + path("r.json") + " --elevate u:1", tmp.path());
  EXPECT_EQ(refined.code, 2);
  EXPECT_NE(refined.err.find("conversion works on splines, not on a swept solid"), std::string::npos) << refined.err;
}

}  // namespace
}  // namespace volspline
