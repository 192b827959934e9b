// The boundary-determination examples of `volspline demo` (Joy–Duchaineau Figs. 1, 10, 11, 13):
// faces plus implicit surface, a picture, and the statistics.
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "volspline/analysis/solid_boundary.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void write_boundary_demo(const std::filesystem::path& dir) {
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
    BoundaryOptions options;
    options.snap = true;
    const SolidBoundary b = solid_boundary(e.volume, options);
    const std::filesystem::path base = dir / (e.name + "-boundary");
    write_mesh(b.mesh, base.string() + ".ply");
    RenderOptions render;
    write_png(render_mesh(b.mesh, render), base.string() + ".png");
    const nlohmann::json stats = {{"cells_examined", b.stats.cells_examined},
                                  {"cells_kept", b.stats.cells_kept},
                                  {"implicit_triangles", b.stats.triangles[6]},
                                  {"max_rel_jacobian_at_vertices", b.stats.max_rel_jacobian_at_vertices},
                                  {"max_domain_distance", b.stats.max_domain_distance},
                                  {"seconds", b.stats.seconds_total}};
    write_file_atomically(base.string() + "-stats.json", stats.dump(2) + "\n");
    std::cout << e.name << "-boundary: " << e.description << "; " << b.stats.cells_examined << " cells examined, "
              << b.stats.cells_kept << " kept, " << b.stats.triangles[6] << " implicit triangles\n  " << base.string()
              << ".ply\n  " << base.string() << ".png\n  " << base.string() << "-stats.json\n";
  }
}

}  // namespace volspline::cli
