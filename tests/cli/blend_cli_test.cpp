// volspline blend: meshes, pictures and statistics from a scene file; bad scenes exit with 2 and
// a message naming the file and the JSON path.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

const char* kSphere = R"({"volspline_scene": 1, "spacing": 0.25, "box": {"min": [-1, -1, -1], "max": [1, 1, 1]},
  "root": {"sphere": {"center": [0, 0, 0], "radius": 0.7}}})";

TEST(BlendCli, WritesMeshPictureAndStatistics) {
  test::TemporaryDirectory dir;
  write_text(dir / "sphere.json", kSphere);
  const auto r = test::run_cli("blend " + (dir / "sphere.json").string() + " -o " + (dir / "s.ply").string() + " --png " +
                                   (dir / "s.png").string() + " --stats " + (dir / "s.json").string() +
                                   " --method exact --project --levels 1",
                               dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(read_file(dir / "s.json"));
  EXPECT_TRUE(stats["closed"].get<bool>());
  EXPECT_LT(stats["max_distance"].get<double>(), 1e-12);
  EXPECT_GT(stats["triangles"].get<int>(), 100);
  const TriangleMesh mesh = read_mesh(dir / "s.ply");
  EXPECT_EQ(mesh.num_triangles(), stats["triangles"].get<std::size_t>());
  EXPECT_TRUE(std::filesystem::file_size(dir / "s.png") > 1000);
}

TEST(BlendCli, ExampleScenesMeshClosed) {
  test::TemporaryDirectory dir;
  for (const char* name : {"scene-cylinder-intersection", "scene-two-tori"}) {
    const auto r = test::run_cli(std::string("blend ") + VOLSPLINE_SOURCE_DIR + "/examples/scenes/" + name + ".json -o " +
                                     (dir / "out.stl").string() + " --stats " + (dir / "s.json").string(),
                                 dir.path());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(nlohmann::json::parse(read_file(dir / "s.json"))["closed"].get<bool>()) << name;
  }
}

TEST(BlendCli, BadScenesExitWithTwoAndSayWhere) {
  test::TemporaryDirectory dir;
  const std::string head = R"({"volspline_scene": 1, )";
  const std::string box = R"("box": {"min": [0, 0, 0], "max": [1, 1, 1]}, )";
  const std::string sphere = R"("root": {"sphere": {"center": [0, 0, 0], "radius": 1}}})";
  const std::pair<std::string, std::string> cases[] = {
      {head + R"("spacing": 0.5, )" + box + R"("root": {"pyramid": {}}})", "bad.json: root.pyramid: unknown node \"pyramid\""},
      {head + R"("spacing": 0.5, )" + box + R"("root": {"sphere": {"center": [0, 0, 0], "radius": -1}}})",
       "bad.json: root.sphere.radius: expected a positive radius, got -1"},
      {head + R"("spacing": 0.5, "box": {"min": [0, 0, 0], "max": [1, 1, 0]}, )" + sphere,
       "bad.json: box: expected a nonempty box"},
      {head + R"("spacing": 0, )" + box + sphere, "bad.json: spacing: expected a positive lattice spacing, got 0"},
      {head + R"("spacing": -1, )" + box + sphere, "bad.json: spacing: expected a positive lattice spacing, got -1"},
  };
  for (const auto& [text, message] : cases) {
    write_text(dir / "bad.json", text);
    const auto r = test::run_cli("blend " + (dir / "bad.json").string() + " -o " + (dir / "out.ply").string(), dir.path());
    EXPECT_EQ(r.code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
  }
  write_text(dir / "ok.json", kSphere);
  EXPECT_EQ(test::run_cli("blend " + (dir / "ok.json").string() + " -o out.xyz", dir.path()).code, 2);
  EXPECT_EQ(test::run_cli("blend " + (dir / "ok.json").string() + " -o out.ply --method magic", dir.path()).code, 2);
  EXPECT_EQ(test::run_cli("blend " + (dir / "ok.json").string() + " -o out.ply --project", dir.path()).code, 2);
  EXPECT_EQ(test::run_cli("blend " + (dir / "missing.json").string() + " -o out.ply", dir.path()).code, 2);
}

}  // namespace
}  // namespace volspline
