// The interactive page (web/interactive_page.h): what it carries is read back from the HTML
// independently — the page's JSON parsed by nlohmann, each base64 glTF decoded here and compared
// with glb_bytes of the part's triangles — and nothing in the data can end the script early.
// The browser side is tests/web/pages_in_browser.mjs.
#include "volspline/web/interactive_page.h"

#include <gtest/gtest.h>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/colormap.h"

namespace volspline {
namespace {

// RFC 4648 decoding, written independently of the page's encoder.
std::string page_test_base64_decode(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned buffer = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    const auto value = alphabet.find(c);
    EXPECT_NE(value, std::string::npos) << c;
    buffer = (buffer << 6) | static_cast<unsigned>(value);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((buffer >> bits) & 0xFF);
    }
  }
  return out;
}

// The JSON of the page's data script.
nlohmann::json page_test_data(const std::string& html) {
  const std::string open = "<script id=\"volspline-page\" type=\"application/json\">";
  const auto begin = html.find(open);
  EXPECT_NE(begin, std::string::npos);
  const auto end = html.find("</script>", begin);
  return nlohmann::json::parse(html.substr(begin + open.size(), end - begin - open.size()));
}

// Two triangles of face u_min and one of the Jacobian-zero surface; vertex 2 is shared.
TriangleMesh page_test_mesh() {
  TriangleMesh m;
  for (int i = 0; i < 5; ++i) m.add_vertex(Eigen::Vector3d(i, i * i, 1.0 - i), Eigen::Vector3d::Zero());
  m.add_triangle(0, 1, 2, Part::UMin);
  m.add_triangle(2, 3, 4, Part::JacobianZero);
  m.add_triangle(0, 2, 4, Part::UMin);
  return m;
}

class InteractivePageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!interactive_pages_available()) GTEST_SKIP() << interactive_pages_unavailable_reason();
  }
};

TEST_F(InteractivePageTest, CarriesEveryPartAsItsOwnGltfAndTheViewerInline) {
  InteractivePage page;
  page.title = "a <test> & more";
  page.mesh = page_test_mesh();
  page.info = {{"degree", {3, 3, 3}}};
  const std::string html = interactive_page_html(page);
  EXPECT_NE(html.find("<title>a &lt;test&gt; &amp; more</title>"), std::string::npos);
  const nlohmann::json data = page_test_data(html);
  EXPECT_EQ(data["title"], page.title);
  EXPECT_EQ(data["info"], page.info);
  ASSERT_EQ(data["parts"].size(), 2u);
  EXPECT_EQ(data["parts"][0]["name"], "u_min");
  EXPECT_EQ(data["parts"][0]["triangles"], 2);
  EXPECT_EQ(data["parts"][1]["name"], "jacobian_zero");
  EXPECT_EQ(data["parts"][1]["number"], 6);
  EXPECT_NEAR(data["parts"][1]["srgb"][0].get<double>(), part_color(Part::JacobianZero).x(), 1e-15);
  // The part's triangles alone, vertices renumbered in order of use, are what the glTF holds.
  TriangleMesh zero;
  for (const int v : {2, 3, 4}) zero.add_vertex(page.mesh.positions[static_cast<std::size_t>(v)], Eigen::Vector3d::Zero());
  zero.add_triangle(0, 1, 2, Part::JacobianZero);
  EXPECT_EQ(page_test_base64_decode(data["parts"][1]["glb"]), glb_bytes(zero));
  // Two scripts, both inline: the data and the viewer; nothing loaded from elsewhere (the browser
  // test watches the requests themselves).
  std::size_t scripts = 0;
  for (auto at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1)) ++scripts;
  EXPECT_EQ(scripts, 2u);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_NE(html.find("Three.js Authors"), std::string::npos);  // the bundled licence notice
}

TEST_F(InteractivePageTest, TextCannotEndTheScriptEarly) {
  InteractivePage page;
  page.mesh = page_test_mesh();
  page.title = "</script><script>alert(1)</script>";
  page.info = {{"note", "<!-- </SCRIPT> -->"}};
  page.command = "volspline faces 'a</script>.json'";
  const std::string html = interactive_page_html(page);
  // The data script ends where the page's own "</script>" is: its JSON parses whole and holds the
  // texts as given.
  const nlohmann::json data = page_test_data(html);
  EXPECT_EQ(data["title"], page.title);
  EXPECT_EQ(data["info"], page.info);
  EXPECT_EQ(data["command"], page.command);
}

TEST_F(InteractivePageTest, ColoursByAScalarFieldWithItsBar) {
  InteractivePage page;
  page.mesh = page_test_mesh();
  page.vertex_scalars = {0, 1, 2, 3, 4};
  page.color_bar = ColorBar{Colormap::Diverging, 0, 4, "jacobian"};
  const nlohmann::json data = page_test_data(interactive_page_html(page));
  ASSERT_TRUE(data["color_bar"].is_object());
  EXPECT_EQ(data["color_bar"]["title"], "jacobian");
  EXPECT_EQ(data["color_bar"]["stops"].size(), 11u);
  // The middle stop is the map's middle: white for the diverging map.
  const Eigen::Vector3d middle = colormap_color(Colormap::Diverging, 0.5);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(data["color_bar"]["stops"][5][c].get<double>(), middle[c], 1e-15);
  // Colours are the map at (s - min) / (max - min): vertices 2, 3, 4 of the Jacobian-zero part.
  TriangleMesh zero;
  for (const int v : {2, 3, 4}) zero.add_vertex(page.mesh.positions[static_cast<std::size_t>(v)], Eigen::Vector3d::Zero());
  zero.add_triangle(0, 1, 2, Part::JacobianZero);
  const std::vector<Eigen::Vector3d> colors{colormap_color(Colormap::Diverging, 0.5), colormap_color(Colormap::Diverging, 0.75),
                                            colormap_color(Colormap::Diverging, 1.0)};
  EXPECT_EQ(page_test_base64_decode(data["parts"][1]["glb"]), glb_bytes(zero, colors));
}

TEST_F(InteractivePageTest, RefusesInconsistentProbesAndColours) {
  InteractivePage page;
  page.mesh = page_test_mesh();
  page.probes.push_back({"u", "u", {0.0, 1.0}, {page_test_mesh()}, 0, true, {}});
  EXPECT_THROW(interactive_page_html(page), InvalidInput);  // two values, one mesh
  page.probes[0].meshes.push_back(page_test_mesh());
  page.probes[0].initial = 2;
  EXPECT_THROW(interactive_page_html(page), InvalidInput);
  page.probes[0].initial = 1;
  EXPECT_NO_THROW(interactive_page_html(page));
  page.probe_point = PageProbePoint{{"u", "v", "w"}, {}};
  EXPECT_THROW(interactive_page_html(page), InvalidInput);  // no probes v and w
  page.probe_point.reset();
  page.vertex_scalars = {1.0};
  EXPECT_THROW(interactive_page_html(page), InvalidInput);  // not one per vertex, no bar
  page.vertex_scalars.clear();
  page.vertex_colors = {Eigen::Vector3d(2, 0, 0)};
  EXPECT_THROW(interactive_page_html(page), InvalidInput);
}

TEST(InteractivePageAvailability, AReasonExactlyWhenUnavailable) {
  EXPECT_EQ(interactive_pages_available(), interactive_pages_unavailable_reason().empty());
  if (!interactive_pages_available()) {
    InteractivePage page;
    EXPECT_THROW(interactive_page_html(page), InvalidInput);
  }
}

}  // namespace
}  // namespace volspline
