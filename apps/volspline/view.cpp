// volspline view MODEL -o IMAGE.png [--iso u:N] [--through U,V,W] [--slices AXIS:N]
//   [--plane NX,NY,NZ,D] [--core X,Y,Z] [--paddlewheel AXIS:N[@X,Y,Z]] [--faces]
//   [--color jacobian|u|v|w|ATTRIBUTE] [--range MIN,MAX] [--mesh OUT] [--camera DX,DY,DZ[,UX,UY,UZ]]
//   [--size W,H]: looking inside a solid (Lasser 1994 §IV).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "view_command.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/core/progress.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/pipeline/solid_view_picture.h"
#include "volspline/extract/simplex_isosurface.h"
#include "volspline/extract/simplex_slices.h"
#include "volspline/extract/simplex_cells.h"

#include <Eigen/Geometry>
#include "volspline/io/atomic_file.h"
#include "volspline/render/color_bar.h"

namespace volspline::cli {
namespace {

// "NAME:N" with NAME one of `names` (its index is returned) and N >= 1.
std::pair<int, int> parse_named_count(const std::string& text, const std::string& names, const std::string& option) {
  const auto colon = text.find(':');
  const std::string name = text.substr(0, colon);
  if (colon == std::string::npos || name.size() != 1 || names.find(name[0]) == std::string::npos) {
    throw InvalidInput("expected " + std::string(1, names[0]) + ":N, " + std::string(1, names[1]) + ":N or " +
                           std::string(1, names[2]) + ":N, got '" + text + "'",
                       option);
  }
  const int count = parse_integers(text.substr(colon + 1), 1, 1, option)[0];
  if (count > 1000) throw InvalidInput("expected at most 1000 surfaces, got '" + text + "'", option);
  return {static_cast<int>(names.find(name[0])), count};
}

Eigen::Vector3d vector3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

SolidViewRequest request_from(const ViewArguments& a) {
  SolidViewRequest request;
  request.resolution = a.resolution;
  request.faces = a.faces;
  request.cutaway = a.cutaway;
  if (a.cutaway && a.planes.empty() && a.core.empty())
    throw InvalidInput("a cutaway needs a cross section (--plane) or a core section (--core) to cut along", "--cutaway");
  for (const auto& s : a.iso) {
    const auto [direction, count] = parse_named_count(s, "uvw", "--iso");
    request.families.push_back({direction, count});
  }
  if (!a.through.empty()) {
    const auto t = parse_numbers(a.through, 3, "--through");
    request.through = std::array<double, 3>{t[0], t[1], t[2]};
  }
  for (const auto& s : a.slices) {
    const auto [axis, count] = parse_named_count(s, "xyz", "--slices");
    request.series.push_back({axis, count});
  }
  for (const auto& s : a.planes) {
    request.planes.push_back(parse_plane(s, "--plane"));
  }
  if (!a.core.empty()) request.core = vector3(parse_numbers(a.core, 3, "--core"));
  for (const auto& s : a.paddlewheels) {
    const auto at = s.find('@');
    const auto [axis, count] = parse_named_count(s.substr(0, at), "xyz", "--paddlewheel");
    SolidViewRequest::Paddlewheel wheel{axis, count, std::nullopt};
    if (at != std::string::npos) wheel.point = vector3(parse_numbers(s.substr(at + 1), 3, "--paddlewheel"));
    request.paddlewheels.push_back(wheel);
  }
  if (request.probes_empty()) request.faces = true;  // nothing inside asked for: show the solid
  return request;
}

// The render options of the arguments: size, camera, edges, background.
RenderOptions render_options_from(const ViewArguments& a) {
  const auto wh = parse_integers(a.size, 2, 16, "--size");
  if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + a.size + "'", "--size");
  RenderOptions options;
  options.width = wh[0];
  options.height = wh[1];
  options.edges = a.edges;
  options.transparent_background = a.transparent;
  if (!a.camera.empty()) {
    const auto count = std::count(a.camera.begin(), a.camera.end(), ',') + 1;
    const auto c = parse_numbers(a.camera, count == 6 ? 6 : 3, "--camera");
    options.view_direction = Eigen::Vector3d(c[0], c[1], c[2]);
    if (count == 6) options.up = Eigen::Vector3d(c[3], c[4], c[5]);
    if (options.view_direction.norm() == 0) throw InvalidInput("the view direction must not be zero", "--camera");
  }
  return options;
}

SolidViewPictureRequest picture_request_from(const ViewArguments& a) {
  SolidViewPictureRequest request;
  request.render = render_options_from(a);
  if (!a.range.empty()) {
    const auto r = parse_numbers(a.range, 2, "--range");
    if (!(r[0] < r[1])) throw InvalidInput("expected MIN < MAX, got '" + a.range + "'", "--range");
    request.range = std::pair(r[0], r[1]);
  }
  request.view = request_from(a);
  if (!a.color.empty()) request.color = scalar_field_named(a.color);
  request.source_name = a.model;
  return request;
}

// The picture and, with --mesh, the mesh: both prepared before either is committed, so a failure
// leaves neither behind.
void write_picture_and_mesh(const ViewArguments& a, const std::string& png, const TriangleMesh& mesh, MeshFormat format,
                            MeshWriteOptions options) {
  if (a.mesh.empty()) {
    write_file_atomically(a.image, png);
    return;
  }
  options.ascii = a.ascii;
  AtomicFile mesh_file(a.mesh);
  mesh_file.stream() << mesh_bytes(mesh, format, options);
  AtomicFile picture_file(a.image);
  picture_file.stream() << png;
  mesh_file.commit();
  picture_file.commit();
}

// A simplex spline volume: the isosurfaces ATTRIBUTE:VALUE of its attributes (Hua–He–Qin §6.2),
// each its own colour of the attribute-isosurface part, shaded with the analytic normals' mesh.
void run_simplex_view(const ViewArguments& a, const Model& model, const DmsSplineVolume& volume, std::ostream& out) {
  for (const char* option : {"--iso", "--through", "--core", "--paddlewheel", "--faces", "--cutaway"}) {
    const bool given = (std::string(option) == "--iso" && !a.iso.empty()) || (std::string(option) == "--through" && !a.through.empty()) ||
                       (std::string(option) == "--core" && !a.core.empty()) || (std::string(option) == "--paddlewheel" && !a.paddlewheels.empty()) ||
                       (std::string(option) == "--faces" && a.faces) || (std::string(option) == "--cutaway" && a.cutaway);
    if (given) throw InvalidInput(std::string(option) + " works on tensor-product volumes; a simplex_spline_volume takes --iso-attribute, --slices and --plane", option);
  }
  if (a.iso_attribute.empty() && a.slices.empty() && a.planes.empty() && (a.iso_edge != 0 || a.iso_subdivisions != 0))
    throw InvalidInput("--iso-edge and --iso-subdivisions set how isosurfaces and slices sample the domain; give --iso-attribute NAME:VALUE, "
                       "--slices or --plane",
                       a.iso_edge != 0 ? "--iso-edge" : "--iso-subdivisions");
  if (a.iso_edge != 0 && a.iso_subdivisions != 0)
    throw InvalidInput("give either --iso-edge (local bisection) or --iso-subdivisions (uniform), not both", "--iso-edge");
  if (a.iso_attribute.empty() && a.slices.empty() && a.planes.empty() && a.cells == 0)
    throw InvalidInput("a simplex_spline_volume is shown by isosurfaces (--iso-attribute NAME:VALUE), slices (--slices AXIS:N, "
                       "--plane NX,NY,NZ,D) and shrunken cells (--cells K), or use `volspline xray`",
                       "--iso-attribute");
  TriangleMesh mesh;
  std::vector<double> scalars;
  std::string summary;
  const std::string color = a.color.empty() && !volume.attribute_names().empty() ? volume.attribute_names().front() : a.color;
  for (const std::string& text : a.iso_attribute) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) throw InvalidInput("expected NAME:VALUE, got '" + text + "'", "--iso-attribute");
    SimplexIsosurfaceOptions options;
    options.attribute = text.substr(0, colon);
    options.value = parse_numbers(text.substr(colon + 1), 1, "--iso-attribute")[0];
    options.target_edge = a.iso_edge;
    options.subdivisions = a.iso_subdivisions;
    const SimplexIsosurface surface = [&] {
      try {
        return simplex_isosurface(volume, options);
      } catch (const InvalidInput& e) {
        throw InvalidInput(e.message(), "--iso-attribute " + text);
      }
    }();
    mesh.append(surface.mesh);
    scalars.insert(scalars.end(), surface.mesh.num_vertices(), options.value);
    summary += "; " + text + ": " + std::to_string(surface.mesh.num_triangles()) + " triangles from " +
               std::to_string(surface.sampled_tetrahedra) + " tetrahedra (" +
               (surface.subdivisions > 0 ? "k = " + std::to_string(surface.subdivisions) : std::string("local bisection")) + ")";
  }
  if (a.cells > 0) {
    const TriangleMesh cells = simplex_cell_mesh(volume, a.cells);
    mesh.append(cells);
    scalars.insert(scalars.end(), cells.num_vertices(), 0.0);
    summary += "; " + std::to_string(cells.num_triangles() / 4) + " cells";
  }
  std::vector<Plane> planes;
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : volume.domain().points) box.extend(p);
  for (const auto& text : a.slices) {
    const auto [axis, count] = parse_named_count(text, "xyz", "--slices");
    for (int i = 0; i < count; ++i) {
      Plane plane{Eigen::Vector3d::Unit(axis), box.min()[axis] + (box.max()[axis] - box.min()[axis]) * (i + 1) / (count + 1)};
      planes.push_back(plane);
    }
  }
  for (const auto& text : a.planes) {
    planes.push_back(parse_plane(text, "--plane"));
  }
  SimplexSliceOptions slice_options;
  slice_options.attribute = color;
  slice_options.target_edge = a.iso_edge;
  slice_options.subdivisions = a.iso_subdivisions;
  const std::vector<SimplexSlice> slices = [&] {
    try {
      return simplex_plane_slices(volume, planes, slice_options);
    } catch (const InvalidInput& e) {
      throw InvalidInput(e.message(), e.message().rfind("no attribute", 0) == 0 ? "--color" : "--plane");
    }
  }();
  long long sliced_tetrahedra = 0;
  for (const SimplexSlice& slice : slices) {
    mesh.append(slice.mesh);
    sliced_tetrahedra = slice.sampled_tetrahedra;
    if (slice.values.empty()) scalars.insert(scalars.end(), slice.mesh.num_vertices(), 0.0);
    else scalars.insert(scalars.end(), slice.values.begin(), slice.values.end());
  }
  if (!planes.empty())
    summary += "; " + std::to_string(planes.size()) + " slice(s) through " + std::to_string(sliced_tetrahedra) + " tetrahedra (" +
               (a.iso_subdivisions > 0 ? "k = " + std::to_string(a.iso_subdivisions) : std::string("local bisection")) + ")";
  RenderOptions render = render_options_from(a);
  const bool colored = !planes.empty() && !color.empty();
  if (colored) {
    render.color = ColorMode::Scalar;
    render.vertex_scalars = scalars;
    render.color_bar_title = color;
    if (!a.range.empty()) {
      const auto r = parse_numbers(a.range, 2, "--range");
      render.scalar_min = r[0], render.scalar_max = r[1];
    }
  }
  const std::string png = png_bytes(render_mesh(mesh, render));
  const MeshFormat mesh_format = a.mesh.empty() ? MeshFormat::Ply : mesh_format_from_path(a.mesh);
  write_picture_and_mesh(a, png, mesh, mesh_format, MeshWriteOptions{});
  if (!a.html.empty()) {
    InteractivePage page;
    page.title = "view of " + a.model;
    page.mesh = mesh;
    page.info = model_page_info(model, a.model);
    page.info["view"] = summary.size() > 2 ? summary.substr(2) : summary;
    if (colored) {
      const auto [lo, hi] = scalar_range(mesh, render);
      page.vertex_scalars = scalars;
      page.color_bar = ColorBar{render.colormap, lo, hi, color};
    }
    write_html_page(a.html, std::move(page));
  }
  out << "wrote " << a.image << ": " << mesh.num_triangles() << " triangles" << summary;
  if (colored) {
    const auto [lo, hi] = scalar_range(mesh, render);
    out << "; " << color << " in [" << color_bar_label(lo) << ", " << color_bar_label(hi) << "]";
  }
  out << "\n";
  if (!a.mesh.empty()) out << "wrote " << a.mesh << "\n";
}

}  // namespace

void run_view(const ViewArguments& a, std::ostream& out, Progress* progress) {
  if (std::filesystem::path(a.image).extension() != ".png")
    throw InvalidInput("expected a picture file name ending in .png, got '" + a.image + "'", "--output");
  check_html_option(a.html);
  if (!a.iso_attribute.empty() || std::filesystem::path(a.model).extension() == ".json" || a.input_format == "json") {
    // A simplex spline volume has no parameter box: its own view (isosurfaces and slices).
    const Model model = read_model_file(a.model, a.input_format);
    for (const ModelObject& object : model.objects)
      if (const auto* volume = std::get_if<DmsSplineVolume>(&object.spline)) return run_simplex_view(a, model, *volume, out);
    if (!a.iso_attribute.empty()) throw InvalidInput(a.model + " has no simplex_spline_volume object", "--iso-attribute");
  }
  if (a.iso_edge != 0 || a.iso_subdivisions != 0)
    throw InvalidInput("--iso-edge and --iso-subdivisions sample the isosurfaces and slices of a simplex_spline_volume",
                       a.iso_edge != 0 ? "--iso-edge" : "--iso-subdivisions");
  const MeshFormat mesh_format = a.mesh.empty() ? MeshFormat::Ply : mesh_format_from_path(a.mesh);
  if (mesh_format == MeshFormat::Stl && !a.color.empty())
    throw InvalidInput("STL cannot carry the colouring; use .ply or .glb", "--mesh");
  const SolidViewPictureRequest request = picture_request_from(a);
  const Model model = [&] {
    const ProgressPhase phase(progress, "reading");
    return read_model_file(a.model, a.input_format);
  }();
  const SolidViewPicture picture = solid_view_picture(model, request, progress);
  if (picture.mesh.triangles.empty()) std::cerr << "volspline: note: nothing to show: the probes miss the solid\n";
  {
    const ProgressPhase phase(progress, "writing");
    write_picture_and_mesh(a, png_bytes(picture.image), picture.mesh, mesh_format, picture.mesh_fields);
    if (!a.html.empty()) {
      InteractivePage page;
      page.title = "view of " + a.model;
      page.mesh = picture.mesh;
      page.vertex_colors = picture.mesh_fields.vertex_colors;
      page.info = model_page_info(model, a.model);
      page.info["view"] = {{"triangles", picture.mesh.num_triangles()}, {"volumes", picture.volumes}, {"planes", picture.planes.size()}};
      if (request.color) {
        page.color_bar = ColorBar{picture.render.colormap, picture.render.scalar_min, picture.render.scalar_max, request.color->name()};
        page.info["view"]["color"] = request.color->name();
        page.info["view"]["range"] = {picture.render.scalar_min, picture.render.scalar_max};
      }
      // The slice probe cuts across the first plane shown, or along z.
      ModelProbeOptions probes;
      if (!picture.planes.empty()) probes.slice_normal = picture.planes.front().normal;
      add_model_probes(page, model, probes, a.model);
      write_html_page(a.html, std::move(page));
    }
  }
  out << "wrote " << a.image << ": " << picture.mesh.num_triangles() << " triangles from " << picture.volumes << " volume(s)";
  if (!picture.planes.empty()) out << ", " << picture.planes.size() << " plane(s)";
  if (request.color)
    out << "; " << request.color->name() << " in [" << color_bar_label(picture.render.scalar_min) << ", "
        << color_bar_label(picture.render.scalar_max) << "]";
  out << "\n";
  if (!a.mesh.empty()) out << "wrote " << a.mesh << "\n";
}

std::string view_command_line(const ViewArguments& a) {
  std::string c = "volspline view " + a.model + " -o " + a.image;
  const auto option = [&c](const std::string& name, const std::string& value) {
    if (!value.empty()) c += " " + name + " " + value;
  };
  for (const auto& s : a.iso) option("--iso", s);
  option("--through", a.through);
  for (const auto& s : a.slices) option("--slices", s);
  for (const auto& s : a.planes) option("--plane", s);
  option("--core", a.core);
  for (const auto& s : a.paddlewheels) option("--paddlewheel", s);
  for (const auto& s : a.iso_attribute) option("--iso-attribute", s);
  if (a.iso_edge != 0) option("--iso-edge", format_double(a.iso_edge));
  if (a.iso_subdivisions != 0) option("--iso-subdivisions", std::to_string(a.iso_subdivisions));
  if (a.cells > 0) option("--cells", std::to_string(a.cells));
  if (a.faces) c += " --faces";
  if (a.cutaway) c += " --cutaway";
  option("--color", a.color);
  option("--range", a.range);
  option("--mesh", a.mesh);
  option("--html", a.html);
  if (a.resolution != ViewArguments{}.resolution) option("--resolution", std::to_string(a.resolution));
  option("--camera", a.camera);
  if (a.size != ViewArguments{}.size) option("--size", a.size);
  if (a.edges) c += " --edges";
  if (a.transparent) c += " --transparent";
  if (a.ascii) c += " --ascii";
  return c;
}

void add_view_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view", "Picture the inside of a solid: isoparametric surfaces, slices, core sections, paddlewheels, coloured by a field");
  auto a = std::make_shared<ViewArguments>();
  cmd->add_option("MODEL", a->model, "model file (.json, .xml, .itd)")->required();
  cmd->add_option("--input-format", a->input_format, "json, gismo, irit or vtu, overriding the extension");
  cmd->add_option("-o,--output", a->image, "picture (.png)")->required();
  cmd->add_option("--iso", a->iso, "a family of N isoparametric surfaces, u:N, v:N or w:N (ends included; repeatable)");
  cmd->add_option("--through", a->through, "the three isoparametric surfaces through V(U,V,W)");
  cmd->add_option("--slices", a->slices, "N parallel slices across the solid, x:N, y:N or z:N (repeatable)");
  cmd->add_option("--plane", a->planes, "a cross section by the plane NX*x + NY*y + NZ*z = D, as NX,NY,NZ,D (repeatable)");
  cmd->add_option("--core", a->core, "three orthogonal slices through the point X,Y,Z (a core section)");
  cmd->add_option("--paddlewheel", a->paddlewheels,
                  "N planes through a common axis along x, y or z: AXIS:N, or AXIS:N@X,Y,Z for an axis through X,Y,Z "
                  "(default: the centre of the solid's box; repeatable)");
  cmd->add_flag("--faces", a->faces, "also draw the boundary faces (drawn alone when nothing else is asked for)");
  cmd->add_flag("--cutaway", a->cutaway,
                "draw the faces with the wedge on the positive side of the --plane and --core planes cut away, "
                "showing those slices in place");
  cmd->add_option("--color", a->color, "colour by a field: jacobian, u, v, w or the name of an attribute");
  cmd->add_option("--range", a->range, "MIN,MAX of the colour map (default: the field's range; a Jacobian of both signs is centred on 0)");
  cmd->add_option("--cells", a->cells, "a simplex_spline_volume's solid as K x K x K shrunken cells per tetrahedron (Hua-He-Qin Fig. 1b)")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--iso-attribute", a->iso_attribute, "a simplex_spline_volume's isosurface NAME:VALUE of an attribute (repeatable)");
  cmd->add_option("--iso-edge", a->iso_edge,
                  "a simplex_spline_volume's isosurfaces and slices sample the domain tetrahedra bisected, longest edge first, until every edge is at most L "
                  "(domain units; default: the domain's bounding-box diagonal / 40); large tetrahedra are refined, small ones not")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--iso-subdivisions", a->iso_subdivisions,
                  "isosurfaces and slices of a simplex_spline_volume instead cut every domain tetrahedron alike into K x K x K sub-tetrahedra (uniform)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--mesh", a->mesh, "also write the shown surfaces: .ply (with the field as a vertex property), .obj, .glb (field colours)");
  cmd->add_option("--html", a->html,
                  "also write an interactive page: what is shown in three.js with parts, probes, clipping, the colour bar and "
                  "the model's description, one self-contained file (docs/web-pages.md)");
  cmd->add_option("--resolution", a->resolution, "segments per parameter direction, plus every knot (default 32)")->check(CLI::Range(1, 512));
  cmd->add_option("--camera", a->camera, "view direction DX,DY,DZ, optionally followed by an up vector UX,UY,UZ");
  cmd->add_option("--size", a->size, "picture size W,H in pixels (default 800,600)");
  cmd->add_flag("--edges", a->edges, "draw the triangle edges");
  cmd->add_flag("--transparent", a->transparent, "transparent picture background");
  cmd->add_flag("--ascii", a->ascii, "write the PLY mesh as text");
  cmd->callback([a] { run_view(*a, std::cout, command_progress()); });
}

}  // namespace volspline::cli
