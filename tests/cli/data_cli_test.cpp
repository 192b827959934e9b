// `volspline data` end to end: the summary of generated grid data (points, grid, attribute
// ranges), the point picture, the grid isosurface written as a mesh, and bad input (exit 2,
// nothing written).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

using test_support::run_cli;

TEST(DataCli, SummarisesGridDataAndDrawsItsPointsAndIsosurfaces) {
  test_support::TemporaryDirectory dir;
  auto r = run_cli("data marschner-lobb:5 --json", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"].get<int>(), 125);
  EXPECT_EQ(j["grid"], nlohmann::json({5, 5, 5}));
  const VolumeData data = marschner_lobb_data(5);
  ASSERT_EQ(j["attributes"].size(), 1u);
  EXPECT_EQ(j["attributes"][0]["name"], "rho");
  EXPECT_EQ(j["attributes"][0]["min"].get<double>(), data.attributes.minCoeff());
  EXPECT_EQ(j["attributes"][0]["max"].get<double>(), data.attributes.maxCoeff());
  EXPECT_EQ(j["box"], nlohmann::json({{-1, -1, -1}, {1, 1, 1}}));

  const auto png = (dir.path() / "p.png").string();
  r = run_cli("data two-material:5 --png " + png + " --attribute material --size 160,120 --cut-open 0,0,1,0.6", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(png));
  EXPECT_NE(r.out.find("wrote " + png + ": 75 points coloured by material"), std::string::npos) << r.out;  // z <= 0.6: 3 of 5 layers

  // The jump of two-material:9 lies between the nodes x = 0.375 and x = 0.5: so does every
  // vertex of the isosurface material = 1.55.
  const auto ply = (dir.path() / "iso.ply").string();
  r = run_cli("data two-material:9 --iso material:1.55 -o " + ply, dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const TriangleMesh mesh = read_mesh(ply);
  ASSERT_GT(mesh.num_triangles(), 0u);
  for (const auto& x : mesh.positions) {
    EXPECT_GE(x.x(), 0.375 - 1e-12);
    EXPECT_LE(x.x(), 0.5 + 1e-12);
  }
}

TEST(DataCli, BadInputExitsWithTwoAndWritesNothing) {
  test_support::TemporaryDirectory dir;
  const auto out = (dir.path() / "x.ply").string(), png = (dir.path() / "x.png").string();
  {
    std::ofstream csv(dir.path() / "scattered.csv");
    csv << "x,y,z,f\n0,0,0,1\n1,0.2,0,2\n0,1,0.3,3\n0.1,0,1,4\n";
  }
  const auto csv = (dir.path() / "scattered.csv").string();
  const std::vector<std::pair<std::string, std::string>> cases{
      {"data " + (dir.path() / "missing.csv").string(), "missing.csv"},
      {"data marschner-lobb:5 -o " + out, "--iso"},
      {"data " + csv + " --iso f:2 -o " + out, "scattered"},
      {"data marschner-lobb:5 --iso rho -o " + out, "NAME:VALUE"},
      {"data marschner-lobb:5 --iso g:0.5 -o " + out, "rho"},
      {"data marschner-lobb:5 --png " + png + " --attribute g", "rho"},
      {"data marschner-lobb:5 --view 1,0,0", "--png"},
      {"data marschner-lobb:5 --iso rho:0.5 --attribute rho --png " + png, "NAME:VALUE"},
      {"data marschner-lobb:1", "marschner-lobb:N"},
      {"data marschner-lobb:5 --png " + (dir.path() / "x.jpg").string(), ".png"},
  };
  for (const auto& [args, said] : cases) {
    const auto r = run_cli(args, dir.path());
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(said), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
    EXPECT_FALSE(std::filesystem::exists(png)) << args;
  }
}

}  // namespace
}  // namespace volspline
