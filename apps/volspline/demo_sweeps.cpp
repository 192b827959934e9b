// The swept-solid examples of `volspline demo` (Conkey–Joy 2000, Figs. 4-8): for each, the
// paper's superset of the envelope beside the true, trimmed boundary, parts coloured by source
// (caps, face and edge sweeps, the rank-deficient set). Each starts from its model file in the
// repository's examples/ (copied into the demo folder's examples/; tests/construct check that
// the files are the constructions of construct/swept_examples.h) and is what the two
// `volspline sweep-envelope` commands the gallery prints make (Fig. 7, the turning folded
// cylinder, too since 2026-12-03: 2 s for its superset and 4 s trimmed at the demo's tolerance,
// docs/performance.md). The demo trims at 4 times the default
// tolerance (16 times fewer grid cells: 3-8 s per example instead of 50-160 s, the same at the
// pictures' size); the gallery says so. Fig. 4 is also shown cut open (`--cut-open`).
#include <iostream>

#include "commands.h"
#include "demo_gallery.h"
#include "cli_support.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_clipping.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/extract/swept_envelope.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {
namespace {

constexpr double kSweepDemoTolerance = 4e-3;

struct SweepDemoExample {
  std::string name, file, description;
  /// --view of both pictures.
  std::string view;
};

// Fig. 4 cut open by the plane y = 2 (the semicircle's middle), seen from the cut side: the
// superset's sheets inside the swept volume show, the trimmed boundary is a shell.
constexpr const char* kSweepDemoCut = "0,-1,0,-2";
constexpr const char* kSweepDemoCutView = "-0.5,1,-0.6";

// One `sweep-envelope` run of the gallery: the superset or the trimmed boundary, whole or cut
// open (then the files are NAME-cut-open[-superset].*).
std::string sweep_demo_command(const SweepDemoExample& e, bool superset, bool cut_open = false) {
  const std::string out = e.name + (cut_open ? "-cut-open" : "") + (superset ? "-superset" : "");
  return "volspline sweep-envelope examples/" + e.file + " --tol 4e-3" + (superset ? " --superset" : "") + " -o " + out + ".ply --png " +
         out + ".png --size 640,480 --view " + (cut_open ? std::string(kSweepDemoCutView) + " --cut-open " + kSweepDemoCut : e.view) +
         (superset || cut_open ? "" : " --html " + e.name + ".html");
}

void write_sweep_example(DemoRun& demo, const SweepDemoExample& example, const std::filesystem::path& examples) {
  if (!demo.wants(example.name)) return;
  const std::filesystem::path source = examples / example.file;
  if (!std::filesystem::exists(source)) {
    std::cout << example.name << ": skipped: " << source.string() << " not found; give the repository's examples folder with --examples\n";
    return;
  }
  const std::string model_file = "examples/" + example.file;
  create_output_directories(demo.dir() / "examples");
  std::error_code copy_error;
  std::filesystem::copy_file(source, demo.dir() / model_file, std::filesystem::copy_options::overwrite_existing, copy_error);
  if (copy_error) throw IoError("cannot copy " + source.string() + " into " + demo.path("examples") + ": " + copy_error.message());
  double volume = 0;
  bool closed = false;
  std::string page_file;
  const std::string command = sweep_demo_command(example, true) + " && " + sweep_demo_command(example, false);
  {
    const ProgressPhase phase(demo.progress(), example.name);
    const Model model = read_model(demo.dir() / model_file);
    const auto patches = swept_patches(std::get<SweptSolid>(model.objects.at(0).spline));
    SweptEnvelopeOptions options;
    options.tolerance = kSweepDemoTolerance;
    const SweptEnvelope superset = swept_envelope_superset(patches, options);
    const SweptEnvelope trimmed = trim_swept_envelope(patches, superset, options);
    volume = trimmed.stats.trimming.volume;
    closed = trimmed.stats.trimming.closed && trimmed.stats.trimming.oriented && trimmed.stats.trimming.self_intersection_free;
    RenderOptions render;
    render.width = 640;
    render.height = 480;
    render.view_direction = parse_view_direction(example.view, "view");
    write_mesh(superset.mesh, demo.path(example.name + "-superset.ply"));
    write_png(render_mesh(superset.mesh, render), demo.path(example.name + "-superset.png"));
    write_mesh(trimmed.mesh, demo.path(example.name + ".ply"));
    write_png(render_mesh(trimmed.mesh, render), demo.path(example.name + ".png"));
    if (example.name == "sweep-fig4") {
      RenderOptions open = render;
      open.view_direction = parse_view_direction(kSweepDemoCutView, "view");
      const std::vector<Plane> cut{parse_plane(kSweepDemoCut, "cut")};
      write_png(render_mesh(remove_convex_region(superset.mesh, cut), open), demo.path("sweep-fig4-cut-open-superset.png"));
      write_png(render_mesh(remove_convex_region(trimmed.mesh, cut), open), demo.path("sweep-fig4-cut-open.png"));
    }
    InteractivePage page;
    page.title = example.name + ": the trimmed envelope";
    page.mesh = trimmed.mesh;
    page.info = model_page_info(model, model_file);
    page.info["envelope"] = {{"tolerance", kSweepDemoTolerance}, {"volume", volume}, {"closed", closed}};
    page_file = demo.write_page(example.name + ".html", std::move(page), command);
  }
  const std::string description = example.description + "; left the paper's superset, right the trimmed boundary (volume " +
                                  std::to_string(volume) + (closed ? ", closed" : ", not closed") + "; tolerance 4e-3 of the diagonal, " +
                                  "4 times the default of sweep-envelope)";
  std::cout << example.name << ": " << description << "\n  " << demo.path(example.name + "-superset.png") << "\n  "
            << demo.path(example.name + ".png") << "\n";
  demo.gallery().add({example.name, description, {example.name + "-superset.png", example.name + ".png"}, command, page_file});
  if (example.name == "sweep-fig4") {
    demo.gallery().add({"sweep-fig4-cut-open",
                        "Conkey-Joy Fig. 4 cut open by the plane y = 2: the superset's sheets inside the swept volume (left) are what "
                        "trimming removes; the trimmed boundary (right) is a shell",
                        {"sweep-fig4-cut-open-superset.png", "sweep-fig4-cut-open.png"},
                        sweep_demo_command(example, true, true) + " && " + sweep_demo_command(example, false, true), page_file});
  }
}

}  // namespace

void write_sweeps_demo(DemoRun& demo, const std::filesystem::path& examples) {
  if (!demo.wants_group("sweep-", "swept solids' envelopes, Conkey-Joy Figs. 4-8")) return;
  const std::vector<SweepDemoExample> examples_to_write{
      {"sweep-fig4", "swept-torus-semicircle.json", "Conkey-Joy Fig. 4: a torus of four quarter patches along a semicircle, Frenet frame",
       "-0.4,-1,-0.9"},
      {"sweep-fig5", "swept-tumbling-cylinder.json", "Conkey-Joy Fig. 5: a cylinder tumbled 180 degrees along a line", "-0.3,-1,-0.5"},
      {"sweep-fig6", "swept-folded-cube-cubic.json", "Conkey-Joy Fig. 6: a cube with a protrusion (J123 = 0 on it) along a cubic",
       "-1,-1.3,-0.8"},
      {"sweep-fig7", "swept-turning-folded-cylinder.json", "Conkey-Joy Fig. 7: a folded cylinder turning about its linear path",
       "-1,-1,-0.4"},
      {"sweep-fig8", "swept-tumbling-folded-cube.json", "Conkey-Joy Fig. 8: the protrusion cube tumbled along a semicircle",
       "-0.4,-1,-0.9"},
  };
  for (const auto& e : examples_to_write) write_sweep_example(demo, e, examples);
}

}  // namespace volspline::cli
