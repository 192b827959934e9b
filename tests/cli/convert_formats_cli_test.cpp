// volspline convert between formats: the geometry survives a chain of conversions through every
// format, --format overrides the extension, and bad files exit with 2 naming file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "support/exchange_support.h"
#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/io/model_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/io/vtk_xml.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {
namespace {

class ConvertFormats : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp / name).string(); }
  test_support::CliResult run(const std::string& args) const { return test_support::run_cli(args, tmp.path()); }
};

TEST_F(ConvertFormats, AChainThroughEveryFormatKeepsTheGeometry) {
  std::mt19937 rng(1);
  Model model = test_support::random_exchange_model(rng);
  for (auto& object : model.objects) object.name.clear();
  write_model(model, path("start.json"));
  ASSERT_EQ(run("convert " + path("start.json") + " -o " + path("a.xml")).code, 0);
  ASSERT_EQ(run("convert " + path("a.xml") + " -o " + path("b.itd")).code, 0);
  const auto last = run("convert " + path("b.itd") + " -o " + path("c.json"));
  ASSERT_EQ(last.code, 0) << last.err;
  EXPECT_NE(last.out.find("wrote"), std::string::npos);
  const Model back = read_model(path("c.json"));
  EXPECT_LE(test_support::max_model_difference(model, back, rng, false), 1e-12);
  // Every format reads what it wrote, also through the table.
  for (const ModelFormat& format : model_formats()) {
    const Model again = read_model_file(path("c.json"));
    const std::string file = path(std::string("d") + format.extension);
    write_model_file(again, file);
    const Model read = read_model_file(file);
    if (std::string(format.name) == "vtu") {
      std::size_t cells = 0;
      for (const auto& object : again.objects) visit_spline(object, "test", "", [&](const auto& s) { cells += bezier_pieces(s).size(); });
      EXPECT_EQ(read.objects.size(), cells);
    } else {
      EXPECT_LE(test_support::max_model_difference(again, read, rng, false), 1e-12) << format.name;
    }
  }
}

TEST_F(ConvertFormats, AttributesFollowKnotInsertionAndBezierSplitting) {
  std::mt19937 rng(2);
  Model model = test_support::random_exchange_model(rng);
  model.objects.erase(model.objects.begin(), model.objects.begin() + 4);  // the two volumes
  write_model(model, path("v.json"));
  const auto result = run("convert " + path("v.json") + " -o " + path("r.json") + " --insert-knots u:0.3,0.7 --elevate w:1");
  ASSERT_EQ(result.code, 0) << result.err;
  EXPECT_LE(test_support::max_model_difference(model, read_model(path("r.json")), rng, true), 1e-12);
}

TEST_F(ConvertFormats, FormatOptionOverridesTheExtension) {
  std::mt19937 rng(3);
  write_model(test_support::random_exchange_model(rng), path("m.json"));
  ASSERT_EQ(run("convert " + path("m.json") + " -o " + path("m.txt") + " --format irit").code, 0);
  EXPECT_EQ(std::ifstream(path("m.txt")).get(), '#');
  ASSERT_EQ(run("convert " + path("m.txt") + " --input-format itd -o " + path("n.json")).code, 0);
  const auto unknown = run("convert " + path("m.json") + " -o " + path("m.step"));
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("expected the extension .json, .xml, .itd, .vtu"), std::string::npos) << unknown.err;
  const auto bad_name = run("convert " + path("m.json") + " -o " + path("m.xml") + " --format step");
  EXPECT_EQ(bad_name.code, 2);
  EXPECT_NE(bad_name.err.find("unknown model format 'step'"), std::string::npos) << bad_name.err;
}

TEST_F(ConvertFormats, BadFilesExitWithTwoAndNameFileAndLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"truncated.xml", "<xml>\n<Geometry type=\"BSpline\">\n<Basis type=\"BSplineBasis\">"},
      {"noknots.xml", "<xml>\n<Geometry type=\"BSpline\"><Basis type=\"BSplineBasis\"></Basis><coefs geoDim=\"1\">0 1</coefs></Geometry></xml>"},
      {"count.itd", "[CURVE BSPLINE 3 2 E1\n[KV 0 0 1 2 2]\n[0]\n[1]\n]"},
      {"token.itd", "[CURVE BSPLINE 2 2 E1\n[KV 0 0 1 1]\n[0]\n[one]\n]"},
      {"points.vtu", "<VTKFile type=\"UnstructuredGrid\" version=\"2.2\"><UnstructuredGrid>\n<Piece NumberOfPoints=\"2\" NumberOfCells=\"1\">\n"
                     "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 1 1</DataArray></Points>\n"
                     "<Cells><DataArray Name=\"connectivity\" format=\"ascii\">0 1</DataArray>\n<DataArray Name=\"offsets\" format=\"ascii\">2</DataArray>\n"
                     "<DataArray Name=\"types\" format=\"ascii\">79</DataArray></Cells></Piece></UnstructuredGrid></VTKFile>"},
  };
  const char* expected[] = {"line 3, column", "line 2, /xml/Geometry/Basis: missing element <KnotVector>",
                            "line 5: expected '[' opening control point 2 of 3, got ']'", "line 4: expected a coordinate", "line 5, /VTKFile"};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    std::ofstream(path(cases[i].first)) << cases[i].second;
    const auto result = run("convert " + path(cases[i].first) + " -o " + path("out.json"));
    EXPECT_EQ(result.code, 2) << cases[i].first;
    EXPECT_NE(result.err.find(path(cases[i].first) + ": " + expected[i]), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(path("out.json")));
  }
}

TEST_F(ConvertFormats, MeshCommandsWriteGlb) {
  std::mt19937 rng(4);
  Model model = test_support::random_exchange_model(rng);
  model.objects.erase(model.objects.begin(), model.objects.begin() + 4);
  write_model(model, path("v.json"));
  const auto result = run("faces " + path("v.json") + " -o " + path("faces.glb") + " --resolution 4");
  ASSERT_EQ(result.code, 0) << result.err;
  std::ifstream in(path("faces.glb"), std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  EXPECT_EQ(std::string(magic, 4), "glTF");
}

}  // namespace
}  // namespace volspline
