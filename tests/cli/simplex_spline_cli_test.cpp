// Simplex spline volumes from the command line: `make simplex-spline` writes the library's
// volume, `info`, `eval`, `convert` and `xray` work on it, and bad input exits with 2 naming the
// file, with nothing written.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "support/cli_runner.h"
#include "support/simplex_domains.h"
#include "support/temporary_directory.h"
#include "volspline/io/model_file.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

class SimplexSplineCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }

  void SetUp() override {
    std::ofstream points(path("points.csv"));
    points << "x,y,z\n";
    for (const Eigen::Vector3d& p : test_support::jittered_cube_domain().points) points << p.x() << ", " << p.y() << ", " << p.z() << "\n";
    std::ofstream(path("skeleton.json")) << R"({"volspline_skeleton": 1, "elements": [{"kind": "point", "points": [[0.5, 0.5, 0.5]], "falloff": {"kind": "inverse_square", "scale": 0.3}}]})";
  }

  test_support::CliResult run(const std::string& args) const { return test_support::run_cli(args, tmp.path()); }

  void expect_bad(const std::string& args, const std::string& named, const std::string& out) const {
    std::filesystem::remove(path(out));
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(path(out))) << args;
  }
};

TEST_F(SimplexSplineCli, MakesInspectsEvaluatesConvertsAndXrays) {
  auto r = run("make simplex-spline --points " + path("points.csv") + " --degree 2 --skeleton " + path("skeleton.json") + " -o " + path("s.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("degree 2 simplex spline volume over"), std::string::npos) << r.out;
  const Model m = read_model(path("s.json"));
  ASSERT_TRUE(is_simplex_spline_volume(m.objects.at(0)));
  const auto& v = std::get<DmsSplineVolume>(m.objects[0].spline);
  EXPECT_EQ(v.attribute_names(), std::vector<std::string>{"density"});

  r = run("info " + path("s.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("simplex_spline_volume"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("attribute       density"), std::string::npos) << r.out;

  r = run("eval " + path("s.json") + " --at 0.3,0.4,0.5 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  DmsSplineEvaluator evaluator(v);
  const DmsSplinePoint expected = evaluator.evaluate(Eigen::Vector3d(0.3, 0.4, 0.5));
  ASSERT_EQ(j["points"][0].size(), 4u);
  EXPECT_NEAR(j["points"][0][0].get<double>(), 0.3, 1e-12);  // the identity geometry
  EXPECT_NEAR(j["points"][0][3].get<double>(), expected.value[3], 1e-15);

  r = run("convert " + path("s.json") + " -o " + path("s.vtu"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("s.vtu")));

  r = run("xray " + path("s.json") + " -o " + path("x.png") + " --size 40,30 --raw " + path("x.pfm"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("x.png")));
  EXPECT_EQ(std::filesystem::file_size(path("x.pfm")), std::string("Pf\n40 30\n-1.0\n").size() + 4u * 40 * 30);

  r = run("view " + path("s.json") + " -o " + path("v.png") + " --iso-attribute density:0.5 --slices z:2 --size 64,48");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 slice(s)"), std::string::npos) << r.out;

  r = run("split-tetrahedron " + path("s.json") + " --tetrahedron 3 -o " + path("split.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("re-fit error max"), std::string::npos) << r.out;
  EXPECT_EQ(std::get<DmsSplineVolume>(read_model(path("split.json")).objects[0].spline).domain().tetrahedra.size(), v.domain().tetrahedra.size() + 3);
}

// The same command gives the same file byte for byte, in separate processes (so heap addresses
// differ) and whatever the load: Mesh_3 refinement and exudation, knot clouds and the
// least-squares skeleton attribute must not depend on timing, addresses or thread scheduling.
// (Mesh_3's exudation used to stop after as many seconds as refinement took.)
TEST_F(SimplexSplineCli, MeshingASurfaceTwiceGivesTheSameFile) {
  const std::string examples = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/";
  const std::string args = "make simplex-spline --surface " + examples + "torus-surface.off --cell-size 0.3 --degree 2 --skeleton " +
                           examples + "skeletons/skeleton-torus-sm.json -o ";
  for (const char* name : {"first.json", "second.json"}) {
    const auto r = run(args + path(name));
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const auto bytes = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string first = bytes(path("first.json"));
  EXPECT_GT(first.size(), 1000u);
  EXPECT_TRUE(first == bytes(path("second.json"))) << "the two runs wrote different files";
}

TEST_F(SimplexSplineCli, BadInputExitsWithTwoAndWritesNothing) {
  std::ofstream(path("bad.csv")) << "0 0 0\n1 0 0\n0 1 0\n0 0 oops\n";
  expect_bad("make simplex-spline --points " + path("bad.csv") + " -o " + path("s.json"), "bad.csv: line 4", "s.json");
  expect_bad("make simplex-spline --points " + path("points.csv") + " --degree 7 -o " + path("s.json"), "degree", "s.json");
  expect_bad("make simplex-spline --points " + path("points.csv") + " --tetrahedra x.mesh -o " + path("s.json"), "exactly one", "s.json");
  expect_bad("make simplex-spline --points " + path("points.csv") + " --degree 0 -o " + path("s.json"), "shared control vectors need degree", "s.json");
  ASSERT_EQ(run("make simplex-spline --points " + path("points.csv") + " -o " + path("s.json")).code, 0);
  expect_bad("xray " + path("s.json") + " --attribute heat -o " + path("x.png"), "no attribute \"heat\"", "x.png");
  expect_bad("split-tetrahedron " + path("s.json") + " --tetrahedron 0 --at 9,9,9 -o " + path("split.json"), "strictly inside", "split.json");
  expect_bad("view " + path("s.json") + " -o " + path("v.png") + " --iso u:3", "a simplex_spline_volume takes", "v.png");
  std::ofstream(path("sk.json")) << R"({"volspline_skeleton": 1, "elements": [{"kind": "segment", "points": [[0, 0, 0]]}]})";
  expect_bad("make simplex-spline --points " + path("points.csv") + " --skeleton " + path("sk.json") + " -o " + path("t.json"), "sk.json", "t.json");
}

}  // namespace
}  // namespace volspline
