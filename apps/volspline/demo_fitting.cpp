// The fitting examples of `volspline demo` (Hua–He–Qin §5, issue 14), each picture made by the
// commands its gallery entry shows, run in the demo folder:
// - fire_ug's temperature (../shared/data/volumes/fire_ug.vtu, the paper's spx-like set): the
//   data's point view, the X-ray and an isosurface of the fit with placed knots (Figs. 7, 10-12);
//   skipped, with a message, where the data folder is absent;
// - Marschner–Lobb sampled 41³: the isosurface ρ = 0.5 of the fit beside the analytic one (the
//   formula sampled 121³) and the 41³ samples' own;
// - a jump of 1 across a tilted plane (two-material:21:0.37): slices of the fit with fixed knots
//   beside the fit with knots on the jump (`--jump`, §4.2).
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "demo_gallery.h"
#include "fit_command.h"
#include "view_command.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"
#include "volspline/io/volume_data.h"
#include "volspline/pipeline/fit_baselines.h"
#include "volspline/pipeline/grid_isosurface.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"
#include "volspline/render/point_cloud_image.h"
#include "volspline/render/xray_image.h"

namespace volspline::cli {
namespace {

// `volspline fit` run in the demo folder (its report kept out of the demo's).
void fit_in(DemoRun& demo, FitArguments a) {
  const bool generated = a.data.rfind("marschner-lobb:", 0) == 0 || a.data.rfind("two-material:", 0) == 0;
  if (!generated && std::filesystem::path(a.data).is_relative()) a.data = demo.path(a.data);
  a.out = demo.path(a.out);
  if (!a.stats.empty()) a.stats = demo.path(a.stats);
  std::ostringstream log;
  run_fit(a, log);
}

void view_in(DemoRun& demo, ViewArguments a) {
  a.model = demo.path(a.model);
  a.image = demo.path(a.image);
  std::ostringstream log;
  run_view(a, log);
}

const char* const kFireView = "-0.3,1,-0.4";

void write_fire(DemoRun& demo, const std::filesystem::path& data_folder) {
  const std::string data_name = "fit-fire-data", xray_name = "fit-fire-xray", iso_name = "fit-fire-iso";
  if (!demo.wants_group("fit-fire", "fit-fire-data, fit-fire-xray, fit-fire-iso")) return;
  const bool data_picture = demo.wants(data_name), xray = demo.wants(xray_name), iso = demo.wants(iso_name);
  const std::filesystem::path source = data_folder / "volumes" / "fire_ug.vtu";
  if (!std::filesystem::exists(source)) {
    std::cout << "fit-fire: skipped: " << source.string() << " not found; give the folder holding volumes/fire_ug.vtu with --data\n";
    return;
  }
  std::filesystem::create_directories(demo.dir());
  std::filesystem::copy_file(source, demo.dir() / "fire_ug.vtu", std::filesystem::copy_options::overwrite_existing);
  const std::string cut = "0,-1,0,-1.25";
  if (data_picture) {
    const ProgressPhase phase(demo.progress(), data_name);
    // As `volspline data fire_ug.vtu --png ... --attribute t --cut-open ... --view ...`.
    const VolumeData data = read_volume_data(demo.path("fire_ug.vtu"));
    const auto column = data.attribute_column("t");
    const std::vector<double> t(data.attributes.col(column).begin(), data.attributes.col(column).end());
    PointCloudPictureOptions picture;
    picture.cut = Plane{Eigen::Vector3d(0, -1, 0), -1.25};
    picture.render.view_direction = Eigen::Vector3d(-0.3, 1, -0.4);
    write_png(point_cloud_image(data.points, t, "t", picture), demo.path(data_name + ".png"));
    demo.gallery().add({data_name,
                        "fire_ug.vtu (a fire simulation's unstructured grid, 12,323 points): the points coloured by temperature, the half "
                        "y < 1.25 left out to show the plume inside",
                        {data_name + ".png"},
                        "volspline data fire_ug.vtu --png " + data_name + ".png --attribute t --cut-open " + cut + " --view " + kFireView});
    std::cout << data_name << ": " << demo.path(data_name + ".png") << "\n";
  }
  if (!xray && !iso) return;
  FitArguments fit;
  fit.data = "fire_ug.vtu";
  fit.out = "fit-fire.json";
  fit.stats = "fit-fire-stats.json";
  fit.attributes = "t";
  fit.primary_knots = 250;
  fit.knots = "place";
  const std::string fit_command = "volspline fit fire_ug.vtu --attributes t --primary-knots 250 --knots place -o fit-fire.json --stats fit-fire-stats.json";
  {
    const ProgressPhase phase(demo.progress(), "fit-fire");
    fit_in(demo, fit);
  }
  if (xray) {
    const ProgressPhase phase(demo.progress(), xray_name);
    // As `volspline xray fit-fire.json -o ... --view ...`.
    const Model model = read_model(demo.path("fit-fire.json"));
    XrayOptions options;
    options.view_direction = Eigen::Vector3d(-0.3, 1, -0.4);
    options.baseline = 298;
    write_png(XrayRenderer(std::get<DmsSplineVolume>(model.objects.at(0).spline), options).image(), demo.path(xray_name + ".png"));
    demo.gallery().add({xray_name,
                        "Hua-He-Qin §5 (cf. Figs. 7, 10-12): the X-ray of the temperature above the ambient 298 K (--baseline), fitted with 250 placed primary knots (0.15 "
                        "coefficients per point; fit-fire-stats.json gives Table 1's columns)",
                        {xray_name + ".png"},
                        fit_command + " && volspline xray fit-fire.json -o " + xray_name + ".png --baseline 298 --view " + kFireView});
    std::cout << xray_name << ": " << demo.path(xray_name + ".png") << "\n";
  }
  if (iso) {
    ViewArguments a;
    a.model = "fit-fire.json";
    a.image = iso_name + ".png";
    a.iso_attribute = {"t:450"};
    a.camera = kFireView;
    {
      const ProgressPhase phase(demo.progress(), iso_name);
      view_in(demo, a);
    }
    demo.gallery().add({iso_name, "the fit's isosurface t = 450 K: the hot plume", {a.image}, fit_command + " && " + view_command_line(a)});
    std::cout << iso_name << ": " << demo.path(a.image) << "\n";
  }
}

const char* const kMarschnerLobbView = "-0.6,-1,-0.7";

void write_marschner_lobb(DemoRun& demo) {
  const std::string truth_name = "fit-marschner-lobb-truth", data_name = "fit-marschner-lobb-data", fit_name = "fit-marschner-lobb-fit";
  if (!demo.wants_group("fit-marschner-lobb", "fit-marschner-lobb-truth, fit-marschner-lobb-data, fit-marschner-lobb-fit")) return;
  const bool truth = demo.wants(truth_name), data = demo.wants(data_name), fit = demo.wants(fit_name);
  // As `volspline data marschner-lobb:N --iso rho:0.5 --png ... --view ...`.
  auto grid_iso = [&](int n, const std::string& name) {
    const ProgressPhase phase(demo.progress(), name);
    const auto grid = regular_grid_of(marschner_lobb_data(n));
    RenderOptions render;
    render.color = ColorMode::Single;
    render.view_direction = Eigen::Vector3d(-0.6, -1, -0.7);
    write_png(render_mesh(grid_isosurface(*grid, "rho", 0.5), render), demo.path(name + ".png"));
    std::cout << name << ": " << demo.path(name + ".png") << "\n";
    return "volspline data marschner-lobb:" + std::to_string(n) + " --iso rho:0.5 --png " + name + ".png --view " + kMarschnerLobbView;
  };
  if (truth)
    demo.gallery().add({truth_name,
                        "Marschner-Lobb (f_M = 6), the analytic isosurface rho = 0.5: the formula sampled 121^3, linear on the grid's "
                        "tetrahedra",
                        {truth_name + ".png"},
                        grid_iso(121, truth_name)});
  if (data)
    demo.gallery().add({data_name,
                        "the same isosurface of the 41^3 samples a fit is given (linear on the grid's tetrahedra): about 3.4 samples per "
                        "ripple, so they alias",
                        {data_name + ".png"},
                        grid_iso(41, data_name)});
  if (fit) {
    FitArguments f;
    f.data = "marschner-lobb:41";
    f.out = "fit-marschner-lobb.json";
    f.stats = "fit-marschner-lobb-stats.json";
    ViewArguments a;
    a.model = "fit-marschner-lobb.json";
    a.image = fit_name + ".png";
    a.iso_attribute = {"rho:0.5"};
    a.camera = kMarschnerLobbView;
    {
      const ProgressPhase phase(demo.progress(), fit_name);
      fit_in(demo, f);
      view_in(demo, a);
    }
    demo.gallery().add({fit_name,
                        "the quadratic simplex spline fitted to the 41^3 samples (lattice knots, faired; docs/fitting.md gives its error "
                        "against the formula beside the tensor product's): the central bump and the inner rings are kept, the outer "
                        "ripples, near the samples' resolution, are not",
                        {a.image},
                        "volspline fit marschner-lobb:41 -o fit-marschner-lobb.json --stats fit-marschner-lobb-stats.json && " +
                            view_command_line(a)});
    std::cout << fit_name << ": " << demo.path(a.image) << "\n";
  }
}

void write_jump(DemoRun& demo) {
  const std::string fixed_name = "fit-jump-fixed-knots", aligned_name = "fit-jump-aligned-knots";
  if (!demo.wants_group("fit-jump", "fit-jump-fixed-knots, fit-jump-aligned-knots")) return;
  for (const bool aligned : {false, true}) {
    const std::string name = aligned ? aligned_name : fixed_name;
    if (!demo.wants(name)) continue;
    FitArguments f;
    f.data = "two-material:21:0.37";
    f.out = name + ".json";
    if (aligned) f.jump = 0.3;
    ViewArguments a;
    a.model = name + ".json";
    a.image = name + ".png";
    a.slices = {"z:3"};
    a.color = "material";
    a.range = "1,2.2";
    a.camera = "0.3,-0.6,-1";
    {
      const ProgressPhase phase(demo.progress(), name);
      fit_in(demo, f);
      view_in(demo, a);
    }
    demo.gallery().add({name,
                        aligned ? "the same data fitted with knots on the jump (--jump 0.3, §4.2): the jump stays sharp, the spline is "
                                  "discontinuous across the interface and smooth on each side"
                                : "a jump of 1 across the tilted plane x + 0.37 y = 0.5 (21^3 samples) fitted with knots that do not "
                                  "follow it: smeared over the tetrahedra that straddle it, with over- and undershoots",
                        {a.image},
                        "volspline fit two-material:21:0.37" + std::string(aligned ? " --jump 0.3" : "") + " -o " + name + ".json && " +
                            view_command_line(a)});
    std::cout << name << ": " << demo.path(a.image) << "\n";
  }
}

}  // namespace

void write_fitting_demo(DemoRun& demo, const SimplexDemoInputs& inputs) {
  write_fire(demo, inputs.data);
  write_marschner_lobb(demo);
  write_jump(demo);
}

}  // namespace volspline::cli
