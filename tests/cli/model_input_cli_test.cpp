// info, eval, faces, boundary and jacobian read every model format of io/model_formats.h (by
// extension, or --input-format), and give the same answers as for the JSON model.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/io/model_formats.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

void expect_close(const std::vector<double>& a, const std::vector<double>& b, double tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], tolerance) << i;
}

class ModelInput : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::filesystem::path written(const std::string& name) {
    Model m;
    m.objects.push_back({"twisted-loft", false, twisted_loft(), nullptr});
    write_model_file(m, tmp.path() / name);
    return tmp.path() / name;
  }
  test_support::CliResult run(const std::string& args) { return test_support::run_cli(args, tmp.path()); }
};

TEST_F(ModelInput, EvalFacesInfoReadGismoAndIrit) {
  const auto json = written("loft.json").string();
  const auto reference = run("eval " + json + " --grid 4,3,5 --derivatives");
  ASSERT_EQ(reference.code, 0) << reference.err;
  const TriangleMesh faces_json = [&] {
    EXPECT_EQ(run("faces " + json + " -o " + (tmp.path() / "json.ply").string()).code, 0);
    return read_mesh(tmp.path() / "json.ply");
  }();
  for (const char* name : {"loft.xml", "loft.itd"}) {
    const auto path = written(name).string();
    const auto r = run("eval " + path + " --grid 4,3,5 --derivatives");
    ASSERT_EQ(r.code, 0) << r.err;
    expect_close(numbers(r.out), numbers(reference.out), 1e-12);
    const auto ply = (tmp.path() / (std::string(name) + ".ply")).string();
    ASSERT_EQ(run("faces " + path + " -o " + ply).code, 0);
    const TriangleMesh mesh = read_mesh(ply);
    ASSERT_EQ(mesh.triangles, faces_json.triangles);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) EXPECT_LT((mesh.positions[i] - faces_json.positions[i]).norm(), 1e-12);
    const auto info = run("info " + path + " --json");
    EXPECT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("\"degree\""), std::string::npos) << info.out;
    EXPECT_EQ(run("jacobian " + path).code, 0);
  }
  // --input-format overrides the extension; an unknown extension is bad input.
  std::filesystem::copy_file(tmp.path() / "loft.xml", tmp.path() / "loft.txt");
  EXPECT_EQ(run("eval " + (tmp.path() / "loft.txt").string() + " --at 0.5,0.5,0.5").code, 2);
  const auto r = run("eval " + (tmp.path() / "loft.txt").string() + " --input-format gismo --grid 4,3,5 --derivatives");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_close(numbers(r.out), numbers(reference.out), 1e-12);
}

TEST_F(ModelInput, GismoDataFilesEvaluateAsTheLibraryReadsThem) {
  const char* env = std::getenv("VOLSPLINE_GISMO_DATA");
  const std::filesystem::path file =
      (env ? std::filesystem::path(env) : std::filesystem::path(VOLSPLINE_SOURCE_DIR) / ".." / "shared" / "data" / "gismo") / "cylinder.xml";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " is absent (set VOLSPLINE_GISMO_DATA to its folder)";
  const Model model = read_model_file(file);
  const auto& volume = std::get<BSplineVolume>(model.objects.at(0).spline);
  const auto r = run("eval " + file.string() + " --at 0.25,0.5,0.75");
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<double> x(3);
  volume.evaluate({0.25, 0.5, 0.75}, x.data());
  expect_close(numbers(r.out), x, 1e-12);
  EXPECT_EQ(run("info " + file.string()).code, 0);
  EXPECT_EQ(run("faces " + file.string() + " -o " + (tmp.path() / "c.ply").string()).code, 0);
}

}  // namespace
}  // namespace volspline
