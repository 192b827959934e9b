// volspline blend: meshes, pictures and statistics from a scene file; bad scenes exit with 2 and
// a message naming the file and the JSON path.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

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

TEST(BlendCli, WritesBinaryGltfWithTheTrianglesOfThePly) {
  // The same scene written as .ply and as .glb: tinygltf's own loader reads the .glb back, and
  // its index count is three per triangle of the .ply; positions agree as floats.
  test::TemporaryDirectory dir;
  const std::string scene = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes/scene-two-tori.json";
  for (const char* out : {"s.ply", "s.glb"})
    ASSERT_EQ(test::run_cli("blend " + scene + " -o " + (dir / out).string() + " --levels 1", dir.path()).code, 0) << out;
  const TriangleMesh ply = read_mesh(dir / "s.ply");
  ASSERT_GT(ply.num_triangles(), 1000u);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (dir / "s.glb").string())) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  std::size_t indices = 0;
  std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
  for (const tinygltf::Mesh& mesh : model.meshes)
    for (const tinygltf::Primitive& primitive : mesh.primitives) {
      EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
      indices += model.accessors.at(static_cast<std::size_t>(primitive.indices)).count;
      const tinygltf::Accessor& position = model.accessors.at(static_cast<std::size_t>(primitive.attributes.at("POSITION")));
      for (int d = 0; d < 3; ++d) {
        lo[static_cast<std::size_t>(d)] = std::min(lo[static_cast<std::size_t>(d)], static_cast<float>(position.minValues.at(static_cast<std::size_t>(d))));
        hi[static_cast<std::size_t>(d)] = std::max(hi[static_cast<std::size_t>(d)], static_cast<float>(position.maxValues.at(static_cast<std::size_t>(d))));
      }
    }
  EXPECT_EQ(indices, 3 * ply.num_triangles());
  // The bounding boxes agree (glTF stores float positions).
  Eigen::Vector3d ply_lo = ply.positions[0], ply_hi = ply.positions[0];
  for (const auto& x : ply.positions) ply_lo = ply_lo.cwiseMin(x), ply_hi = ply_hi.cwiseMax(x);
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(lo[static_cast<std::size_t>(d)], ply_lo[d], 1e-5);
    EXPECT_NEAR(hi[static_cast<std::size_t>(d)], ply_hi[d], 1e-5);
  }
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
