// The blending examples of `volspline demo` (Peters & Wittman 1995, the page of figures). Each
// figure is what one `volspline blend` command draws from a scene file of examples/scenes; the
// demo writes those scene files into its examples/scenes and shows the command beside the figure.
#include "demo_blend.h"

#include <iostream>
#include <map>
#include <optional>

#include "volspline/boxspline/blend_examples.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {
namespace {

// The view of every blend figure: from below the front, so that the tunnels of Fig. 3 show.
constexpr const char* kBlendDemoView = "-1,-1.6,-0.9";

struct BlendFigureCommand {
  const char* scene;
  const char* arguments;
};

// The scene and the `blend` arguments of each figure (paper_blend_figures builds the same).
const std::map<std::string, BlendFigureCommand>& blend_figure_commands() {
  static const std::map<std::string, BlendFigureCommand> commands{
      {"blend-fig1a", {"peters-wittman-fig1", "--levels 0"}},
      {"blend-fig1b", {"peters-wittman-fig1", "--levels 1"}},
      {"blend-fig1c", {"peters-wittman-fig1", ""}},
      {"blend-fig2a", {"peters-wittman-fig2", "--show primitives --spacing 0.05"}},
      {"blend-fig2b", {"peters-wittman-fig2", "--show union --spacing 0.05"}},
      {"blend-fig2c", {"peters-wittman-fig2", ""}},
      {"blend-fig3a", {"peters-wittman-fig3", "--show primitives --spacing 0.05"}},
      {"blend-fig3b", {"peters-wittman-fig3", "--show union --spacing 0.05"}},
      {"blend-fig3c", {"peters-wittman-fig3", ""}},
      {"blend-fig4a", {"peters-wittman-fig4", "--show primitives --spacing 0.05"}},
      {"blend-fig4b", {"peters-wittman-fig4", "--show spline"}},
      {"blend-fig4c", {"peters-wittman-fig4", ""}},
  };
  return commands;
}

std::string blend_figure_command(const std::string& name) {
  const BlendFigureCommand& c = blend_figure_commands().at(name);
  const std::string arguments = *c.arguments == '\0' ? std::string() : std::string(" ") + c.arguments;
  return "volspline blend examples/scenes/" + std::string(c.scene) + ".json" + arguments + " -o " + name + ".ply --png " + name +
         ".png --view " + kBlendDemoView + " --html " + name + ".html";
}

}  // namespace

void write_blend_demo(DemoRun& demo) {
  // The figures are built together; built only if --only names one of them.
  if (!demo.wants_group("blend-fig", "blend-fig1a..blend-fig4c")) return;
  std::optional<ProgressPhase> phase(std::in_place, demo.progress(), "blend figures");
  // The figures' scenes as files (scene_to_json: the same bytes as the repository's
  // examples/scenes/peters-wittman-fig*.json, which BlendExamples.TheFigureSceneFilesAreTheScenes
  // checks).
  const std::filesystem::path scenes = demo.dir() / "examples" / "scenes";
  create_output_directories(scenes);
  for (const auto& [file, scene] : {std::pair{"peters-wittman-fig1", cylinder_intersection_scene()},
                                    std::pair{"peters-wittman-fig2", sphere_and_rod_scene()},
                                    std::pair{"peters-wittman-fig3", various_primitives_scene()},
                                    std::pair{"peters-wittman-fig4", two_tori_scene()}})
    write_file_atomically(scenes / (std::string(file) + ".json"), scene_to_json(scene));
  const std::vector<BlendFigure> figures = paper_blend_figures();
  phase.reset();
  for (const BlendFigure& figure : figures) {
    if (!demo.wants(figure.name)) continue;
    const std::filesystem::path base = demo.dir() / figure.name;
    const std::string command = blend_figure_command(figure.name);
    phase.emplace(demo.progress(), figure.name);
    write_mesh(figure.mesh, base.string() + ".ply");
    RenderOptions options;
    options.view_direction = Eigen::Vector3d(-1.0, -1.6, -0.9);  // kBlendDemoView
    write_png(render_mesh(figure.mesh, options), base.string() + ".png");
    InteractivePage page;
    page.title = figure.name;
    page.mesh = figure.mesh;
    page.info = {{"figure", "Peters-Wittman 1995, " + figure.description}};
    const std::string page_file = demo.write_page(figure.name + ".html", std::move(page), command);
    phase.reset();
    std::cout << figure.name << ": " << figure.description << "\n  " << base.string() << ".ply\n  " << base.string() << ".png\n";
    demo.gallery().add({figure.name, "Peters-Wittman 1995, " + figure.description, {figure.name + ".png"}, command, page_file});
  }
}

}  // namespace volspline::cli
