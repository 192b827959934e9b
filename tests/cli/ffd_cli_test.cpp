// `volspline lattice` and `volspline ffd` end to end: the identity round trip, a moved control
// point moving the mesh exactly as the library does, exit codes and messages.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "support/test_meshes.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/lattice.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"

namespace volspline {
namespace {

using Result = test_support::CliResult;

class FfdCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp / name).string(); }
  Result run(const std::string& args) const {
    return test_support::run_cli(args, tmp.path());
  }
};

TEST_F(FfdCli, HelpListsBothCommands) {
  for (const char* sub : {"lattice", "ffd"}) {
    const auto r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << sub;
  }
}

TEST_F(FfdCli, UndeformedLatticeGivesBackTheMesh) {
  const TriangleMesh sphere = test_support::icosphere(2);
  write_mesh(sphere, path("sphere.ply"));
  for (const std::string options : {"--degree 3,3,3", "--degree 2,3,1 --divisions 3,2,4 --margin 0.2 --axes 1,0.2,0,0.3,1,0,0,0.1,1"}) {
    auto r = run("lattice " + path("sphere.ply") + " " + options + " -o " + path("lattice.json"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("wrote"), std::string::npos);
    r = run("ffd " + path("lattice.json") + " " + path("sphere.ply") + " -o " + path("out.ply"));
    ASSERT_EQ(r.code, 0) << r.err;
    const TriangleMesh back = read_mesh(path("out.ply"));
    ASSERT_EQ(back.num_vertices(), sphere.num_vertices());
    EXPECT_EQ(back.triangles, sphere.triangles);
    EXPECT_EQ(back.parameters, sphere.parameters);
    for (std::size_t i = 0; i < sphere.num_vertices(); ++i) EXPECT_LE((back.positions[i] - sphere.positions[i]).norm(), 1e-12) << i;
  }
}

TEST_F(FfdCli, MovedControlPointMovesTheMeshAsTheLibraryDoes) {
  write_mesh(test_support::icosphere(2), path("sphere.obj"));
  ASSERT_EQ(run("lattice " + path("sphere.obj") + " --degree 2,2,2 -o " + path("lattice.json")).code, 0);
  Model model = read_model(path("lattice.json"));
  const auto& v = std::get<BSplineVolume>(model.objects[0].spline);
  std::vector<double> points = v.points();
  const auto top = static_cast<std::size_t>(v.linear_index({1, 1, 2}));
  points[3 * top + 2] += 1.0;  // pull the middle of the top face up
  model.objects[0].spline = BSplineVolume(v.knot_vectors(), 3, points);
  write_model(model, path("pulled.json"));
  const auto r = run("ffd " + path("pulled.json") + " " + path("sphere.obj") + " -o " + path("out.stl") + " --png " +
                     path("out.png") + " --size 64,48");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("out.png")));
  const TriangleMesh out = read_mesh(path("out.stl"));
  const TriangleMesh expected = deform_mesh(lattice_from_model(model, "pulled.json"), read_mesh(path("sphere.obj")));
  ASSERT_EQ(out.num_triangles(), expected.num_triangles());
  for (std::size_t t = 0; t < out.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(out.positions[out.triangles[t][c]], expected.positions[expected.triangles[t][c]].cast<float>().cast<double>());
  // The north pole (0, 0, 1) moves up by about B_2^2(w) B_1^2(1/2)^2 = 0.9^2 / 4; the south pole,
  // near w = 0 where that basis function vanishes quadratically, hardly moves.
  EXPECT_GT(out.bounding_box().second.z(), 1.15);
  EXPECT_NEAR(out.bounding_box().first.z(), -1.0, 1e-3);
}

TEST_F(FfdCli, SplineCurvesAreComposedExactly) {
  // A single-cell lattice around the unit cube with one control point pulled, and a cubic curve
  // inside it: the written curve must be lattice(curve(t)) at every t.
  const std::vector<Eigen::Vector3d> corners{{0, 0, 0}, {1, 1, 1}};
  Lattice lattice = undeformed_lattice(corners, {2, 2, 2}, {1, 1, 1}, 0.0);
  std::vector<double> points = lattice.volume.points();
  points[3 * static_cast<std::size_t>(lattice.volume.linear_index({1, 1, 1})) + 2] += 0.5;
  lattice.volume = BSplineVolume(lattice.volume.knot_vectors(), 3, points);
  write_model(lattice_to_model(lattice), path("lattice.json"));
  const BSplineCurve curve({KnotVector::bezier(3)}, 3, {0.1, 0.2, 0.3, 0.4, 0.9, 0.5, 0.7, 0.1, 0.6, 0.9, 0.8, 0.2});
  Model in;
  in.objects.push_back({"curve", false, curve, nullptr});
  write_model(in, path("curve.json"));
  const auto r = run("ffd " + path("lattice.json") + " " + path("curve.json") + " -o " + path("bent.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const Model result = read_model(path("bent.json"));
  const auto& bent = std::get<BSplineCurve>(result.objects[0].spline);
  for (int i = 0; i <= 20; ++i) {
    const double t = i / 20.0;
    const Eigen::Vector3d expected = deform_point(lattice, curve.evaluate({t}));
    EXPECT_LT((bent.evaluate({t}) - expected).norm(), 1e-12);
  }
  EXPECT_EQ(run("ffd " + path("lattice.json") + " " + path("curve.json") + " -o " + path("bent.ply")).code, 2);
}

TEST_F(FfdCli, BadInputIsExitCode2WithAMessage) {
  write_mesh(test_support::unit_cube(), path("cube.obj"));
  std::ofstream(path("broken.obj")) << "v 0 0 0\nf 1 2 3\n";
  std::ofstream(path("plain.json")) << R"({"volspline": 1, "objects": [{"type": "bezier_volume", "degree": [1, 1, 1],
    "control_points": [[0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]]}]})";
  ASSERT_EQ(run("lattice " + path("cube.obj") + " --degree 1,1,1 -o " + path("lattice.json")).code, 0);
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"lattice " + path("cube.obj") + " --degree 0,1,1 -o " + path("l.json"), "--degree"},
      {"lattice " + path("cube.obj") + " --degree 1,1 -o " + path("l.json"), "--degree"},
      {"lattice " + path("cube.obj") + " --degree 1,1,1 --margin -1 -o " + path("l.json"), "margin"},
      {"lattice " + path("cube.obj") + " --degree 1,1,1 --axes 1,0,0,0,1,0,1,1,0 -o " + path("l.json"), "non-coplanar"},
      {"lattice " + path("missing.obj") + " --degree 1,1,1 -o " + path("l.json"), "missing.obj"},
      {"lattice " + path("broken.obj") + " --degree 1,1,1 -o " + path("l.json"), "broken.obj: line 2: face index 2 out of range"},
      {"ffd " + path("plain.json") + " " + path("cube.obj") + " -o " + path("o.ply"), "plain.json: objects[0].metadata"},
      {"ffd " + path("lattice.json") + " " + path("cube.obj") + " -o " + path("o.off"), "expected the extension"},
      {"ffd " + path("lattice.json") + " " + path("cube.obj") + " -o " + path("o.ply") + " --png x.jpg", "--png"},
      {"ffd " + path("lattice.json") + " " + path("cube.off") + " -o " + path("o.ply"), "cube.off"},
  };
  for (const auto& c : cases) {
    const auto r = run(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
  // Nothing was written by the failures.
  for (const char* name : {"l.json", "o.ply", "o.off"}) EXPECT_FALSE(std::filesystem::exists(path(name))) << name;
}

}  // namespace
}  // namespace volspline
