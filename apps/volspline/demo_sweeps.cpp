// The swept-solid examples of `volspline demo` (Conkey–Joy 2000, Figs. 4-8): for each, the
// paper's superset of the envelope (left) beside the true, trimmed boundary (right), parts
// coloured by source (caps, face and edge sweeps, the rank-deficient set); and one cut-open view
// of Fig. 4, where the superset's sheets inside the swept volume show and the trimmed boundary
// is a shell. Fig. 7 (the turning folded cylinder) is left out of the default demo: its
// rank-deficient set alone takes about 45 s (docs/performance.md); `--only sweep-fig7` makes it.
// The demo trims at 4 times the default tolerance (16 times fewer grid cells: 3-8 s per example
// instead of 50-160 s, the same at the pictures' size); the gallery says so.
#include <iostream>

#include "commands.h"
#include "demo_gallery.h"
#include "volspline/construct/swept_examples.h"
#include "volspline/extract/swept_envelope.h"
#include "volspline/mesh/mesh_clipping.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {
namespace {

// Two pictures side by side, of equal height.
Image sweep_demo_side_by_side(const Image& left, const Image& right) {
  Image both(left.width + right.width, left.height);
  for (int y = 0; y < left.height; ++y) {
    for (int x = 0; x < left.width; ++x) std::copy_n(left.pixel(x, y), 4, both.pixel(x, y));
    for (int x = 0; x < right.width; ++x) std::copy_n(right.pixel(x, y), 4, both.pixel(left.width + x, y));
  }
  return both;
}

constexpr double kSweepDemoTolerance = 4e-3;

struct SweepDemoExample {
  std::string name, description;
  SweptSolid (*solid)();
  Eigen::Vector3d view;
  bool by_default = true;
};

void write_sweep_example(DemoRun& demo, const SweepDemoExample& example) {
  if (!demo.wants(example.name) || (!example.by_default && !demo.selective())) return;
  const std::string picture = example.name + ".png";
  double volume = 0;
  bool closed = false;
  std::string page_file;
  {
    const ProgressPhase phase(demo.progress(), example.name);
    const auto patches = swept_patches(example.solid());
    SweptEnvelopeOptions options;
    options.tolerance = kSweepDemoTolerance;
    options.trim = false;
    const SweptEnvelope superset = swept_envelope_superset(patches, options);
    options.trim = true;
    const SweptEnvelope trimmed = swept_envelope(patches, options);
    volume = trimmed.stats.trimming.volume;
    closed = trimmed.stats.trimming.closed && trimmed.stats.trimming.oriented && trimmed.stats.trimming.self_intersection_free;
    InteractivePage page;
    page.title = example.name + ": the trimmed envelope";
    page.mesh = trimmed.mesh;
    page.info = {{"description", example.description}, {"volume", volume}, {"closed", closed}};
    page_file = demo.write_page(example.name + ".html", std::move(page), demo_only_command(example.name));
    RenderOptions render;
    render.width = 640;
    render.height = 480;
    render.view_direction = example.view;
    write_png(sweep_demo_side_by_side(render_mesh(superset.mesh, render), render_mesh(trimmed.mesh, render)), demo.path(picture));
    if (example.name == "sweep-fig4") {
      // Cut open by the plane y = 2 (the semicircle's middle, seen from the cut side).
      const std::vector<Plane> cut{plane_through({0, 2, 0}, {0, -1, 0})};
      RenderOptions open = render;
      open.view_direction = Eigen::Vector3d(-0.5, 1.0, -0.6);
      write_png(sweep_demo_side_by_side(render_mesh(remove_convex_region(superset.mesh, cut), open),
                                        render_mesh(remove_convex_region(trimmed.mesh, cut), open)),
                demo.path("sweep-fig4-cut-open.png"));
    }
  }
  const std::string description = example.description + "; left the paper's superset, right the trimmed boundary (volume " +
                                  std::to_string(volume) + (closed ? ", closed" : ", not closed") + "; tolerance 4e-3 of the diagonal, " +
                                  "4 times the default of sweep-envelope)";
  std::cout << example.name << ": " << description << "\n  " << demo.path(picture) << "\n";
  std::vector<std::string> pictures{picture};
  if (example.name == "sweep-fig4") pictures.push_back("sweep-fig4-cut-open.png");
  demo.gallery().add({example.name, description, pictures, demo_only_command(example.name), page_file});
}

}  // namespace

void write_sweeps_demo(DemoRun& demo) {
  if (!demo.wants_group("sweep-", "swept solids' envelopes, Conkey-Joy Figs. 4-8")) return;
  const std::vector<SweepDemoExample> examples{
      {"sweep-fig4", "Conkey-Joy Fig. 4: a torus of four quarter patches along a semicircle, Frenet frame", torus_along_semicircle,
       {-0.4, -1.0, -0.9}},
      {"sweep-fig5", "Conkey-Joy Fig. 5: a cylinder tumbled 180 degrees along a line", tumbling_cylinder, {-0.3, -1.0, -0.5}},
      {"sweep-fig6", "Conkey-Joy Fig. 6: a cube with a protrusion (J123 = 0 on it) along a cubic", folded_cube_along_cubic,
       {-1.0, -1.3, -0.8}},
      {"sweep-fig7", "Conkey-Joy Fig. 7: a folded cylinder turning about its linear path", turning_folded_cylinder, {-1.0, -1.0, -0.4},
       false},
      {"sweep-fig8", "Conkey-Joy Fig. 8: the protrusion cube tumbled along a semicircle", tumbling_folded_cube, {-0.4, -1.0, -0.9}},
  };
  for (const auto& e : examples) write_sweep_example(demo, e);
}

}  // namespace volspline::cli
