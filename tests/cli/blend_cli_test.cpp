// volspline blend: meshes, pictures and statistics from a scene file; bad scenes exit with 2 and
// a message naming the file and the JSON path.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/parts.h"

namespace volspline {
namespace {

void write_text(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

const char* kSphere = R"({"volspline_scene": 1, "spacing": 0.25, "box": {"min": [-1, -1, -1], "max": [1, 1, 1]},
  "root": {"sphere": {"center": [0, 0, 0], "radius": 0.7}}})";

TEST(BlendCli, WritesMeshPictureAndStatistics) {
  test_support::TemporaryDirectory dir;
  write_text(dir / "sphere.json", kSphere);
  const auto r = test_support::run_cli("blend " + (dir / "sphere.json").string() + " -o " + (dir / "s.ply").string() + " --png " +
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

// --show: the ingredients (union, primitives) are closed and bound what they should relative to
// the blend; the spline part is the blend's BlendSpline triangles alone; --view turns the camera.
TEST(BlendCli, ShowsTheIngredientsTheUnionAndTheSplinePart) {
  test_support::TemporaryDirectory dir;
  const std::string scene = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes/scene-sphere-rod-blend.json";
  const auto mesh_of = [&](const std::string& arguments, const std::string& name) {
    const auto r = test_support::run_cli("blend " + scene + " " + arguments + " -o " + (dir / (name + ".ply")).string() + " --stats " +
                                             (dir / (name + ".json")).string(),
                                         dir.path());
    EXPECT_EQ(r.code, 0) << r.err;
    const nlohmann::json stats = nlohmann::json::parse(read_file(dir / (name + ".json")));
    EXPECT_EQ(stats["show"], arguments.empty() ? "blend" : arguments.substr(7, arguments.find(' ', 7) - 7)) << arguments;
    return read_mesh(dir / (name + ".ply"));
  };
  const TriangleMesh blend = mesh_of("", "blend");
  const TriangleMesh spline = mesh_of("--show spline", "spline");
  const TriangleMesh united = mesh_of("--show union --spacing 0.05", "union");
  const TriangleMesh primitives = mesh_of("--show primitives --spacing 0.05", "primitives");
  EXPECT_TRUE(edge_statistics(united).closed_and_oriented());
  EXPECT_TRUE(edge_statistics(primitives).closed_and_oriented());
  // The sphere and the rod overlap: meshed apart they bound more than their union, and the blend
  // fills the crease of the union (it bounds more than the union).
  EXPECT_GT(enclosed_volume(primitives), enclosed_volume(united) + 0.05);
  EXPECT_GT(enclosed_volume(blend), enclosed_volume(united));
  std::size_t spline_triangles = 0;
  for (const int part : blend.parts) spline_triangles += part == part_number(Part::BlendSpline) ? 1 : 0;
  EXPECT_EQ(spline.num_triangles(), spline_triangles);
  EXPECT_GT(spline.num_triangles(), 100u);
  for (const int part : spline.parts) EXPECT_EQ(part, part_number(Part::BlendSpline));

  // --view changes the picture; a zero direction, or --spacing without an ingredient, is refused
  // before anything is written.
  const auto picture = [&](const std::string& view, const std::string& name) {
    const auto r = test_support::run_cli("blend " + scene + " --levels 0 -o " + (dir / "p.ply").string() + " --png " +
                                             (dir / name).string() + view,
                                         dir.path());
    EXPECT_EQ(r.code, 0) << r.err;
    return read_file(dir / name);
  };
  EXPECT_NE(picture("", "a.png"), picture(" --view 0,-1,-0.2", "b.png"));
  EXPECT_EQ(picture("", "a.png"), picture(" --view -1,-1.3,-0.8", "c.png"));  // the default
  for (const auto& [arguments, option] : {std::pair{"--view 0,0,0", "--view"}, std::pair{"--view 1,2", "--view"},
                                          std::pair{"--spacing 0.1", "--spacing"}, std::pair{"--show union --spacing -1", "--spacing"}}) {
    const auto r = test_support::run_cli("blend " + scene + " " + arguments + " -o " + (dir / "bad.ply").string(), dir.path());
    EXPECT_EQ(r.code, 2) << arguments;
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.ply"));
  }
}

TEST(BlendCli, WritesBinaryGltfWithTheTrianglesOfThePly) {
  // The same scene written as .ply and as .glb: tinygltf's own loader reads the .glb back, and
  // its index count is three per triangle of the .ply; positions agree as floats.
  test_support::TemporaryDirectory dir;
  const std::string scene = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes/scene-two-tori.json";
  for (const char* out : {"s.ply", "s.glb"})
    ASSERT_EQ(test_support::run_cli("blend " + scene + " -o " + (dir / out).string() + " --levels 1", dir.path()).code, 0) << out;
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

// The README and `blend --help` promise: the spline surface orange, the primitives outside the box
// grey. Read back from the .glb (COLOR_0, linear RGB) without the part table: grey is r = g = b,
// orange is red well above green above blue. Triangles well inside the box must be orange, those
// well outside grey (the primitives were once drawn in the blue of the u-isoparametric surfaces).
TEST(BlendCli, GltfColoursTheSplineOrangeAndThePrimitivesOutsideTheBoxGrey) {
  test_support::TemporaryDirectory dir;
  const std::string scene = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes/scene-two-tori.json";
  for (const char* out : {"s.ply", "s.glb"})
    ASSERT_EQ(test_support::run_cli("blend " + scene + " -o " + (dir / out).string() + " --levels 1", dir.path()).code, 0) << out;
  const Eigen::Vector3d box_min(-0.75, -1.2, -0.6), box_max(0.75, 1.2, 0.6);  // the scene's box
  const double margin = 0.15;                                                   // the lattice spacing

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &error, &warning, (dir / "s.glb").string())) << error;
  const tinygltf::Primitive& primitive = model.meshes.at(0).primitives.at(0);
  const auto floats = [&](int index, std::size_t components) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    std::vector<float> values(accessor.count * components);
    std::memcpy(values.data(), model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data() + view.byteOffset + accessor.byteOffset,
                values.size() * sizeof(float));
    return values;
  };
  const std::vector<float> positions = floats(primitive.attributes.at("POSITION"), 3);
  const std::vector<float> colours = floats(primitive.attributes.at("COLOR_0"), 3);
  const tinygltf::Accessor& index_accessor = model.accessors.at(static_cast<std::size_t>(primitive.indices));
  ASSERT_EQ(index_accessor.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const tinygltf::BufferView& index_view = model.bufferViews.at(static_cast<std::size_t>(index_accessor.bufferView));
  std::vector<std::uint32_t> indices(index_accessor.count);
  std::memcpy(indices.data(),
              model.buffers.at(static_cast<std::size_t>(index_view.buffer)).data.data() + index_view.byteOffset + index_accessor.byteOffset,
              indices.size() * sizeof(std::uint32_t));

  const auto grey = [](const Eigen::Vector3d& c) { return std::abs(c[0] - c[1]) < 1e-6 && std::abs(c[1] - c[2]) < 1e-6; };
  const auto orange = [](const Eigen::Vector3d& c) { return c[0] > 0.5 && c[0] > c[1] + 0.2 && c[1] > c[2]; };
  std::size_t inside = 0, outside = 0;
  for (std::size_t t = 0; 3 * t < indices.size(); ++t) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero(), colour = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t g = indices[3 * t + k];
      centre += Eigen::Vector3d(positions[3 * g], positions[3 * g + 1], positions[3 * g + 2]) / 3.0;
      colour = Eigen::Vector3d(colours[3 * g], colours[3 * g + 1], colours[3 * g + 2]);
    }
    if ((centre.array() > box_min.array() + margin).all() && (centre.array() < box_max.array() - margin).all()) {
      ++inside;
      EXPECT_TRUE(orange(colour)) << "triangle " << t << " inside the box has colour " << colour.transpose();
    } else if ((centre.array() < box_min.array() - margin).any() || (centre.array() > box_max.array() + margin).any()) {
      ++outside;
      EXPECT_TRUE(grey(colour)) << "triangle " << t << " outside the box has colour " << colour.transpose();
    }
  }
  EXPECT_GT(inside, 100u);
  EXPECT_GT(outside, 100u);

  // The .ply carries the blend's own part numbers, nothing of the solid-boundary parts.
  const TriangleMesh ply = read_mesh(dir / "s.ply");
  for (const int part : ply.parts) {
    EXPECT_TRUE(part == part_number(Part::BlendSpline) || part == part_number(Part::BlendPrimitive)) << part;
  }
}

TEST(BlendCli, ExampleScenesMeshClosed) {
  test_support::TemporaryDirectory dir;
  for (const char* name : {"scene-cylinder-intersection", "scene-two-tori"}) {
    const auto r = test_support::run_cli(std::string("blend ") + VOLSPLINE_SOURCE_DIR + "/examples/scenes/" + name + ".json -o " +
                                     (dir / "out.stl").string() + " --stats " + (dir / "s.json").string(),
                                 dir.path());
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(nlohmann::json::parse(read_file(dir / "s.json"))["closed"].get<bool>()) << name;
  }
}

TEST(BlendCli, BadScenesExitWithTwoAndSayWhere) {
  test_support::TemporaryDirectory dir;
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
    const auto r = test_support::run_cli("blend " + (dir / "bad.json").string() + " -o " + (dir / "out.ply").string(), dir.path());
    EXPECT_EQ(r.code, 2) << text;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
  }
  write_text(dir / "ok.json", kSphere);
  EXPECT_EQ(test_support::run_cli("blend " + (dir / "ok.json").string() + " -o out.xyz", dir.path()).code, 2);
  EXPECT_EQ(test_support::run_cli("blend " + (dir / "ok.json").string() + " -o out.ply --method magic", dir.path()).code, 2);
  EXPECT_EQ(test_support::run_cli("blend " + (dir / "ok.json").string() + " -o out.ply --project", dir.path()).code, 2);
  EXPECT_EQ(test_support::run_cli("blend " + (dir / "missing.json").string() + " -o out.ply", dir.path()).code, 2);
}

}  // namespace
}  // namespace volspline
