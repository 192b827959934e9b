// `volspline sweep-envelope` end to end: the trimmed envelope of the translated box example is
// the closed hull of its end positions (volume from the formula), --superset writes more than the
// boundary, and bad input exits with 2 naming what was wrong, with nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline {
namespace {

class SweepEnvelopeCli : public ::testing::Test {
 protected:
  test_support::TemporaryDirectory tmp;
  std::string path(const std::string& name) const { return (tmp.path() / name).string(); }
  static std::string example(const std::string& name) { return (std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / name).string(); }
};

TEST_F(SweepEnvelopeCli, TrimmedTranslatedBoxIsItsClosedHull) {
  const auto r = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("hull.ply") +
                                       " --stats " + path("s.json"),
                                       tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const TriangleMesh mesh = read_mesh(path("hull.ply"));
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  std::ifstream in(path("s.json"));
  const auto stats = nlohmann::json::parse(in);
  const auto& o = stats["objects"][0];
  EXPECT_TRUE(o["closed"].get<bool>());
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_NEAR(enclosed_volume(mesh), o["volume"].get<double>(), 1e-9);
  // The box 1 x 2 x 0.5 along D = (3, -1, 2): abc + |Dx| bc + |Dy| ac + |Dz| ab.
  EXPECT_NEAR(o["volume"].get<double>(), 1.0 + 3 * 2 * 0.5 + 1 * 1 * 0.5 + 2 * 1 * 2, 1e-9);
  EXPECT_EQ(o["result_triangles"]["total"].get<std::int64_t>(), static_cast<std::int64_t>(mesh.num_triangles()));
  EXPECT_EQ(o["result_triangles"]["caps"].get<std::int64_t>() + o["result_triangles"]["face_sweeps"].get<std::int64_t>() +
                o["result_triangles"]["rank_deficient"].get<std::int64_t>(),
            static_cast<std::int64_t>(mesh.num_triangles()));
  EXPECT_EQ(o["trimming"]["tags_beyond_tolerance"].get<std::int64_t>(), 0);

  // Every vertex carries its (u, v, w) and, after them, t and the generator patch: s there is
  // the vertex.
  std::ifstream ply(path("hull.ply"), std::ios::binary);
  std::string line, header;
  while (std::getline(ply, line) && line != "end_header") header += line + "\n";
  ASSERT_NE(header.find("property double w\nproperty double t\nproperty int patch\nproperty int object\n"), std::string::npos) << header;
  const Model model = read_model(example("swept-translated-box.json"));
  const auto patches = swept_patches(std::get<SweptSolid>(model.objects.at(0).spline));
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    double values[7];
    std::int32_t patch = -1, object = -1;
    ply.read(reinterpret_cast<char*>(values), sizeof values);
    ply.read(reinterpret_cast<char*>(&patch), sizeof patch);
    ply.read(reinterpret_cast<char*>(&object), sizeof object);
    ASSERT_TRUE(ply.good());
    ASSERT_EQ(patch, 0);
    ASSERT_EQ(object, 0);
    const Eigen::VectorXd x = patches[0].evaluate({values[3], values[4], values[5], values[6]});
    EXPECT_NEAR((Eigen::Vector3d(x[0], x[1], x[2]) - Eigen::Vector3d(values[0], values[1], values[2])).norm(), 0, 1e-9) << v;
  }

  // Trimmed by the arrangement: no contouring summary.
  EXPECT_EQ(r.out.find("coarse cells refined"), std::string::npos) << r.out;

  // A bare 4-variate spline (a bezier_hypervolume object): its image is the swept volume, here
  // the unit cube moved by 2 along x as the fourth parameter goes from 0 to 1: volume 3.
  {
    std::ofstream hv(path("hv.json"));
    hv << R"({"volspline": 1, "objects": [{"type": "bezier_hypervolume", "degree": [1,1,1,1], "control_points": [)"
          R"([0,0,0],[1,0,0],[0,1,0],[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1],)"
          R"([2,0,0],[3,0,0],[2,1,0],[3,1,0],[2,0,1],[3,0,1],[2,1,1],[3,1,1]]}]})";
  }
  const auto h = test_support::run_cli("sweep-envelope " + path("hv.json") + " -o " + path("hv.ply") + " --stats " + path("hv-s.json"), tmp.path());
  ASSERT_EQ(h.code, 0) << h.err;
  std::ifstream hv_stats(path("hv-s.json"));
  const auto hs = nlohmann::json::parse(hv_stats);
  EXPECT_NEAR(hs["objects"][0]["volume"].get<double>(), 3.0, 1e-9);
  EXPECT_TRUE(hs["objects"][0]["closed"].get<bool>());

  const auto s = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("superset.ply") +
                                       " --superset",
                                       tmp.path());
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_GT(read_mesh(path("superset.ply")).num_triangles(), mesh.num_triangles());
}

// The superset (no trimming) keeps this cheap under the sanitizers; pictures are drawn alike.
TEST_F(SweepEnvelopeCli, ViewTurnsTheCameraOfThePicture) {
  const auto picture = [&](const std::string& view, const std::string& name) {
    const auto r = test_support::run_cli("sweep-envelope " + example("swept-translated-box.json") + " -o " + path("e.ply") +
                                             " --superset --size 160,120 --png " + path(name) + view,
                                         tmp.path());
    EXPECT_EQ(r.code, 0) << r.err;
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(picture("", "a.png"), picture(" --view -1,-1.3,-0.8", "b.png"));  // the default
  EXPECT_NE(picture("", "a.png"), picture(" --view 0,-1,-0.3", "c.png"));
  // --cut-open changes the picture and nothing else: the mesh file is the whole superset.
  const std::string whole = picture("", "a.png");
  std::ifstream whole_mesh(path("e.ply"), std::ios::binary);
  const std::string mesh_bytes(std::istreambuf_iterator<char>(whole_mesh), {});
  EXPECT_NE(picture(" --cut-open 1,0,0,1.5", "d.png"), whole);
  std::ifstream cut_mesh(path("e.ply"), std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(cut_mesh), {}), mesh_bytes);
}

// --coarse-cells: a ball of radius 1 along a segment of length 3 (the capsule, volume
// 3 pi + 4/3 pi) contoured on a grid of 16 tolerances with its edges refined toward the sheets:
// closed, oriented, free of self-intersections, no unrefined edge beyond the tolerance, the
// volume of the inscribed surface below the capsule's and within 1e-3 of it.
TEST_F(SweepEnvelopeCli, ACoarseGridRefinedTowardTheSheetsKeepsTheCapsule) {
  const auto r = test_support::run_cli("sweep-envelope " + example("swept-translated-ball.json") + " -o " + path("c.ply") +
                                       " --coarse-cells 16 --stats " + path("s.json"),
                                       tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("refined toward the sheets"), std::string::npos) << r.out;
  const TriangleMesh mesh = read_mesh(path("c.ply"));
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  std::ifstream in(path("s.json"));
  const auto o = nlohmann::json::parse(in)["objects"][0];
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_EQ(o["trimming"]["grid_passes"].get<int>(), 1);
  EXPECT_GT(o["trimming"]["refinement"]["split_edges"].get<int>(), 0);
  // The edges refinement could not split (at crease points, failed) are within the tolerance of
  // the boundary by membership tests on either side of their midpoints.
  EXPECT_EQ(o["trimming"]["refinement"]["edges_beyond_tolerance"].get<int>(), 0);
  EXPECT_EQ(r.err.find("farther than the tolerance"), std::string::npos) << r.err;
  const double exact = 3 * std::numbers::pi + 4.0 / 3 * std::numbers::pi;
  EXPECT_LT(o["volume"].get<double>(), exact);
  EXPECT_NEAR(o["volume"].get<double>(), exact, 1e-3 * exact);
}

// --tol 1e-4 on the capsule: the coarse cells stay about 1.2 % of the diagonal (the automatic
// ratio, 32), the refinement toward the sheets gives the accuracy. Closed, oriented, one
// component, free of self-intersections, every vertex on the capsule, the volume within 2e-4 of
// the exact one, and far fewer triangles than cells 4 x the fine grid would give (5.8 million,
// docs/envelopes.md "Fine tolerances").
TEST_F(SweepEnvelopeCli, AtAFinerToleranceTheCoarseCellsStayAndTheCapsuleIsKept) {
  const auto r = test_support::run_cli("sweep-envelope " + example("swept-translated-ball.json") + " -o " + path("c.ply") +
                                       " --tol 1e-4 --stats " + path("s.json"),
                                       tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  // The default run says how wide its coarse cells were.
  EXPECT_NE(r.out.find("coarse cells refined (32 fine cells wide)"), std::string::npos) << r.out;
  const TriangleMesh mesh = read_mesh(path("c.ply"));
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  std::ifstream in(path("s.json"));
  const auto o = nlohmann::json::parse(in)["objects"][0];
  EXPECT_EQ(o["trimming"]["grid_coarse_ratio"].get<int>(), 32);
  EXPECT_EQ(o["trimming"]["grid_crease_width"].get<int>(), 8);
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_EQ(o["components"].get<int>(), 1);
  EXPECT_EQ(o["trimming"]["refinement"]["edges_beyond_tolerance"].get<int>(), 0);
  const double exact = 3 * std::numbers::pi + 4.0 / 3 * std::numbers::pi;
  EXPECT_NEAR(o["volume"].get<double>(), exact, 2e-4 * exact);
  // The ball of radius 1 about the segment from 0 to (3, 0, 0); diagonal of its box sqrt(33).
  const double tolerance = 1e-4 * std::sqrt(33.0);
  for (const Eigen::Vector3d& x : mesh.positions) {
    const double t = std::clamp(x.x() / 3, 0.0, 1.0);
    EXPECT_NEAR((x - Eigen::Vector3d(3 * t, 0, 0)).norm(), 1.0, tolerance) << x.transpose();
  }
  EXPECT_LT(mesh.num_triangles(), 500000u);
}

// Adaptive cells (--adaptive-cells 4) on the annulus (examples/swept-rotating-box.json: the box
// [1, 2] x [-1/2, 1/2] x [0, 1] turned once about z): fine cells only along the four circular
// creases of its rims, coarse cells with their edges refined toward the sheets elsewhere. The
// result is one closed, oriented torus free of self-intersections with the annulus's volume
// pi (4.25 - 1), every vertex near the analytic annulus and every edge midpoint within 1.5
// tolerances of it (the fine grid's chamfers).
TEST_F(SweepEnvelopeCli, AdaptiveCellsKeepTheAnnulusAndItsCreases) {
  const auto r = test_support::run_cli("sweep-envelope " + example("swept-rotating-box.json") + " -o " + path("a.ply") +
                                       " --adaptive-cells 4 --stats " + path("s.json"),
                                       tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("coarse cells refined"), std::string::npos) << r.out;
  const TriangleMesh mesh = read_mesh(path("a.ply"));
  EXPECT_TRUE(edge_statistics(mesh).closed_and_oriented());
  std::ifstream in(path("s.json"));
  const auto o = nlohmann::json::parse(in)["objects"][0];
  EXPECT_TRUE(o["self_intersection_free"].get<bool>());
  EXPECT_EQ(o["components"].get<int>(), 1);
  EXPECT_EQ(o["trimming"]["grid_passes"].get<int>(), 1);
  EXPECT_GT(o["trimming"]["grid_cells_refined"].get<int>(), 0);
  const double exact = std::numbers::pi * (4.25 - 1);
  EXPECT_NEAR(o["volume"].get<double>(), exact, 1e-3 * exact);
  // Signed distance to the annulus 1 <= r <= sqrt(4.25), 0 <= z <= 1 in the (r, z) half-plane.
  const auto distance = [](const Eigen::Vector3d& x) {
    const double radius = std::hypot(x.x(), x.y());
    const double dr = std::max(1 - radius, radius - std::sqrt(4.25)), dz = std::max(-x.z(), x.z() - 1);
    return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
  };
  const auto [lo, hi] = mesh.bounding_box();
  const double tol = 1e-3 * (hi - lo).norm();
  double worst_vertex = 0, worst_midpoint = 0;
  for (const auto& x : mesh.positions) worst_vertex = std::max(worst_vertex, std::abs(distance(x)));
  for (const auto& t : mesh.triangles)
    for (int j = 0; j < 3; ++j)
      worst_midpoint = std::max(worst_midpoint, std::abs(distance(0.5 * (mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>(j)])] +
                                                                          mesh.positions[static_cast<std::size_t>(t[static_cast<std::size_t>((j + 1) % 3)])]))));
  // Crossings lie on the sheets; crease points where the rims' tangent planes meet, off the
  // curved rim by a fraction of the tolerance.
  EXPECT_LT(worst_vertex, 0.05 * tol);
  // Edges across the rims' creases are chamfered by at most half a fine cell (3 x tol wide).
  EXPECT_LT(worst_midpoint, 1.5 * tol);
}

TEST_F(SweepEnvelopeCli, BadInputExitsTwoAndWritesNothing) {
  // A model without a swept solid, a bad option value, an unknown bounds method.
  for (const std::string& args : {example("swept-patch.json") + " -o " + path("a.ply"),
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --tol 0",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --bounds box",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --png " + path("a.png") + " --view 0,0,0",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --png " + path("a.png") + " --cut-open 0,0,0,1",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --cut-open 1,0,0,1",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --coarse-cells -1",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --coarse-cells 16 --refine 0",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --adaptive-cells 3",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --adaptive-cells 66",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --adaptive-cells 34 --tol 3e-3",
                                 example("swept-translated-box.json") + " -o " + path("a.ply") + " --adaptive-cells 4 --coarse-cells 16"}) {
    const auto r = test_support::run_cli("sweep-envelope " + args, tmp.path());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("a.ply"))) << args;
  }
}

}  // namespace
}  // namespace volspline
