// The command line end to end: outputs, exit codes, error messages and files left behind.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/example_solids.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/web/interactive_page.h"

namespace volspline {
namespace {

using Result = test_support::CliResult;

Result run(const std::string& args, const std::filesystem::path& dir) { return test_support::run_cli(args, dir); }

class Cli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::filesystem::path dir() const { return tmp.path(); }
  std::string write(const std::string& name, const std::string& text) {
    const auto p = dir() / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string model(const std::string& name, const BSplineVolume& v) {
    Model m;
    m.objects.push_back({"", false, v, nullptr});
    const auto p = dir() / name;
    write_model(m, p);
    return p.string();
  }
  // Everything in the folder except our captured streams and the named inputs.
  std::vector<std::string> outputs(const std::vector<std::string>& inputs) const {
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir())) {
      const auto name = e.path().filename().string();
      if (name == "stdout.txt" || name == "stderr.txt") continue;
      if (std::find(inputs.begin(), inputs.end(), name) != inputs.end()) continue;
      files.push_back(name);
    }
    return files;
  }
};

std::vector<double> numbers(const std::string& line) {
  std::istringstream in(line);
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

TEST_F(Cli, HelpOnEverySubcommand) {
  for (const char* sub : {"", "info", "eval", "convert", "faces", "demo", "make", "make ball", "make sweep", "ffd", "lattice"}) {
    const auto r = run(std::string(sub) + " --help", dir());
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
  EXPECT_EQ(run("", dir()).code, 2);            // a subcommand is required
  EXPECT_EQ(run("no-such-command", dir()).code, 2);
}

TEST_F(Cli, EvalPrintsPointsAndDerivativesWith17Digits) {
  const auto v = half_cylinder_shell(1.0, 2.0, 3.0);
  const auto path = model("shell.json", v);
  const auto r = run("eval " + path + " --at 0.25,0.5,0.75 --at 1,1,1 --derivatives", dir());
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  const auto a = numbers(line);
  ASSERT_EQ(a.size(), 12u);
  const auto expected = v.evaluate_derivatives({0.25, 0.5, 0.75}, 1);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(a[i], expected[i]) << i;  // 17 digits: exact
  EXPECT_NEAR(std::hypot(a[0], a[1]), 1.25, 1e-12);
}

TEST_F(Cli, EvalGridIsUFastestWithEndpoints) {
  const auto v = bent_tricubic_volume();
  const auto path = model("bent.json", v);
  const auto r = run("eval " + path + " --grid 3,2,2", dir());
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  int n = 0;
  while (std::getline(lines, line)) {
    const double u = (n % 3) / 2.0, vv = (n / 3) % 2, w = n / 6;
    const auto x = v.evaluate({u, vv, w});
    const auto got = numbers(line);
    ASSERT_EQ(got.size(), 3u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[static_cast<std::size_t>(c)], x[c], 1e-14 * (1 + std::abs(x[c])));
    ++n;
  }
  EXPECT_EQ(n, 12);
}

TEST_F(Cli, EvalOutsideTheDomainIsBadInput) {
  const auto path = model("bent.json", bent_tricubic_volume());
  const auto r = run("eval " + path + " --at 0.5,0.5,0.5 --at 0.5,1.5,0", dir());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--at[1]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("outside the domain"), std::string::npos) << r.err;
  EXPECT_EQ(run("eval " + path + " --at 0.5,0.5", dir()).code, 2);
  EXPECT_EQ(run("eval " + path + " --at 0.5,x,0.5", dir()).code, 2);
  EXPECT_EQ(run("eval " + path + " --at 0.5,0.5,0.5 --object 3", dir()).code, 2);
}

TEST_F(Cli, InfoJsonDescribesTheObjects) {
  const auto path = model("shell.json", half_cylinder_shell(1.0, 2.0, 1.0));
  const auto r = run("info --json " + path, dir());
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& o = j["objects"][0];
  EXPECT_EQ(o["degree"], nlohmann::json({1, 2, 1}));
  EXPECT_EQ(o["control_points"], nlohmann::json({2, 3, 2}));
  EXPECT_TRUE(o["rational"].get<bool>());
  EXPECT_EQ(o["points_at_infinity"].get<int>(), 4);
  // the box of the half shell is [-2, 2] x [0, 2] x [0, 1], up to the subdivided net
  EXPECT_NEAR(o["bounding_box"]["max"][1].get<double>(), 2.0, 1e-2);
  EXPECT_NEAR(o["bounding_box"]["min"][0].get<double>(), -2.0, 1e-12);
  EXPECT_EQ(run("info " + path, dir()).code, 0);
}

TEST_F(Cli, ConvertKeepsTheGeometry) {
  const auto v = bent_tricubic_volume();
  const auto path = model("bent.json", v);
  const auto out = (dir() / "pieces.json").string();
  const auto r = run("convert " + path + " -o " + out + " --insert-knots w:0.3,0.6 --elevate u:1 --bezier", dir());
  ASSERT_EQ(r.code, 0) << r.err;
  const Model m = read_model(out);
  // cells: u 3 spans, v 2, w 1 + 2 inserted
  ASSERT_EQ(m.objects.size(), 3u * 2u * 3u);
  EXPECT_EQ(object_type_name(m.objects[0]), "bezier_volume");
  // cell 0 is [0,1/3] x [0,1/2] x [0,0.3] of the original, reparameterised to [0,1]^3
  const auto& piece = std::get<BSplineVolume>(m.objects[0].spline);
  EXPECT_EQ(piece.degrees()[0], 4);
  for (double s : {0.0, 0.3, 0.8}) {
    const auto a = piece.evaluate({s, s, s});
    const auto b = v.evaluate({s / 3.0, s / 2.0, 0.3 * s});
    EXPECT_LT((a - b).norm(), 1e-12);
  }
  EXPECT_EQ(run("convert " + path + " -o " + out + " --elevate q:1", dir()).code, 2);
  EXPECT_EQ(run("convert " + path + " -o " + out + " --insert-knots u:7", dir()).code, 2);
}

TEST_F(Cli, FacesWritesAClosedMeshAndAPicture) {
  const auto path = model("twisted.json", twisted_volume(0.25));
  const auto ply = (dir() / "faces.ply").string(), png = (dir() / "faces.png").string();
  const auto r = run("faces " + path + " -o " + ply + " --png " + png + " --resolution 8", dir());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("closed"), std::string::npos);
  EXPECT_EQ(r.out.find("not closed"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(ply), 100u);
  std::ifstream in(png, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST_F(Cli, BadModelsGiveTheJsonPathAndExitCode2AndNoOutput) {
  const std::string base = R"({"volspline": 1, "objects": [{"type": "bspline_volume", "degree": [1, 1, 1],
      "knots": [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, KNOT, 1]], "control_points": POINTS WEIGHTS}]})";
  const std::string cube = "[[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]]";
  auto make = [&](std::string knot, std::string points, std::string weights) {
    std::string s = base;
    s.replace(s.find("KNOT"), 4, knot);
    s.replace(s.find("POINTS"), 6, points);
    s.replace(s.find("WEIGHTS"), 7, weights);
    return s;
  };
  struct Case {
    std::string name, text, expect;
  };
  const std::vector<Case> cases{
      {"not-json.json", "{\"volspline\": 1, \"objects\": [", "line"},
      {"decreasing.json", make("1.5", cube, ""), "objects[0].knots[2][3]"},
      {"count.json", make("1", "[[0,0,0],[1,0,0]]", ""), "objects[0].control_points"},
      {"negative-weight.json", make("1", cube, ", \"weights\": [1,1,1,-1,1,1,1,1]"), "objects[0].weights[3]"},
      {"infinite.json", make("1", "[[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1e999],[1,1,1]]", ""),
       "objects[0].control_points[6][2]"},
      {"empty.json", R"({"volspline": 1, "objects": []})", "objects"},
      {"multiplicity.json", make("0", cube, ""),
       "objects[0].knots[2][2]"},
      {"degree.json", R"({"volspline": 1, "objects": [{"type": "bezier_curve", "degree": [0], "control_points": [[0,0,0]]}]})",
       "objects[0].degree[0]"},
      {"nan.json", make("1", "[[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,NaN],[1,1,1]]", ""), "line"},
  };
  for (const auto& c : cases) {
    const auto in = write(c.name, c.text);
    for (const std::string& cmd : {"info " + in, "eval " + in + " --at 0,0,0", "faces " + in + " -o " + (dir() / "x.ply").string(),
                                  "convert " + in + " -o " + (dir() / "x.json").string()}) {
      const auto r = run(cmd, dir());
      EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
      EXPECT_NE(r.err.find(c.name), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << ": " << r.err;
      EXPECT_TRUE(r.out.empty()) << r.out;
    }
  }
  std::vector<std::string> inputs;
  for (const auto& c : cases) inputs.push_back(c.name);
  EXPECT_TRUE(outputs(inputs).empty());
  const auto missing = run("info " + (dir() / "missing.json").string(), dir());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("missing.json"), std::string::npos);
}

TEST_F(Cli, UnwritableOutputLeavesNothingBehind) {
  const auto path = model("bent.json", bent_tricubic_volume());
  const auto r = run("faces " + path + " -o " + (dir() / "no-such-dir" / "f.ply").string(), dir());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(run("faces " + path + " -o " + (dir() / "f.xyz").string(), dir()).code, 2);
  // the picture fails after the mesh is made: neither file may remain
  const auto ply = (dir() / "f.ply").string();
  EXPECT_EQ(run("faces " + path + " -o " + ply + " --png " + (dir() / "no-such-dir" / "p.png").string(), dir()).code, 2);
  EXPECT_EQ(run("faces " + path + " -o " + ply + " --png " + (dir() / "p.png").string() + " --size 100000,100000", dir()).code, 2);
  EXPECT_EQ(outputs({"bent.json"}).size(), 0u);
  EXPECT_EQ(run("demo --out " + path + "/sub", dir()).code, 2);  // the parent is a file
  EXPECT_EQ(run("eval " + path + " --grid 100000,100000,100000", dir()).code, 2);
}

TEST_F(Cli, FacesNeedPointsInSpace) {
  const auto in = write("planar.json", R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [1, 1, 1],
      "control_points": [[0,0],[1,0],[0,1],[1,1],[0,0],[1,0],[0,1],[1,1]]}]})");
  const auto r = run("faces " + in + " -o " + (dir() / "f.ply").string(), dir());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("planar.json: objects[0].control_points"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir() / "f.ply"));
}

TEST_F(Cli, OutsideTheDomainNamesFileObjectAndPoint) {
  const auto path = model("bent.json", bent_tricubic_volume());
  const auto r = run("eval " + path + " --at 0.5,0.5,1.5", dir());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("bent.json: objects[0] at --at[0]"), std::string::npos) << r.err;
  EXPECT_EQ(run("eval " + path + " --at +0.5,0.5,0.25", dir()).code, 0);
}

// The text of an HTML page's element content back to plain text (the escapes Gallery writes).
std::string html_unescape(std::string text) {
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}}) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  }
  return text;
}

// One run of the demo (slow under sanitizers) for all its checks: every example's files, then the
// gallery page.
TEST_F(Cli, DemoWritesEveryExampleAndItsGallery) {
  // The demo folder stays for the browser test of its interactive pages (tests/CMakeLists.txt:
  // WebPages.OpenInChromium requires this test as its fixture).
  const std::filesystem::path out = VOLSPLINE_DEMO_GALLERY_DIR;
  std::filesystem::remove_all(out);
  // Hua-He-Qin Figs. 5 and 6 read the repository's examples and the shared data (Fig. 6 is skipped
  // where that is absent).
  const std::filesystem::path data = std::filesystem::path(VOLSPLINE_SOURCE_DIR) / ".." / "shared" / "data";
  const auto demo = run("demo --out " + out.string() + " --examples " + VOLSPLINE_SOURCE_DIR + "/examples --data " + data.string(), dir());
  ASSERT_EQ(demo.code, 0) << demo.err;

  for (const char* name : {"bent-tricubic", "twisted", "half-cylinder-shell", "ball", "torus-segment", "hollow-cylinder",
                           "frustum", "half-torus", "hyperboloid", "half-cylinder-sweep", "swept-patch", "twisted-loft",
                           "curved-loft"})
    for (const char* ext : {".json", ".ply", ".png"}) EXPECT_TRUE(std::filesystem::exists(out / (std::string(name) + ext))) << name << ext;
  for (const char* file : {"examples/ffd-bent-bar-lattice.json", "ffd-bent-bar.ply", "ffd-bent-bar.png"})
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  for (const char* file : {"simplex-torus-sm.json", "simplex-torus-sm-xray.png", "simplex-torus-sm-iso.png", "examples/torus-surface.off"})
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  if (std::filesystem::exists(data / "volumes" / "bunny00.off")) {
    for (const char* file : {"simplex-bunny.json", "simplex-bunny-xray.png", "simplex-bunny-iso.png", "simplex-bunny-slice.png"})
      EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  } else {
    EXPECT_NE(demo.out.find("simplex-bunny: skipped"), std::string::npos) << demo.out;
  }
  // the demo's rational model has points at infinity and reads back
  const Model m = read_model(out / "half-cylinder-shell.json");
  const auto& v = std::get<BSplineVolume>(m.objects[0].spline);
  EXPECT_TRUE(std::count(v.weights().begin(), v.weights().end(), 0.0) > 0);

  const std::string html = read_file(out / "index.html");
  std::set<std::string> linked;
  const std::regex image("<img src=\"([^\"]+)\""), source("src=\"([^\"]+)\"");
  for (std::sregex_iterator it(html.begin(), html.end(), image), end; it != end; ++it)
    linked.insert((*it)[1].str());
  std::set<std::string> pictures;
  for (const auto& e : std::filesystem::directory_iterator(out))
    if (e.path().extension() == ".png") pictures.insert(e.path().filename().string());
  EXPECT_EQ(linked, pictures);  // every picture shown, every link to a picture that exists
  EXPECT_GE(pictures.size(), 30u);

  // Each section's title, pictures and command.
  std::map<std::string, std::pair<std::vector<std::string>, std::string>> entries;
  const std::regex section("<h2>([^<]*)</h2>[\\s\\S]*?<div[^>]*>([\\s\\S]*?)</div>\n<pre><code>([^<]*)</code>");
  for (std::sregex_iterator it(html.begin(), html.end(), section), end; it != end; ++it) {
    std::vector<std::string> srcs;
    const std::string div = (*it)[2].str();
    for (std::sregex_iterator p(div.begin(), div.end(), source); p != end; ++p) srcs.push_back((*p)[1].str());
    entries[(*it)[1].str()] = {srcs, html_unescape((*it)[3].str())};
  }
  // Every picture belongs to one entry; an entry may show several side by side (a superset and
  // its trimmed result).
  std::size_t shown = 0;
  for (const auto& [title, entry] : entries) shown += entry.first.size();
  EXPECT_EQ(shown, pictures.size());
  EXPECT_LE(entries.size(), pictures.size());
  // Every entry shows the commands that make it from files (not `demo --only`).
  for (const auto& [title, entry] : entries) {
    EXPECT_EQ(entry.second.rfind("volspline ", 0), 0u) << title << ": " << entry.second;
    EXPECT_EQ(entry.second.find("volspline demo"), std::string::npos) << title << ": " << entry.second;
  }
  // Every page the gallery links exists, and the thumbnails of an entry with a page open it.
  const std::regex page_link("<a href=\"([^\"]+\\.html)\">");
  std::size_t pages = 0;
  for (std::sregex_iterator it(html.begin(), html.end(), page_link), end; it != end; ++it, ++pages)
    EXPECT_TRUE(std::filesystem::exists(out / (*it)[1].str())) << (*it)[1].str();
  if (interactive_pages_available()) {
    EXPECT_GE(pages, 30u);
  }
  // The solids built in code that no `make` kind builds are files of examples/: the same bytes.
  for (const char* name : {"bent-tricubic", "twisted", "half-cylinder-shell", "ffd-bent-bar-lattice", "simplex-tetrahedron-cubic",
                           "scenes/peters-wittman-fig1", "scenes/peters-wittman-fig2", "scenes/peters-wittman-fig3",
                           "scenes/peters-wittman-fig4"})
    EXPECT_EQ(read_file(out / "examples" / (std::string(name) + ".json")),
              read_file(std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / (std::string(name) + ".json")))
        << name;

  // A few commands run in an empty folder holding the demo's examples/ write the same pictures,
  // byte for byte: `make` + `faces`, `make` + `boundary`, `make` + `faces` + `ffd`, `blend` with
  // --show, and the two `sweep-envelope` runs (superset and trimmed) of a swept solid.
  const auto again = dir() / "again";
  std::filesystem::create_directories(again);
  std::filesystem::copy(out / "examples", again / "examples", std::filesystem::copy_options::recursive);
  for (const char* title : {"ball", "bent-tricubic", "swept-patch-boundary", "ffd-bent-bar", "blend-fig2a", "blend-fig4b", "sweep-fig5"}) {
    ASSERT_TRUE(entries.contains(title)) << title;
    const auto& [srcs, command] = entries[title];
    const std::string line = std::regex_replace(command, std::regex("(^|&& )volspline "), std::string("$1") + VOLSPLINE_CLI + " ");
    ASSERT_EQ(std::system(("cd " + again.string() + " && " + line + " >/dev/null").c_str()), 0) << line;
    for (const auto& picture : srcs) EXPECT_EQ(read_file(again / picture), read_file(out / picture)) << picture;
    std::smatch page;
    if (std::regex_search(line, page, std::regex("--html (\\S+)"))) {
      EXPECT_TRUE(std::filesystem::exists(again / page[1].str())) << line;
    }
  }
  // A `view` command, run in the demo folder where its models are, redraws its picture exactly.
  {
    ASSERT_TRUE(entries.contains("Core section"));
    const auto& [srcs, command] = entries["Core section"];
    ASSERT_EQ(srcs.size(), 1u);
    const std::string before = read_file(out / srcs[0]);
    std::filesystem::remove(out / srcs[0]);
    const std::string line = std::regex_replace(command, std::regex("^volspline "), std::string(VOLSPLINE_CLI) + " ");
    ASSERT_EQ(std::system(("cd " + out.string() + " && " + line + " >/dev/null").c_str()), 0) << line;
    EXPECT_EQ(read_file(out / srcs[0]), before);
  }
  // Hua-He-Qin Fig. 5: `make simplex-spline` from the copied examples/ and `xray`, run in the demo
  // folder, redraw the X-ray (not byte for byte: Mesh_3's result can differ by a tetrahedron
  // between runs).
  {
    ASSERT_TRUE(entries.contains("simplex-torus-sm-xray"));
    const auto& [srcs, command] = entries["simplex-torus-sm-xray"];
    ASSERT_EQ(srcs.size(), 1u);
    std::filesystem::remove(out / srcs[0]);
    const std::string line = std::regex_replace(command, std::regex("(^|&& )volspline "), std::string("$1") + VOLSPLINE_CLI + " ");
    ASSERT_EQ(std::system(("cd " + out.string() + " && " + line + " >/dev/null").c_str()), 0) << line;
    EXPECT_TRUE(std::filesystem::exists(out / srcs[0]));
  }
  // Fitting (issue 14): the formula's isosurface (`data`) and a fit with its slices (`fit` +
  // `view`), run in the demo folder, redraw their pictures byte for byte; fire_ug's three
  // pictures where the shared data is.
  for (const char* title : {"fit-marschner-lobb-truth", "fit-jump-aligned-knots"}) {
    ASSERT_TRUE(entries.contains(title)) << title;
    const auto& [srcs, command] = entries[title];
    ASSERT_EQ(srcs.size(), 1u);
    const std::string before = read_file(out / srcs[0]);
    std::filesystem::remove(out / srcs[0]);
    const std::string line = std::regex_replace(command, std::regex("(^|&& )volspline "), std::string("$1") + VOLSPLINE_CLI + " ");
    ASSERT_EQ(std::system(("cd " + out.string() + " && " + line + " >/dev/null").c_str()), 0) << line;
    EXPECT_EQ(read_file(out / srcs[0]), before) << title;
  }
  for (const char* title : {"fit-marschner-lobb-data", "fit-marschner-lobb-fit", "fit-jump-fixed-knots"}) EXPECT_TRUE(entries.contains(title)) << title;
  if (std::filesystem::exists(data / "volumes" / "fire_ug.vtu")) {
    for (const char* title : {"fit-fire-data", "fit-fire-xray", "fit-fire-iso"}) EXPECT_TRUE(entries.contains(title)) << title;
  } else {
    EXPECT_NE(demo.out.find("fit-fire: skipped"), std::string::npos) << demo.out;
  }
  EXPECT_FALSE(std::filesystem::exists(again / "index.html"));  // --only leaves the gallery alone
  const auto r = run("demo --only no-such-example --out " + again.string(), dir());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--only"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("twisted-loft-boundary"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace volspline
