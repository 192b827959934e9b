// The blending examples of `volspline demo` (Peters & Wittman 1995, the page of figures).
#include "demo_blend.h"

#include <iostream>
#include <optional>

#include "volspline/boxspline/blend_examples.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void write_blend_demo(DemoRun& demo) {
  // The figures are built together; built only if --only names one of them.
  if (!demo.wants_group("blend-fig", "blend-fig1a..blend-fig4c")) return;
  std::optional<ProgressPhase> phase(std::in_place, demo.progress(), "blend figures");
  const std::vector<BlendFigure> figures = paper_blend_figures();
  phase.reset();
  for (const BlendFigure& figure : figures) {
    if (!demo.wants(figure.name)) continue;
    const std::filesystem::path base = demo.dir() / figure.name;
    phase.emplace(demo.progress(), figure.name);
    write_mesh(figure.mesh, base.string() + ".ply");
    RenderOptions options;
    options.view_direction = Eigen::Vector3d(-1.0, -1.6, -0.9);
    write_png(render_mesh(figure.mesh, options), base.string() + ".png");
    InteractivePage page;
    page.title = figure.name;
    page.mesh = figure.mesh;
    page.info = {{"figure", "Peters-Wittman 1995, " + figure.description}};
    const std::string page_file = demo.write_page(figure.name + ".html", std::move(page), demo_only_command(figure.name));
    phase.reset();
    std::cout << figure.name << ": " << figure.description << "\n  " << base.string() << ".ply\n  " << base.string() << ".png\n";
    demo.gallery().add({figure.name, "Peters-Wittman 1995, " + figure.description, {figure.name + ".png"},
                        demo_only_command(figure.name), page_file});
  }
}

}  // namespace volspline::cli
