// `volspline view` end to end: every kind of probe gives a picture that shows something, files
// appear together or not at all, bad input exits 2 naming the problem.
#include <gtest/gtest.h>

#include <set>
#include <stb_image.h>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

using test_support::run_cli;

const std::string kTorus = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/torus-temperature.json";

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

Picture load_png(const std::filesystem::path& path) {
  const std::string bytes = read_file(path);
  Picture p;
  int channels = 0;
  std::uint8_t* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                                             &p.width, &p.height, &channels, 4);
  EXPECT_NE(data, nullptr) << path;
  if (data) p.rgba.assign(data, data + 4 * std::size_t(p.width) * p.height);
  stbi_image_free(data);
  return p;
}

// Not blank, not one colour, and the object (pixels unlike the grey backdrop) covers a sensible
// share of the frame.
void expect_sensible_picture(const std::filesystem::path& path, int width, int height) {
  const Picture p = load_png(path);
  ASSERT_EQ(p.width, width);
  ASSERT_EQ(p.height, height);
  std::set<std::uint32_t> colours;
  std::size_t object = 0;
  for (std::size_t i = 0; i < p.rgba.size(); i += 4) {
    const int r = p.rgba[i], g = p.rgba[i + 1], b = p.rgba[i + 2];
    colours.insert(std::uint32_t(r) << 16 | g << 8 | b);
    // The backdrop is a light grey gradient: near-equal channels, all above 195.
    const bool backdrop = std::max({r, g, b}) - std::min({r, g, b}) < 12 && std::min({r, g, b}) > 195;
    object += !backdrop;
  }
  EXPECT_GT(colours.size(), 50u) << path;
  const double share = double(object) / (double(width) * height);
  EXPECT_GT(share, 0.05) << path;
  EXPECT_LT(share, 0.95) << path;
}

TEST(ViewCli, EveryProbeGivesASensiblePicture) {
  test_support::TemporaryDirectory dir;
  const std::vector<std::string> probes{"",
                                        "--iso w:4 --color w",
                                        "--iso u:3 --iso v:2",
                                        "--through 0.5,0.3,0.6 --color jacobian",
                                        "--slices z:3 --color temperature",
                                        "--plane 1,1,0,0.5",
                                        "--core 0,2.5,0.2 --color u",
                                        "--core 0.5,2.8,0.2 --cutaway --color temperature",
                                        "--plane 1,0,0.4,0.3 --cutaway",
                                        "--paddlewheel z:4 --color temperature --range 0,100",
                                        "--paddlewheel x:3@0,2.5,0 --faces --camera 0,-1,-0.3"};
  for (std::size_t i = 0; i < probes.size(); ++i) {
    std::string name = "v";  // (not "v" + std::to_string(i): GCC 12 warns falsely, -Wrestrict)
    name += std::to_string(i) + ".png";
    const auto png = dir.path() / name;
    const auto r = run_cli("view " + kTorus + " -o " + png.string() + " --size 240,180 --resolution 12 " + probes[i], dir.path());
    ASSERT_EQ(r.code, 0) << probes[i] << "\n" << r.err;
    expect_sensible_picture(png, 240, 180);
  }
}

TEST(ViewCli, MeshCarriesTheFieldAndSlicesLieInTheirPlanes) {
  test_support::TemporaryDirectory dir;
  const auto png = dir.path() / "s.png", ply = dir.path() / "s.ply", glb = dir.path() / "s.glb";
  auto r = run_cli("view " + kTorus + " -o " + png.string() + " --slices x:2 --color temperature --mesh " + ply.string() +
                       " --size 200,150",
                   dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string bytes = read_file(ply);
  EXPECT_NE(bytes.find("property double temperature\n"), std::string::npos);
  const TriangleMesh mesh = read_mesh(ply);
  ASSERT_GT(mesh.num_triangles(), 100u);
  // The torus spans x in [-4, 4]: two slices at x = -4/3 and 4/3.
  for (const auto& p : mesh.positions) EXPECT_NEAR(std::abs(p.x()), 4.0 / 3, 1e-12);
  r = run_cli("view " + kTorus + " -o " + png.string() + " --iso w:2 --color jacobian --mesh " + glb.string() + " --size 200,150",
              dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(glb).substr(0, 4), "glTF");
  // A field named like a PLY coordinate (--color u) is written as color_u beside u.
  r = run_cli("view " + kTorus + " -o " + png.string() + " --iso w:2 --color u --mesh " + ply.string() + " --size 200,150", dir.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(read_file(ply).find("property double u\nproperty double v\nproperty double w\nproperty double color_u\n"), std::string::npos);
}

TEST(ViewCli, BadInputExitsTwoAndWritesNothing) {
  test_support::TemporaryDirectory dir;
  const auto png = (dir.path() / "x.png").string(), mesh = (dir.path() / "x.ply").string();
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--iso q:3", "--iso"},
      {"--iso u:0", "--iso"},
      {"--slices x", "--slices"},
      {"--through 0.5,0.5,7", "outside the domain"},
      {"--through 0.5,0.5", "--through"},
      {"--plane 0,0,0,1", "--plane"},
      {"--paddlewheel z:3@1,2", "--paddlewheel"},
      {"--color density", "temperature"},
      {"--camera 0,0,0", "--camera"},
      {"--range 5,1", "--range"},
      {"--size 10,10", "--size"},
      {"--cutaway --slices x:2", "--cutaway"},
  };
  for (const auto& [args, expected] : cases) {
    const auto r = run_cli("view " + kTorus + " -o " + png + " --mesh " + mesh + " " + args, dir.path());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(png)) << args;
    EXPECT_FALSE(std::filesystem::exists(mesh)) << args;
  }
  EXPECT_EQ(run_cli("view " + kTorus + " -o " + (dir.path() / "x.jpg").string(), dir.path()).code, 2);
  EXPECT_EQ(run_cli("view " + (dir.path() / "missing.json").string() + " -o " + png, dir.path()).code, 2);
  const auto curve = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/half-circle-curve.json";
  const auto r = run_cli("view " + curve + " -o " + png, dir.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no volume"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace volspline
