// `volspline boundary` on a simplex spline volume: the image of the domain's boundary (part 17),
// closed, on the solid's surface, and with --iso-attribute the attribute's isosurface (part 16)
// on its level set; an unknown attribute exits with 2 and writes nothing.
#include <filesystem>
#include <span>
#include <string>

#include <gtest/gtest.h>

#include "support/cli_runner.h"
#include "support/simplex_domains.h"
#include "support/temporary_directory.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/parts.h"

namespace volspline {
namespace {

class SimplexBoundaryCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }
  test_support::CliResult run(const std::string& args) const { return test_support::run_cli(args, tmp.path()); }

  // The unit cube with density |x − c|² (a quadratic, reproduced exactly by degree 2).
  void SetUp() override {
    DmsSplineVolume v = test_support::cube_simplex_volume(2);
    set_column_from_blossom(v, 3, [&](std::span<const Eigen::Vector3d> args) {
      double sum = 0;
      int pairs = 0;
      for (std::size_t i = 0; i < args.size(); ++i)
        for (std::size_t j = 0; j < args.size(); ++j)
          if (i != j) sum += (args[i] - centre).dot(args[j] - centre), ++pairs;
      return sum / pairs;
    });
    Model model;
    model.objects.push_back({"cube", false, std::move(v), nullptr});
    write_model(model, path("cube.json"));
  }
  const Eigen::Vector3d centre{0.5, 0.48, 0.52};
};

TEST_F(SimplexBoundaryCli, WritesTheClosedDomainBoundaryAndIsosurfaces) {
  auto r = run("boundary " + path("cube.json") + " -o " + path("b.ply") + " --png " + path("b.png") + " --size 64,48 --stats " + path("b.json") + " --iso-edge 0.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("domain boundary triangles"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(path("b.png")));
  EXPECT_TRUE(std::filesystem::exists(path("b.json")));
  const TriangleMesh boundary = read_mesh(path("b.ply"));
  ASSERT_GT(boundary.num_triangles(), 100u);
  EXPECT_TRUE(edge_statistics(boundary).closed_and_oriented());
  EXPECT_NEAR(enclosed_volume(boundary), 1.0, 1e-9);  // the identity geometry: the unit cube, outward
  for (const int part : boundary.parts) EXPECT_EQ(part, part_number(Part::DomainBoundary));

  r = run("boundary " + path("cube.json") + " -o " + path("both.ply") + " --iso-attribute density:0.09 --iso-edge 0.1");
  ASSERT_EQ(r.code, 0) << r.err;
  const TriangleMesh both = read_mesh(path("both.ply"));
  EXPECT_TRUE(edge_statistics(both).closed_and_oriented());  // two closed surfaces
  std::size_t iso = 0;
  for (std::size_t t = 0; t < both.num_triangles(); ++t)
    if (both.parts[t] == part_number(Part::AttributeIsosurface)) {
      ++iso;
      for (const int v : both.triangles[t]) EXPECT_NEAR((both.positions[static_cast<std::size_t>(v)] - centre).norm(), 0.3, 1e-6);
    }
  EXPECT_GT(iso, 100u);
  // The cube, then the ball inside it facing outward: the enclosed volumes add up.
  EXPECT_NEAR(enclosed_volume(both), 1.0 + 4.0 / 3.0 * M_PI * 0.027, 0.01);

  for (const char* ext : {".obj", ".stl", ".glb"}) {
    r = run("boundary " + path("cube.json") + " -o " + path(std::string("b") + ext) + " --iso-attribute density:0.09 --iso-edge 0.3");
    EXPECT_EQ(r.code, 0) << ext << ": " << r.err;
    EXPECT_TRUE(std::filesystem::exists(path(std::string("b") + ext))) << ext;
  }
}

TEST_F(SimplexBoundaryCli, UnknownAttributeExitsWithTwoAndWritesNothing) {
  const auto r = run("boundary " + path("cube.json") + " -o " + path("x.ply") + " --png " + path("x.png") + " --iso-attribute temperature:1");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("no attribute \"temperature\""), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--iso-attribute"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("x.ply")));
  EXPECT_FALSE(std::filesystem::exists(path("x.png")));
  const auto bad = run("boundary " + path("cube.json") + " -o " + path("x.ply") + " --iso-attribute density");
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("NAME:VALUE"), std::string::npos) << bad.err;
}

// `view --iso-attribute` and slices sample by local bisection (--iso-edge) or alike everywhere
// (--iso-subdivisions), not both, and only isosurfaces and slices.
TEST_F(SimplexBoundaryCli, ViewChoosesTheIsosurfaceSampling) {
  auto r = run("view " + path("cube.json") + " -o " + path("v.png") + " --size 64,48 --iso-attribute density:0.09 --iso-edge 0.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("local bisection"), std::string::npos) << r.out;
  r = run("view " + path("cube.json") + " -o " + path("v.png") + " --size 64,48 --iso-attribute density:0.09 --iso-subdivisions 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("k = 2"), std::string::npos) << r.out;
  r = run("view " + path("cube.json") + " -o " + path("v.png") + " --size 64,48 --slices z:2 --iso-edge 0.1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 slice(s) through"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(local bisection)"), std::string::npos) << r.out;
  r = run("view " + path("cube.json") + " -o " + path("v.png") + " --size 64,48 --plane 0,0,1,0.5 --iso-subdivisions 3");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("(k = 3)"), std::string::npos) << r.out;
  std::filesystem::remove(path("v.png"));
  for (const char* bad : {" --iso-attribute density:0.09 --iso-edge 0.1 --iso-subdivisions 2", " --cells 2 --iso-edge 0.1"}) {
    r = run("view " + path("cube.json") + " -o " + path("v.png") + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find("--iso-"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("v.png")));
  }
}

}  // namespace
}  // namespace volspline
