// The jacobian and boundary subcommands end to end: JSON keys, exit codes, files, no leftovers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

using test_support::run_cli;

TEST(JacobianCli, JsonVerdictsAndFailInvalid) {
  test_support::TemporaryDirectory dir;
  const auto folded = (dir.path() / "loft.json").string(), box = (dir.path() / "box.json").string();
  ASSERT_EQ(run_cli("make twisted-loft -o " + folded, dir.path()).code, 0);
  ASSERT_EQ(run_cli("make box --size 1,2,3 -o " + box, dir.path()).code, 0);
  auto r = run_cli("jacobian " + box + " --json --fail-invalid", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objects"][0]["verdict"], "valid");
  EXPECT_EQ(j["objects"][0]["orientation"], 1);
  EXPECT_TRUE(j["objects"][0]["witness"].is_null());
  EXPECT_NEAR(j["objects"][0]["lower"].get<double>(), 6.0, 1e-9);
  r = run_cli("jacobian " + folded + " --json", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["objects"][0]["verdict"], "invalid");
  EXPECT_EQ(j["objects"][0]["witness"].size(), 3u);
  for (const char* key : {"lower", "upper", "cells", "seconds", "orientation"}) EXPECT_TRUE(j["objects"][0].contains(key)) << key;
  EXPECT_EQ(run_cli("jacobian " + folded + " --fail-invalid", dir.path()).code, 3);
  EXPECT_EQ(run_cli("jacobian " + folded + " --bounds cone --json", dir.path()).code, 0);
  r = run_cli("jacobian " + folded + " --bounds spheres", dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--bounds"), std::string::npos);
  EXPECT_EQ(run_cli("jacobian " + (dir.path() / "missing.json").string(), dir.path()).code, 2);
}

TEST(BoundaryCli, MeshStatsAndPictureTogether) {
  test_support::TemporaryDirectory dir;
  const auto model = (dir.path() / "patch.json").string();
  ASSERT_EQ(run_cli("make swept-patch -o " + model, dir.path()).code, 0);
  const auto out = (dir.path() / "b.ply").string(), stats = (dir.path() / "s.json").string(), png = (dir.path() / "b.png").string();
  auto r = run_cli("boundary " + model + " -o " + out + " --stats " + stats + " --png " + png + " --snap", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto s = nlohmann::json::parse(read_file(stats));
  for (const char* key : {"cells_examined", "cells_kept", "triangles", "max_rel_jacobian_at_vertices", "seconds"}) {
    EXPECT_TRUE(s.contains(key)) << key;
  }
  EXPECT_GT(s["triangles"]["implicit"].get<int>(), 0);
  EXPECT_LT(s["max_rel_jacobian_at_vertices"].get<double>(), 1e-10);
  const TriangleMesh mesh = read_mesh(out);
  int implicit = 0;
  for (int p : mesh.parts) implicit += p == 6;
  EXPECT_EQ(implicit, s["triangles"]["implicit"].get<int>());
  EXPECT_TRUE(std::filesystem::exists(png));
  // Uniform baseline and cone bounds run too.
  EXPECT_EQ(run_cli("boundary " + model + " -o " + out + " --method uniform --resolution 20", dir.path()).code, 0);
  EXPECT_EQ(run_cli("boundary " + model + " -o " + out + " --bounds cone --tol 0.05", dir.path()).code, 0);
}

// --trim on a model of two overlapping unit boxes ([0, 1]^3 and [0.5, 1.5] x [0, 1]^2): the
// boundary of their union, one closed box of volume 1.5 with no vertex inside it, not two boxes
// trimmed each on its own (which would keep the faces x = 0.5 and x = 1 inside the union).
TEST(BoundaryCli, TrimGivesTheBoundaryOfTheUnionOfTheVolumes) {
  test_support::TemporaryDirectory dir;
  nlohmann::json objects = nlohmann::json::array();
  for (const double x0 : {0.0, 0.5}) {
    nlohmann::json points = nlohmann::json::array();
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) points.push_back({x0 + x, y, z});
    objects.push_back({{"type", "bspline_volume"}, {"degree", {1, 1, 1}}, {"knots", {{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}}}, {"control_points", points}});
  }
  const auto model = (dir.path() / "two.json").string(), out = (dir.path() / "t.ply").string(), stats = (dir.path() / "s.json").string();
  {
    std::ofstream file(model);
    file << nlohmann::json{{"volspline", 1}, {"objects", objects}}.dump();
  }
  const auto r = run_cli("boundary " + model + " --trim --trim-cell 2e-2 -o " + out + " --stats " + stats, dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("2 volumes: trimmed boundary of their union"), std::string::npos) << r.out;
  const auto s = nlohmann::json::parse(read_file(stats));
  ASSERT_EQ(s["objects"].size(), 1u);
  const auto& o = s["objects"][0];
  EXPECT_EQ(o["objects"], nlohmann::json({0, 1}));
  EXPECT_TRUE(o["closed"].get<bool>());
  EXPECT_TRUE(o["oriented"].get<bool>());
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_EQ(o["components"].get<int>(), 1);
  EXPECT_NEAR(o["volume"].get<double>(), 1.5, 1e-6);
  EXPECT_EQ(o["tags_beyond_tolerance"].get<int>(), 0);
  const TriangleMesh mesh = read_mesh(out);
  for (const auto& x : mesh.positions) {
    const double inside = std::min({x.x(), 1.5 - x.x(), x.y(), 1 - x.y(), x.z(), 1 - x.z()});
    EXPECT_LT(std::abs(inside), 1e-6) << x.transpose();
  }
}

TEST(BoundaryCli, BadInputLeavesNothingBehind) {
  test_support::TemporaryDirectory dir;
  const auto model = (dir.path() / "patch.json").string();
  ASSERT_EQ(run_cli("make swept-patch -o " + model, dir.path()).code, 0);
  const auto out = (dir.path() / "b.ply").string();
  for (const std::string args : {"--tol 0", "--method marching", "--stop never", "--png x.jpg", "--bounds cone --tol nan"}) {
    const auto r = run_cli("boundary " + model + " -o " + out + " " + args, dir.path());
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
  const auto torus = (dir.path() / "torus.json").string();
  ASSERT_EQ(run_cli("make torus --major 3 --minor 1 -o " + torus, dir.path()).code, 0);
  const auto r = run_cli("boundary " + torus + " -o " + out + " --bounds cone", dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("objects[0]"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace volspline
