// volspline demo [--out DIR] [--only NAME...]: example solids built in code, each written as a
// model, a face mesh and a picture, and index.html, the gallery of the pictures with the command
// line that reproduces each.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "demo_blend.h"
#include "demo_view.h"
#include "demo_gallery.h"
#include "progress_bar.h"
#include "volspline/core/error.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/ffd_example.h"
#include "volspline/deform/lattice.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void add_demo_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo", "Build the example solids and write each one's model (.json), faces (.ply) and picture (.png), and index.html, "
              "a gallery of the pictures with the command line that reproduces each");
  auto dir = std::make_shared<std::string>("out/demo");
  auto only = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--out", *dir, "output folder (created if missing; default out/demo)");
  cmd->add_option("--only", *only, "write only the examples with these names (index.html is then not written)");
  auto simplex_inputs = std::make_shared<SimplexDemoInputs>();
  cmd->add_option("--examples", simplex_inputs->examples,
                  "the repository's examples folder, where Hua-He-Qin Figs. 5 and 6 find their surface and skeletons and Conkey-Joy Figs. 4-8 "
                  "their swept solids (default examples)");
  cmd->add_option("--data", simplex_inputs->data,
                  "the shared data folder with volumes/bunny00.off for Hua-He-Qin Fig. 6 (default ../shared/data; skipped if absent)");
  cmd->callback([=] {
    // The demo reads back some of what it writes, so its files are renamed as they are written;
    // a failed run still removes them and the folders it made.
    if (OutputTransaction* outputs = OutputTransaction::current()) outputs->publish_each_file();
    create_output_directories(*dir);
    DemoRun demo(*dir, *only, command_progress());
    // `make` is the `volspline make` arguments that build the same volume; empty where none does:
    // then the model is a file of the repository's examples/ (the same bytes), copied into the
    // demo folder's examples/.
    struct Example {
      std::string name, description;
      BSplineVolume volume;
      std::string make;
    };
    const std::vector<Example> examples{
        {"bent-tricubic", "tricubic B-spline slab bent along u", bent_tricubic_volume(), ""},
        {"twisted", "column twisted a quarter turn (degree 1, 1, 3)", twisted_volume(0.25), ""},
        {"half-cylinder-shell", "exact rational thick half cylinder, weight-0 control points (Lasser Thm 2, 180 deg)",
         half_cylinder_shell(1.0, 2.0, 1.0), ""},
        {"ball", "exact solid ball: a half disk revolved, degree (1, 2, 2)", ball(1.0), "ball --radius 1"},
        {"torus-segment", "270 degree segment of an exact solid torus", torus(3.0, 1.0, 270.0),
         "torus --major 3 --minor 1 --angle 270"},
        {"hollow-cylinder", "exact thick ring (make cylinder --inner)", cylinder(2.0, 1.0, 1.2),
         "cylinder --radius 2 --height 1 --inner 1.2"},
        {"frustum", "exact cone frustum", cone(2.0, 0.7, 3.0), "cone --radius1 2 --radius2 0.7 --height 3"},
        {"half-torus", "Lasser Fig. 2: solid half torus, one Bezier volume with weight-0 control points", half_torus(),
         "half-torus"},
        {"hyperboloid", "Lasser Fig. 3: segment of a solid hyperboloid of one sheet", hyperboloid_segment(), "hyperboloid"},
        {"half-cylinder-sweep", "Joy-Duchaineau Fig. 1: half cylinder swept along a line (folds over itself)",
         half_cylinder_sweep(), "half-cylinder-sweep"},
        {"swept-patch", "Joy-Duchaineau Fig. 10: bicubic patch swept along a line", swept_patch(), "swept-patch"},
        {"twisted-loft", "Joy-Duchaineau Fig. 11: the patch twisted 35 degrees, sampled 4 times and lofted", twisted_loft(),
         "twisted-loft"},
        {"curved-loft", "Joy-Duchaineau Fig. 13: the patch swept along a curved path and lofted", curved_loft(), "curved-loft"},
    };
    for (const auto& e : examples) {
      if (!demo.wants(e.name)) continue;
      const std::string model_file = e.make.empty() ? "examples/" + e.name + ".json" : e.name + ".json";
      const std::string command = (e.make.empty() ? "" : "volspline make " + e.make + " -o " + model_file + " && ") + "volspline faces " +
                                  model_file + " -o " + e.name + ".ply --resolution 32 --png " + e.name + ".png --html " + e.name + ".html";
      std::string page_file;
      {
        const ProgressPhase phase(demo.progress(), e.name);
        Model model;
        model.objects.push_back({e.name, true, e.volume, nullptr});  // bezier_volume when it is one span on [0,1]^3
        write_model(model, demo.path(e.name + ".json"));
        if (e.make.empty()) {
          create_output_directories(demo.dir() / "examples");
          write_model(model, demo.path(model_file));
        }
        // As `volspline faces --resolution 32 --html` (the command in the gallery) tessellates, renders and
        // writes the page.
        const TriangleMesh mesh = tessellate_faces(e.volume, {.resolution = 32});
        write_mesh(mesh, demo.path(e.name + ".ply"));
        write_png(render_mesh(mesh, RenderOptions{}), demo.path(e.name + ".png"));
        InteractivePage page;
        page.title = "faces of " + model_file;
        page.mesh = mesh;
        page.info = model_page_info(model, model_file);
        const auto stats = edge_statistics(mesh);
        page.info["faces"] = {{"vertices", mesh.num_vertices()}, {"triangles", mesh.num_triangles()}, {"closed", stats.closed()}};
        add_model_probes(page, model, {}, model_file);
        page_file = demo.write_page(e.name + ".html", std::move(page), command);
      }
      std::cout << e.name << ": " << e.description << "\n  " << demo.path(e.name + ".json") << "\n  " << demo.path(e.name + ".ply")
                << "\n  " << demo.path(e.name + ".png") << "\n";
      demo.gallery().add({e.name, e.description, {e.name + ".png"}, command, page_file});
    }
    // Free-form deformation (Lasser §III.2): a bar bent and twisted by a segmented lattice. The
    // lattice is a file of examples/ (the same bytes); the bar is made by `make box` and `faces`,
    // and both go through their files here as they do in the gallery's commands.
    if (demo.wants("ffd-bent-bar")) {
      const std::string lattice_file = "examples/ffd-bent-bar-lattice.json";
      const std::string command = "volspline make box --size 4,1,1 -o bar.json && volspline faces bar.json -o bar.ply --resolution 40 && "
                                  "volspline ffd " + lattice_file + " bar.ply -o ffd-bent-bar.ply --png ffd-bent-bar.png"
                                  " --html ffd-bent-bar.html";
      TriangleMesh bent;
      Model lattice_model;
      {
        const ProgressPhase phase(demo.progress(), "ffd-bent-bar");
        const FfdExample ffd = bent_bar_ffd_example();
        create_output_directories(demo.dir() / "examples");
        write_model(lattice_to_model(ffd.lattice), demo.path(lattice_file));
        lattice_model = read_model(demo.path(lattice_file));
        Model bar;
        bar.objects.push_back({"", true, box(Eigen::Vector3d(4.0, 1.0, 1.0)), nullptr});
        write_model(bar, demo.path("bar.json"));
        write_mesh(tessellate_faces(std::get<BSplineVolume>(read_model(demo.path("bar.json")).objects.at(0).spline), {.resolution = 40}),
                   demo.path("bar.ply"));
        bent = deform_mesh(lattice_from_model(lattice_model, lattice_file), read_mesh(demo.path("bar.ply")));
        write_mesh(bent, demo.path("ffd-bent-bar.ply"));
        RenderOptions options;
        options.color = ColorMode::Single;
        write_png(render_mesh(bent, options), demo.path("ffd-bent-bar.png"));
      }
      const std::string description = "a 4 x 1 x 1 bar deformed by a degree (3, 2, 2) lattice with 3 cells (Lasser §III.2)";
      std::cout << "ffd-bent-bar: " << description << "\n  " << demo.path(lattice_file) << "\n  " << demo.path("ffd-bent-bar.ply")
                << "\n  " << demo.path("ffd-bent-bar.png") << "\n";
      InteractivePage page;
      page.title = "ffd-bent-bar";
      page.mesh = bent;
      page.info = {{"lattice", model_page_info(lattice_model, lattice_file)}, {"description", description}};
      const std::string page_file = demo.write_page("ffd-bent-bar.html", std::move(page), command);
      demo.gallery().add({"ffd-bent-bar", description, {"ffd-bent-bar.png"}, command, page_file});
    }
    write_boundary_demo(demo);
    write_blend_demo(demo);  // Peters-Wittman blends, figures 1a-4c
    write_view_demo(demo);   // Lasser §IV: isoparametric surfaces, slices, cutaways, colouring
    write_simplex_demo(demo, *simplex_inputs);  // Hua-He-Qin Figs. 1, 5, 6
    write_sweeps_demo(demo, simplex_inputs->examples);  // Conkey-Joy Figs. 4-8
    write_fitting_demo(demo, *simplex_inputs);  // Hua-He-Qin §5: fire_ug, Marschner-Lobb, a jump
    demo.check_selection();
    if (!demo.selective()) {
      demo.gallery().write(*dir);
      std::cout << "gallery: " << demo.path("index.html") << "\n";
    }
  });
}

}  // namespace volspline::cli
