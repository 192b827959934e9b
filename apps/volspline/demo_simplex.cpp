// The simplex-spline examples of `volspline demo` (Hua–He–Qin):
// - Fig. 1: a cubic DMS spline solid over a single tetrahedron with 20 control points, its
//   control points moved (§4.2), shown as shrunken cells so that its interior geometry is seen;
// - Fig. 5: the solid torus of examples/torus-surface.off (Mesh_3) whose density comes from the
//   letters "SM" sketched as a skeleton (examples/skeletons/skeleton-torus-sm.json): X-ray and
//   isosurface;
// - Fig. 6: the bunny (../shared/data/volumes/bunny00.off) with an ellipsoid "stomach" and two
//   pipes as skeleton (examples/skeletons/skeleton-bunny-digestion.json): X-ray, isosurface and a
//   coloured slice. Skipped, with a message, where the data folder is absent.
// Figs. 5 and 6 start from files: their inputs are copied into the demo folder (examples/...,
// bunny00.off) and each gallery entry shows the `make simplex-spline` / `xray` / `view` commands
// that, run in that folder, make its picture; the demo does what those commands do.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "demo_gallery.h"
#include "view_command.h"
#include "volspline/core/error.h"
#include "volspline/extract/simplex_cells.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/surface_tetrahedralization.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"
#include "volspline/render/xray_image.h"
#include "volspline/simplex/attribute_assignment.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline::cli {
namespace {

void write_tetrahedron_demo(DemoRun& demo) {
  const std::string name = "simplex-tetrahedron-cubic";
  if (!demo.wants(name)) return;
  // The model is built here and is a file of the repository's examples/ (the same bytes); the
  // picture and the page are the `volspline view` command the gallery prints, run in the demo
  // folder.
  ViewArguments arguments;
  arguments.model = "examples/" + name + ".json";
  arguments.image = name + ".png";
  arguments.cells = 4;
  arguments.edges = true;
  arguments.camera = "-1,-0.6,-0.5";
  if (interactive_pages_available()) arguments.html = name + ".html";
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
    create_output_directories(demo.dir() / "examples");
    write_model(model, demo.path(arguments.model));
    ViewArguments run = arguments;
    run.model = demo.path(run.model);
    run.image = demo.path(run.image);
    if (!run.html.empty()) run.html = demo.path(run.html);
    std::ostringstream log;
    run_view(run, log);
  }
  const std::string description = "Hua-He-Qin Fig. 1: a cubic DMS spline solid over one tetrahedron (20 control points, moved), "
                                  "as 64 shrunken cells";
  std::cout << name << ": " << description << "\n  " << demo.path(arguments.model) << "\n  " << demo.path(arguments.image) << "\n";
  demo.gallery().add({name, description, {arguments.image}, view_command_line(arguments), arguments.html});
}

// A figure made from files: `volspline make simplex-spline --surface SURFACE --cell-size H
// --degree 2 --skeleton SKELETON -o MODEL`, then `xray` and `view` pictures of it.
struct SimplexFigure {
  std::string name;      // prefix of the model and pictures
  std::string figure;    // "Hua-He-Qin Fig. 5"
  std::string surface;   // relative to the demo folder
  std::string skeleton;  // relative to the demo folder
  std::string cell_size;  // --cell-size, as written in the command
  std::string xray_view, xray_up, xray_size;
  std::string iso;                   // --iso-attribute
  std::string camera;                // --camera of the views
  std::string plane;                 // --plane of the slice; empty: none
  std::string what_xray, what_iso, what_slice;
};

std::string make_command(const SimplexFigure& f) {
  return "volspline make simplex-spline --surface " + f.surface + " --cell-size " + f.cell_size +
         " --degree 2 --skeleton " + f.skeleton + " -o " + f.name + ".json";
}

XrayOptions xray_options(const SimplexFigure& f) {
  XrayOptions options;
  const auto number = [](const std::string& text, int count) {
    std::vector<double> v;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) v.push_back(std::stod(item));
    if (static_cast<int>(v.size()) != count) throw InvalidInput("demo: bad numbers '" + text + "'");
    return v;
  };
  const auto size = number(f.xray_size, 2), view = number(f.xray_view, 3), up = number(f.xray_up, 3);
  options.width = static_cast<int>(size[0]);
  options.height = static_cast<int>(size[1]);
  options.view_direction = Eigen::Vector3d(view[0], view[1], view[2]);
  options.up = Eigen::Vector3d(up[0], up[1], up[2]);
  return options;
}

std::string xray_command(const SimplexFigure& f) {
  return "volspline xray " + f.name + ".json -o " + f.name + "-xray.png --size " + f.xray_size + " --view " + f.xray_view + " --up " + f.xray_up;
}

ViewArguments view_arguments(const SimplexFigure& f, const std::string& image) {
  ViewArguments a;
  a.model = f.name + ".json";
  a.image = image;
  a.size = "640,480";
  a.camera = f.camera;
  return a;
}

void copy_input(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::filesystem::create_directories(to.parent_path());
  std::error_code ec;
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing, ec);
  if (ec) throw IoError("cannot copy " + from.string() + " to " + to.string() + ": " + ec.message());
}

// The model (as `make simplex-spline` builds it), then each wanted picture.
void write_figure(DemoRun& demo, const SimplexFigure& f) {
  const std::filesystem::path& dir = demo.dir();
  const std::string xray_name = f.name + "-xray", iso_name = f.name + "-iso", slice_name = f.name + "-slice";
  const bool xray = demo.wants(xray_name), iso = demo.wants(iso_name), slice = !f.plane.empty() && demo.wants(slice_name);
  if (!xray && !iso && !slice) return;
  {
    const ProgressPhase phase(demo.progress(), f.name);
    SurfaceTetrahedralizationOptions meshing;
    meshing.cell_size = std::stod(f.cell_size);
    TetrahedralMesh domain = tetrahedralize_closed_surface(read_mesh(dir / f.surface), meshing);
    KnotClouds clouds = generate_knot_clouds(domain, 2);
    DmsSplineVolume volume(std::move(domain), std::move(clouds), DmsControlSharing::Shared);
    const SkeletonField field = read_skeleton(dir / f.skeleton);
    assign_attribute(volume, "density", [&](const Eigen::Vector3d& x) { return field(x); }, AttributeAssignment::LeastSquares);
    Model model;
    model.objects.push_back({"simplex spline volume", false, std::move(volume), nullptr});
    write_model(model, dir / (f.name + ".json"));
  }
  const Model model = read_model(dir / (f.name + ".json"));
  const auto& volume = std::get<DmsSplineVolume>(model.objects[0].spline);
  std::cout << f.name << ": " << f.figure << ", degree 2 over " << volume.domain().tetrahedra.size() << " tetrahedra\n  "
            << demo.path(f.name + ".json") << "\n";
  if (xray) {
    {
      const ProgressPhase phase(demo.progress(), xray_name);
      const XrayRenderer renderer(volume, xray_options(f));
      write_png(renderer.image(), demo.path(xray_name + ".png"));
    }
    demo.gallery().add({xray_name, f.figure + ": " + f.what_xray, {xray_name + ".png"}, make_command(f) + " && " + xray_command(f)});
    std::cout << "  " << demo.path(xray_name + ".png") << "\n";
  }
  const auto view = [&](const std::string& name, const ViewArguments& a, const std::string& what) {
    ViewArguments arguments = a;
    if (interactive_pages_available()) arguments.html = name + ".html";
    ViewArguments run = arguments;
    run.model = (dir / a.model).string();
    run.image = (dir / a.image).string();
    if (!run.html.empty()) run.html = (dir / run.html).string();
    {
      const ProgressPhase phase(demo.progress(), name);
      std::ostringstream log;
      run_view(run, log);
    }
    demo.gallery().add({name, f.figure + ": " + what, {a.image}, make_command(f) + " && " + view_command_line(arguments), arguments.html});
    std::cout << "  " << run.image << "\n";
  };
  if (iso) {
    ViewArguments a = view_arguments(f, iso_name + ".png");
    a.iso_attribute = {f.iso};
    view(iso_name, a, f.what_iso);
  }
  if (slice) {
    ViewArguments a = view_arguments(f, slice_name + ".png");
    a.planes = {f.plane};
    a.color = "density";
    view(slice_name, a, f.what_slice);
  }
}

}  // namespace

void write_simplex_demo(DemoRun& demo, const SimplexDemoInputs& inputs) {
  write_tetrahedron_demo(demo);
  const std::filesystem::path& dir = demo.dir();

  const SimplexFigure torus{"simplex-torus-sm", "Hua-He-Qin Fig. 5",
                            "examples/torus-surface.off", "examples/skeletons/skeleton-torus-sm.json", "0.3",
                            "0,0,-1", "0,1,0", "320,320", "density:0.55", "-0.3,0.5,-1", "",
                            "X-ray of a solid torus whose density comes from the letters \"SM\" sketched inside it as a skeleton (from above)",
                            "the isosurface density = 0.55, closed around the skeleton letters \"SM\"", ""};
  if (demo.wants_group(torus.name, "simplex-torus-sm-xray, simplex-torus-sm-iso")) {
    const std::filesystem::path surface = inputs.examples / "torus-surface.off", skeleton = inputs.examples / "skeletons" / "skeleton-torus-sm.json";
    if (std::filesystem::exists(surface) && std::filesystem::exists(skeleton)) {
      copy_input(surface, dir / torus.surface);
      copy_input(skeleton, dir / torus.skeleton);
      write_figure(demo, torus);
    } else {
      demo.wants(torus.name + "-xray"), demo.wants(torus.name + "-iso");
      std::cout << torus.name << ": skipped (Fig. 5): " << surface.string() << " or " << skeleton.string()
                << " not found; give the repository's examples folder with --examples\n";
    }
  }

  const SimplexFigure bunny{"simplex-bunny", "Hua-He-Qin Fig. 6",
                            "bunny00.off", "examples/skeletons/skeleton-bunny-digestion.json", "0.09",
                            "0,0,-1", "0,1,0", "320,320", "density:0.7", "0,0,-1,0,1,0", "0,0,1,0",
                            "X-ray of the bunny whose density comes from an ellipsoid \"stomach\" and two pipes (a skeleton)",
                            "the isosurface density = 0.7: the stomach and the two pipes, closed (seen as in the X-ray)",
                            "the slice z = 0 coloured by density, bright along the digestive tract"};
  if (demo.wants_group(bunny.name, "simplex-bunny-xray, simplex-bunny-iso, simplex-bunny-slice")) {
    const std::filesystem::path surface = inputs.data / "volumes" / "bunny00.off",
                                skeleton = inputs.examples / "skeletons" / "skeleton-bunny-digestion.json";
    if (std::filesystem::exists(surface) && std::filesystem::exists(skeleton)) {
      copy_input(surface, dir / bunny.surface);
      copy_input(skeleton, dir / bunny.skeleton);
      write_figure(demo, bunny);
    } else {
      demo.wants(bunny.name + "-xray"), demo.wants(bunny.name + "-iso"), demo.wants(bunny.name + "-slice");
      std::cout << bunny.name << ": skipped (Fig. 6): " << surface.string() << " or " << skeleton.string()
                << " not found; give the folder holding volumes/bunny00.off with --data\n";
    }
  }
}

}  // namespace volspline::cli
