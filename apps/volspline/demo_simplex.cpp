// The simplex-spline example of `volspline demo` (Hua–He–Qin Fig. 1): a cubic DMS spline solid
// over a single tetrahedron with 20 control points, its control points moved (§4.2), shown as
// shrunken cells so that its interior geometry is seen. The figures on real domains (Fig. 5, the
// torus with the "SM" skeleton; Fig. 6, the bunny) come from files: README.md's commands.
#include <cmath>
#include <iostream>

#include "commands.h"
#include "demo_gallery.h"
#include "volspline/extract/simplex_cells.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline::cli {

void write_simplex_demo(DemoRun& demo) {
  const std::string name = "simplex-tetrahedron-cubic";
  if (!demo.wants(name)) return;
  {
    const ProgressPhase phase(demo.progress(), name);
    const std::vector<Eigen::Vector3d> corners{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    TetrahedralMesh domain = delaunay_tetrahedralization(corners);
    KnotClouds clouds = generate_knot_clouds(domain, 3);
    DmsSplineVolume volume(std::move(domain), std::move(clouds), DmsControlSharing::Shared);
    // Editing by moving control points (§4.2): the solid bulges along z and twists about it.
    for (int r = 0; r < volume.control_vector_count(); ++r) {
      auto p = volume.control_vectors().row(r);
      const double x = p[0], y = p[1], z = p[2];
      p[0] = x - 0.6 * y * z + 0.3 * y * y;
      p[1] = y + 0.6 * x * z;
      p[2] = z + 1.2 * x * y;
    }
    Model model;
    model.objects.push_back({name, false, volume, nullptr});
    write_model(model, demo.path(name + ".json"));
    RenderOptions options;
    options.view_direction = Eigen::Vector3d(-1.0, -0.6, -0.5);
    options.edges = true;
    options.smooth_normals = false;
    write_png(render_mesh(simplex_cell_mesh(volume, 4, 0.7), options), demo.path(name + ".png"));
  }
  const std::string description = "Hua-He-Qin Fig. 1: a cubic DMS spline solid over one tetrahedron (20 control points, moved), "
                                  "as 64 shrunken cells";
  std::cout << name << ": " << description << "\n  " << demo.path(name + ".json") << "\n  " << demo.path(name + ".png") << "\n";
  demo.gallery().add({name, description, {name + ".png"},
                      demo_only_command(name) + " && volspline view " + name + ".json --cells 4 -o " + name + "-view.png"});
}

}  // namespace volspline::cli
