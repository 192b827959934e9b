// volspline demo [--out DIR]: example solids built in code, each written as a model, a face
// mesh and a picture.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "demo_blend.h"
#include "demo_view.h"
#include "volspline/core/error.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/ffd_example.h"
#include "volspline/deform/lattice.h"
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
        {"ball", "exact solid ball: a half disk revolved, degree (1, 2, 2)", ball(1.0)},
        {"torus-segment", "270 degree segment of an exact solid torus", torus(3.0, 1.0, 270.0)},
        {"hollow-cylinder", "exact thick ring (make cylinder --inner)", cylinder(2.0, 1.0, 1.2)},
        {"frustum", "exact cone frustum", cone(2.0, 0.7, 3.0)},
        {"half-torus", "Lasser Fig. 2: solid half torus, one Bezier volume with weight-0 control points", half_torus()},
        {"hyperboloid", "Lasser Fig. 3: segment of a solid hyperboloid of one sheet", hyperboloid_segment()},
        {"half-cylinder-sweep", "Joy-Duchaineau Fig. 1: half cylinder swept along a line (folds over itself)",
         half_cylinder_sweep()},
        {"swept-patch", "Joy-Duchaineau Fig. 10: bicubic patch swept along a line", swept_patch()},
        {"twisted-loft", "Joy-Duchaineau Fig. 11: the patch twisted 35 degrees, sampled 4 times and lofted", twisted_loft()},
        {"curved-loft", "Joy-Duchaineau Fig. 13: the patch swept along a curved path and lofted", curved_loft()},
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
    // Free-form deformation (Lasser §III.2): a bar bent and twisted by a segmented lattice.
    const FfdExample ffd = bent_bar_ffd_example();
    const std::filesystem::path base = std::filesystem::path(*dir) / "ffd-bent-bar";
    write_model(lattice_to_model(ffd.lattice), base.string() + "-lattice.json");
    const TriangleMesh bent = deform_mesh(ffd.lattice, ffd.mesh);
    write_mesh(bent, base.string() + ".ply");
    RenderOptions options;
    options.color = ColorMode::Single;
    write_png(render_mesh(bent, options), base.string() + ".png");
    std::cout << "ffd-bent-bar: a 4 x 1 x 1 bar deformed by a degree (3, 2, 2) lattice with 3 cells\n  " << base.string()
              << "-lattice.json\n  " << base.string() << ".ply\n  " << base.string() << ".png\n";
    write_boundary_demo(*dir);
    write_blend_demo(*dir);  // Peters-Wittman blends, figures 1a-4c
    write_view_demo(*dir);   // Lasser §IV: isoparametric surfaces, slices, colouring
  });
}

}  // namespace volspline::cli
