// The paper's page of examples (Peters & Wittman 1995, Figs. 1-4): every figure of a closed surface
// is a closed, consistently and outward oriented mesh; the tunnels of Fig. 3c belong to the zero
// set itself (the spline's, the control polyhedron's and the pointwise blend's agree in topology).
#include "volspline/boxspline/blend_examples.h"

#include <gtest/gtest.h>

#include <numeric>

#include "support/test_meshes.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::components_and_euler;


TEST(BlendExamples, EveryClosedFigureIsClosedAndOutwardOriented) {
  const std::vector<BlendFigure> figures = paper_blend_figures();
  ASSERT_EQ(figures.size(), 12u);
  for (const BlendFigure& figure : figures) {
    const EdgeStatistics e = edge_statistics(figure.mesh);
    if (figure.name == "blend-fig4b") {
      // The box-spline part of the join alone: a patch bounded by the box.
      EXPECT_GT(e.boundary_edges, 0u);
      EXPECT_EQ(e.nonmanifold_edges, 0u);
      continue;
    }
    EXPECT_TRUE(e.closed_and_oriented()) << figure.name << ": " << e.boundary_edges << " boundary, " << e.nonmanifold_edges
                                         << " non-manifold, " << e.inconsistently_oriented_edges << " inconsistently oriented edges";
    EXPECT_GT(enclosed_volume(figure.mesh), 0.1) << figure.name;
  }
}

TEST(BlendExamples, Fig3TunnelsBelongToTheZeroSet) {
  // The ellipsoid is joined to the torus around it in four places (blend fillets across the
  // narrow gap, and the rod), which leaves four windows: genus 4, Euler characteristic −6. The
  // control polyhedron, the exact spline values and the pointwise smooth minimum all give this.
  const Scene scene = various_primitives_scene();
  const std::pair<int, long> genus4{1, -6};
  EXPECT_EQ(components_and_euler(scene_zero_set(scene, {.levels = 1, .method = ZeroSetMethod::Control, .statistics = false}).mesh), genus4);
  EXPECT_EQ(components_and_euler(scene_zero_set(scene, {.levels = 1, .method = ZeroSetMethod::Exact, .statistics = false}).mesh), genus4);
  EXPECT_EQ(components_and_euler(implicit_zero_set(scene.root, scene.box_min, scene.box_max, 0.05)), genus4);
}

// The scene files from which `volspline blend` makes the figures in the demo's gallery
// (examples/scenes/peters-wittman-fig*.json) are the scenes built here, written by scene_to_json,
// and read back as the same scenes.
TEST(BlendExamples, TheFigureSceneFilesAreTheScenes) {
  const std::pair<const char*, Scene> scenes[] = {{"peters-wittman-fig1", cylinder_intersection_scene()},
                                                  {"peters-wittman-fig2", sphere_and_rod_scene()},
                                                  {"peters-wittman-fig3", various_primitives_scene()},
                                                  {"peters-wittman-fig4", two_tori_scene()}};
  for (const auto& [name, scene] : scenes) {
    const std::filesystem::path file = std::string(VOLSPLINE_SOURCE_DIR) + "/examples/scenes/" + name + ".json";
    EXPECT_EQ(read_file(file), scene_to_json(scene)) << name;
    EXPECT_EQ(scene_to_json(read_scene(file)), scene_to_json(scene)) << name;
  }
}

}  // namespace
}  // namespace volspline
