// The blending examples of `volspline demo` (Peters & Wittman 1995, the page of figures).
#include "demo_blend.h"

#include <iostream>

#include "volspline/boxspline/blend_examples.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void write_blend_demo(const std::filesystem::path& dir) {
  for (const BlendFigure& figure : paper_blend_figures()) {
    const std::filesystem::path base = dir / figure.name;
    write_mesh(figure.mesh, base.string() + ".ply");
    RenderOptions options;
    options.view_direction = Eigen::Vector3d(-1.0, -1.6, -0.9);
    write_png(render_mesh(figure.mesh, options), base.string() + ".png");
    std::cout << figure.name << ": " << figure.description << "\n  " << base.string() << ".ply\n  " << base.string() << ".png\n";
  }
}

}  // namespace volspline::cli
