// `--html` on faces, boundary, view, blend, sweep-envelope and ffd: the page carries the triangles the
// mesh file has, part by part, the model's description, the probes where there are volumes and
// the colour bar where the command colours by a field; a bad name or a build without the viewer
// exits 2 with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/web/interactive_page.h"

namespace volspline {
namespace {

class HtmlPagesCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }
  static std::string example(const std::string& name) { return (std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / name).string(); }
  // The data of a written page.
  nlohmann::json page_data(const std::string& name) const {
    std::ifstream in(path(name));
    std::stringstream s;
    s << in.rdbuf();
    const std::string html = s.str();
    const std::string open = "<script id=\"volspline-page\" type=\"application/json\">";
    const auto begin = html.find(open);
    EXPECT_NE(begin, std::string::npos) << name;
    const auto end = html.find("</script>", begin);
    return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
  }
  // Triangles per part name in the page, and in the mesh file.
  static std::map<std::string, long> page_triangles(const nlohmann::json& data) {
    std::map<std::string, long> count;
    for (const auto& part : data["parts"]) count[part["name"].get<std::string>()] = part["triangles"].get<long>();
    return count;
  }
  static std::map<std::string, long> mesh_triangles(const TriangleMesh& mesh) {
    std::map<std::string, long> count;
    for (const int p : mesh.parts) ++count[part_name(p)];
    return count;
  }
};

TEST_F(HtmlPagesCli, FacesBoundaryViewBlendAndEnvelopeWriteTheirPages) {
  if (!interactive_pages_available()) GTEST_SKIP() << interactive_pages_unavailable_reason();
  auto r = test_support::run_cli("faces " + example("bent-tricubic.json") + " -o " + path("f.ply") + " --resolution 8 --html " +
                                     path("f.html"),
                                 tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json data = page_data("f.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("f.ply"))));
  EXPECT_EQ(data["info"]["objects"][0]["degree"], nlohmann::json({3, 3, 3}));
  EXPECT_TRUE(data["info"]["faces"]["closed"].get<bool>());
  ASSERT_EQ(data["probes"].size(), 4u);  // u, v, w and the slice
  EXPECT_EQ(data["probes"][0]["glbs"].size(), 9u);
  EXPECT_EQ(data["probe_points"]["points"].size(), 729u);
  EXPECT_NE(data["command"].get<std::string>().find("--html"), std::string::npos);

  r = test_support::run_cli("boundary " + example("twisted-loft.json") + " -o " + path("b.ply") + " --html " + path("b.html"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  data = page_data("b.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("b.ply"))));
  EXPECT_GT(page_triangles(data)["jacobian_zero"], 0);  // the twisted loft folds
  EXPECT_TRUE(data["info"]["boundary"].contains("cells_examined"));

  r = test_support::run_cli("view " + example("torus-temperature.json") + " -o " + path("v.png") +
                                " --slices x:3 --color temperature --mesh " + path("v.ply") + " --html " + path("v.html"),
                            tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  data = page_data("v.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("v.ply"))));
  ASSERT_TRUE(data["color_bar"].is_object());
  EXPECT_EQ(data["color_bar"]["title"], "temperature");
  EXPECT_LT(data["color_bar"]["min"].get<double>(), data["color_bar"]["max"].get<double>());
  // The slice probe cuts along the slices' normal, x.
  const auto& slice = data["probes"][3];
  EXPECT_EQ(slice["name"], "slice");

  r = test_support::run_cli("blend " + example("scenes/scene-two-tori.json") + " -o " + path("z.ply") + " --levels 1 --html " + path("z.html"),
                            tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  data = page_data("z.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("z.ply"))));
  EXPECT_TRUE(data["probes"].empty());
  EXPECT_TRUE(data["info"]["blend"].contains("closed"));

  r = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("e.ply") + " --html " + path("e.html"),
                            tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  data = page_data("e.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("e.ply"))));
  EXPECT_TRUE(data["info"]["envelope"]["objects"][0]["closed"].get<bool>());

  // ffd: the deformed mesh, with the lattice's description.
  r = test_support::run_cli("lattice " + path("f.ply") + " -o " + path("l.json") + " --degree 2,2,2", tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  r = test_support::run_cli("ffd " + path("l.json") + " " + path("f.ply") + " -o " + path("d.ply") + " --html " + path("d.html"), tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  data = page_data("d.html");
  EXPECT_EQ(page_triangles(data), mesh_triangles(read_mesh(path("d.ply"))));
  EXPECT_TRUE(data["info"]["lattice"].contains("objects"));
  // A model input gives a model, which has no page of its own here.
  r = test_support::run_cli("ffd " + path("l.json") + " " + example("bent-tricubic.json") + " -o " + path("m.json") + " --html " + path("m.html"),
                            tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--html"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("m.json")));
}

TEST_F(HtmlPagesCli, ABadNameOrNoViewerExitsTwoWithNothingWritten) {
  auto r = test_support::run_cli("faces " + example("bent-tricubic.json") + " -o " + path("f.ply") + " --html " + path("f.htm"), tmp.path());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--html"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(path("f.ply")));
  EXPECT_FALSE(std::filesystem::exists(path("f.htm")));
  if (!interactive_pages_available()) {
    r = test_support::run_cli("faces " + example("bent-tricubic.json") + " -o " + path("f.ply") + " --html " + path("f.html"), tmp.path());
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("install-web-deps"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("f.ply")));
  }
}

}  // namespace
}  // namespace volspline
