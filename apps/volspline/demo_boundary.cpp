// The boundary-determination examples of `volspline demo` (Joy–Duchaineau Figs. 1, 10, 11, 13):
// faces plus implicit surface, a picture, and the statistics.
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "demo_gallery.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "cli_support.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void write_boundary_demo(DemoRun& demo) {
  struct Example {
    std::string name, description;
    BSplineVolume volume;
  };
  const std::vector<Example> examples{
      {"half-cylinder-sweep", "Joy-Duchaineau Fig. 1: its top is the implicit surface", half_cylinder_sweep()},
      {"swept-patch", "Joy-Duchaineau Fig. 10: the implicit surface is the plane v = 2/3", swept_patch()},
      {"twisted-loft", "Joy-Duchaineau Fig. 11 (paper: 900 cells, 5,161 triangles)", twisted_loft()},
      {"curved-loft", "Joy-Duchaineau Fig. 13", curved_loft()},
  };
  for (const auto& e : examples) {
    const std::string name = e.name + "-boundary";
    if (!demo.wants(name)) continue;
    SolidBoundary b;
    const std::string command = "volspline make " + e.name + " -o " + e.name + ".json && volspline boundary " + e.name + ".json -o " +
                                name + ".ply --snap --png " + name + ".png --html " + name + ".html";
    std::string page_file;
    {
      const ProgressPhase phase(demo.progress(), name);
      // As `volspline boundary --snap` with its defaults (the command in the gallery).
      BoundaryOptions options;
      options.snap = true;
      b = solid_boundary(e.volume, options);
      write_mesh(b.mesh, demo.path(name + ".ply"));
      write_png(render_mesh(b.mesh, RenderOptions{}), demo.path(name + ".png"));
      const nlohmann::json stats = {{"cells_examined", b.stats.cells_examined},
                                    {"cells_kept", b.stats.cells_kept},
                                    {"implicit_triangles", b.stats.triangles_of(Part::JacobianZero)},
                                    {"max_rel_jacobian_at_vertices", b.stats.max_rel_jacobian_at_vertices},
                                    {"max_domain_distance", b.stats.max_domain_distance},
                                    {"seconds", b.stats.seconds_total}};
      write_file_atomically(demo.path(name + "-stats.json"), json_text(stats) + "\n");
      Model model;
      model.objects.push_back({e.name, true, e.volume, nullptr});
      InteractivePage page;
      page.title = "boundary of " + e.name + ".json";
      page.mesh = b.mesh;
      page.info = model_page_info(model, e.name + ".json");
      page.info["boundary"] = stats;
      add_model_probes(page, model, {}, e.name + ".json");
      page_file = demo.write_page(name + ".html", std::move(page), command);
    }
    std::cout << name << ": " << e.description << "; " << b.stats.cells_examined << " cells examined, " << b.stats.cells_kept
              << " kept, " << b.stats.triangles_of(Part::JacobianZero) << " implicit triangles\n  " << demo.path(name + ".ply") << "\n  "
              << demo.path(name + ".png") << "\n  " << demo.path(name + "-stats.json") << "\n";
    demo.gallery().add({name,
                        "Boundary (faces and the implicit surface J = 0 in orange), " + e.description,
                        {name + ".png"},
                        command,
                        page_file});
  }
}

}  // namespace volspline::cli
