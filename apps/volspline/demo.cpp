// volspline demo [--out DIR]: example solids built in code, each written as a model, a face
// mesh and a picture.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/construct/example_solids.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/face_tessellation.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void add_demo_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("demo", "Build the example solids and write each one's model (.json), faces (.ply) and picture (.png)");
  auto dir = std::make_shared<std::string>("out/demo");
  cmd->add_option("--out", *dir, "output folder (created if missing; default out/demo)");
  cmd->callback([=] {
    std::error_code ec;
    std::filesystem::create_directories(*dir, ec);
    if (ec || !std::filesystem::is_directory(*dir)) throw IoError("cannot create the output folder '" + *dir + "': " + ec.message());
    struct Example {
      std::string name, description;
      BSplineVolume volume;
    };
    const std::vector<Example> examples{
        {"bent-tricubic", "tricubic B-spline slab bent along u", bent_tricubic_volume()},
        {"twisted", "column twisted a quarter turn (degree 1, 1, 3)", twisted_volume(0.25)},
        {"half-cylinder-shell", "exact rational thick half cylinder, weight-0 control points (Lasser Thm 2, 180 deg)",
         half_cylinder_shell(1.0, 2.0, 1.0)},
    };
    for (const auto& e : examples) {
      const std::filesystem::path base = std::filesystem::path(*dir) / e.name;
      Model model;
      const bool bezier = std::all_of(e.volume.knot_vectors().begin(), e.volume.knot_vectors().end(),
                                      [](const KnotVector& k) { return k.is_bezier() && k.domain_min() == 0 && k.domain_max() == 1; });
      model.objects.push_back({e.name, bezier, e.volume, nullptr});
      write_model(model, base.string() + ".json");
      const TriangleMesh mesh = tessellate_faces(e.volume, {.resolution = 32});
      write_mesh(mesh, base.string() + ".ply");
      RenderOptions options;
      options.edges = false;
      write_png(render_mesh(mesh, options), base.string() + ".png");
      std::cout << e.name << ": " << e.description << "\n  " << base.string() << ".json\n  " << base.string() << ".ply\n  "
                << base.string() << ".png\n";
    }
  });
}

}  // namespace volspline::cli
