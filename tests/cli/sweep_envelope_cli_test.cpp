// `volspline sweep-envelope` end to end: the trimmed envelope of the translated box example is
// the closed hull of its end positions (volume from the formula), --superset writes more than the
// boundary, and bad input exits with 2 naming what was wrong, with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

class SweepEnvelopeCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }
  static std::string example(const std::string& name) { return std::string(VOLSPLINE_SOURCE_DIR) + "/examples/" + name; }
};

TEST_F(SweepEnvelopeCli, TrimmedTranslatedBoxIsItsClosedHull) {
  const auto r = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("hull.ply") +
                                       " --stats " + path("s.json"),
                                       tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const TriangleMesh mesh = read_mesh(path("hull.ply"));
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  std::ifstream in(path("s.json"));
  const auto stats = nlohmann::json::parse(in);
  const auto& o = stats["objects"][0];
  EXPECT_TRUE(o["closed"].get<bool>());
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_NEAR(enclosed_volume(mesh), o["volume"].get<double>(), 1e-9);

  const auto s = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("superset.ply") +
                                       " --superset",
                                       tmp.path());
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_GT(read_mesh(path("superset.ply")).num_triangles(), mesh.num_triangles());
}

TEST_F(SweepEnvelopeCli, BadInputExitsTwoAndWritesNothing) {
  // A model without a swept solid, a bad option value, an unknown bounds method.
  for (const std::string& args : {example("swept-patch.json") + " -o " + path("a.ply"),
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --tol 0",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --bounds box"}) {
    const auto r = test_support::run_cli("sweep-envelope " + args, tmp.path());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("a.ply"))) << args;
  }
}

}  // namespace
}  // namespace volspline
