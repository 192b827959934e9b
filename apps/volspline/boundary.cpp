// volspline boundary MODEL -o OUT.(ply|obj|stl|glb) [--tol T] [--max-cells N] [--bounds bezier|cone]
//   [--method adaptive|uniform] [--resolution N] [--snap] [--stats STATS.json] [--png IMAGE.png]
//   [--iso-attribute NAME:VALUE]... [--trim [--trim-cell H]]
// Tensor-product volumes: the six faces and the surface J = 0 (Joy–Duchaineau). Simplex spline
// volumes: the image of the domain's boundary s(∂Ω) and, with --iso-attribute, attribute
// isosurfaces (Hua–He–Qin §6.2), as `view` samples them.
#include <algorithm>
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/extract/simplex_boundary.h"
#include "volspline/extract/simplex_isosurface.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/extract/trimmed_solid_boundary.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/io/model_volumes.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"

namespace volspline::cli {

namespace {

struct BoundaryArguments {
  std::shared_ptr<ModelInput> input;
  std::string out, bounds = "bezier", method = "adaptive", stop = "flatness", stats, png, size = "800,600", html;
  double tol = 1e-3;
  std::int64_t max_cells = 200000;
  int resolution = 64, face_resolution = 24, min_level = 3;
  bool snap = false;
  /// --trim: contour the certified membership near the superset; the grid spacing relative to
  /// the superset's diagonal.
  bool trim = false;
  double trim_cell = 4e-3;
  /// Simplex spline volumes: isosurfaces NAME:VALUE of attributes, and the sampling edge.
  std::vector<std::string> iso_attribute;
  double iso_edge = 0;
};

// A simplex spline volume: s(∂Ω) and the asked-for isosurfaces, with the figures for --stats.
TriangleMesh simplex_volume_boundary(const BoundaryArguments& a, std::size_t index, const DmsSplineVolume& volume, nlohmann::json& stats) {
  // The isosurfaces asked for, checked before anything is computed.
  std::vector<SimplexIsosurfaceOptions> isosurfaces;
  for (const std::string& text : a.iso_attribute) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) throw InvalidInput("expected NAME:VALUE, got '" + text + "'", "--iso-attribute");
    SimplexIsosurfaceOptions iso;
    iso.attribute = text.substr(0, colon);
    iso.value = parse_numbers(text.substr(colon + 1), 1, "--iso-attribute")[0];
    iso.target_edge = a.iso_edge;
    try {
      volume.attribute_column(iso.attribute);
    } catch (const InvalidInput& e) {
      throw InvalidInput(e.message(), "--iso-attribute " + text);
    }
    isosurfaces.push_back(iso);
  }
  SimplexBoundaryOptions options;
  options.target_edge = a.iso_edge;
  TriangleMesh mesh = simplex_boundary_mesh(volume, options);
  nlohmann::json triangles = {{"domain_boundary", mesh.num_triangles()}};
  std::cout << "object " << index << ": simplex spline volume, " << mesh.num_triangles() << " domain boundary triangles";
  std::size_t iso_triangles = 0;
  for (std::size_t i = 0; i < isosurfaces.size(); ++i) {
    const std::string& text = a.iso_attribute[i];
    const SimplexIsosurface surface = [&] {
      try {
        return simplex_isosurface(volume, isosurfaces[i]);
      } catch (const InvalidInput& e) {
        throw InvalidInput(e.message(), "--iso-attribute " + text);
      }
    }();
    mesh.append(surface.mesh);
    iso_triangles += surface.mesh.num_triangles();
    std::cout << ", " << text << ": " << surface.mesh.num_triangles() << " isosurface triangles";
  }
  if (!a.iso_attribute.empty()) triangles["attribute_isosurface"] = iso_triangles;
  std::cout << "\n";
  stats["simplex_objects"].push_back({{"object", index}, {"triangles", triangles}});
  return mesh;
}

BoundaryOptions boundary_options(const BoundaryArguments& a) {
  BoundaryOptions options;
  if (a.bounds == "bezier") options.bounds = JacobianBoundMethod::Bezier;
  else if (a.bounds == "cone") options.bounds = JacobianBoundMethod::Cone;
  else throw InvalidInput("expected 'bezier' or 'cone', got '" + a.bounds + "'", "--bounds");
  if (a.method == "adaptive") options.method = ZeroSurfaceMethod::Adaptive;
  else if (a.method == "uniform") options.method = ZeroSurfaceMethod::Uniform;
  else throw InvalidInput("expected 'adaptive' or 'uniform', got '" + a.method + "'", "--method");
  if (a.stop == "flatness") options.stop = StopCriterion::Flatness;
  else if (a.stop == "width") options.stop = StopCriterion::Width;
  else throw InvalidInput("expected 'flatness' or 'width', got '" + a.stop + "'", "--stop");
  if (!(a.tol > 0) || !std::isfinite(a.tol)) throw InvalidInput("expected a finite number > 0", "--tol");
  options.tolerance = a.tol;
  options.max_cells = a.max_cells;
  options.resolution = a.resolution;
  options.face_resolution = a.face_resolution;
  options.min_level = a.min_level;
  options.snap = a.snap;
  return options;
}

// The statistics of object `index`, as --stats writes them.
nlohmann::json object_stats(std::size_t index, const BoundaryStats& s) {
  nlohmann::json triangles = nlohmann::json::object();
  for (int p = 0; p < 7; ++p) triangles[p < 6 ? "face_" + std::to_string(p) : "implicit"] = s.triangles[static_cast<std::size_t>(p)];
  return {{"object", index},
          {"cells_examined", s.cells_examined},
          {"cells_kept", s.cells_kept},
          {"triangles", triangles},
          {"max_rel_jacobian_at_vertices", s.max_rel_jacobian_at_vertices},
          {"max_domain_distance", s.max_domain_distance},
          {"seconds",
           {{"subdivision", s.seconds_subdivision},
            {"tetrahedra", s.seconds_tetrahedra},
            {"isosurface", s.seconds_isosurface},
            {"snap", s.seconds_snap},
            {"faces", s.seconds_faces},
            {"total", s.seconds_total}}}};
}

// The whole-model figures of the per-object `stats["objects"]`, with the keys of one object at
// the top level: sums of cells and triangles, the largest errors, the first object's seconds.
void add_model_stats(nlohmann::json& stats) {
  const auto& objects = stats["objects"];
  for (const char* key : {"cells_examined", "cells_kept", "max_rel_jacobian_at_vertices", "max_domain_distance", "seconds"}) {
    stats[key] = objects[0][key];
  }
  nlohmann::json triangles = nlohmann::json::object();
  for (const auto& o : objects)
    for (const auto& [part, count] : o["triangles"].items())
      triangles[part] = triangles.value(part, std::int64_t{0}) + count.get<std::int64_t>();
  stats["triangles"] = triangles;
  if (objects.size() > 1) {
    std::int64_t examined = 0, kept = 0;
    double rel = 0, dist = 0;
    for (const auto& o : objects) {
      examined += o["cells_examined"].get<std::int64_t>();
      kept += o["cells_kept"].get<std::int64_t>();
      rel = std::max(rel, o["max_rel_jacobian_at_vertices"].get<double>());
      dist = std::max(dist, o["max_domain_distance"].get<double>());
    }
    stats["cells_examined"] = examined;
    stats["cells_kept"] = kept;
    stats["max_rel_jacobian_at_vertices"] = rel;
    stats["max_domain_distance"] = dist;
  }
}

void run_boundary(const BoundaryArguments& a) {
  const MeshFormat format = mesh_format_from_path(a.out);
  if (!a.png.empty() && std::filesystem::path(a.png).extension() != ".png")
    throw InvalidInput("expected a file name ending in .png, got '" + a.png + "'", "--png");
  const auto wh = parse_integers(a.size, 2, 16, "--size");
  if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + a.size + "'", "--size");
  check_html_option(a.html);
  BoundaryOptions options = boundary_options(a);
  options.progress = command_progress();
  const Model model = [&] {
    const ProgressPhase phase(options.progress, "reading");
    return a.input->read();
  }();
  const std::size_t simplex_volumes = static_cast<std::size_t>(std::count_if(
      model.objects.begin(), model.objects.end(), [](const ModelObject& o) { return std::holds_alternative<DmsSplineVolume>(o.spline); }));
  if (simplex_volumes == 0 && !a.iso_attribute.empty())
    throw InvalidInput(a.input->path + " has no simplex_spline_volume object to take isosurfaces of", "--iso-attribute");
  if (a.trim && simplex_volumes > 0)
    throw InvalidInput(a.input->path + " has simplex spline volumes: --trim applies to tensor-product volumes only", "--trim");
  if (simplex_volumes == 0 && a.iso_edge != 0)
    throw InvalidInput(a.input->path + " has no simplex_spline_volume object to sample", "--iso-edge");
  const bool several = count_volumes(model) + simplex_volumes > 1;
  TriangleMesh mesh;
  PlyVertexProperty trimmed_vertex_objects;
  nlohmann::json stats = {{"objects", nlohmann::json::array()}};
  if (simplex_volumes > 0) stats["simplex_objects"] = nlohmann::json::array();
  for (std::size_t i = 0; i < model.objects.size(); ++i)
    if (const auto* volume = std::get_if<DmsSplineVolume>(&model.objects[i].spline)) {
      try {
        mesh.append(simplex_volume_boundary(a, i, *volume, stats));
      } catch (const InvalidInput& e) {
        if (e.where().rfind("--", 0) == 0) throw;
        throw e.located(object_location(a.input->path, i));
      }
    }
  if (simplex_volumes == 0 || count_volumes(model) > 0) {
    std::vector<BSplineVolume> trimmed_volumes;
    std::vector<std::size_t> trimmed_objects;
    for_each_volume(model, a.input->path, [&](std::size_t i, const ModelObject&, const BSplineVolume& volume) {
      if (several) reporter().set_label("object " + std::to_string(i));
      if (a.trim) {
        // Trimmed together below: the boundary of the union of the volumes' images (a
        // multi-patch solid's patches meet inside it).
        trimmed_volumes.push_back(volume);
        trimmed_objects.push_back(i);
        return;
      }
      const SolidBoundary b = solid_boundary(volume, options);
      mesh.append(b.mesh);
      const BoundaryStats& s = b.stats;
      stats["objects"].push_back(object_stats(i, s));
      std::cout << "object " << i << ": " << s.cells_examined << " cells examined, " << s.cells_kept << " kept, " << s.triangles_of(Part::JacobianZero)
                << " implicit triangles, max |J| at implicit vertices " << std::setprecision(3) << s.max_rel_jacobian_at_vertices
                << " of max |J|, " << s.seconds_total * 1e3 << " ms\n";
    });
    reporter().set_label("");
    if (a.trim) {
      ImageContouringOptions contouring;
      contouring.cell_size = a.trim_cell;
      contouring.superset_error = std::min(0.25, 0.5 * a.trim_cell);
      contouring.progress = options.progress;
      const TrimmedSolidBoundary t = trimmed_solid_boundary(trimmed_volumes, options, contouring);
      mesh.append(t.mesh);
      // Per vertex, the model object whose (u, v, w) it carries (a PLY property after w).
      trimmed_vertex_objects.name = "object";
      trimmed_vertex_objects.integer = true;
      for (const int v : t.volumes) trimmed_vertex_objects.values.push_back(static_cast<double>(trimmed_objects[static_cast<std::size_t>(v)]));
      const SupersetTrimmingStats& ts = t.stats;
      stats["objects"].push_back({{"objects", trimmed_objects},
                                  {"superset_triangles", t.superset_triangles},
                                  {"triangles", ts.result_triangles},
                                  {"grid_cell_size", ts.cell_size},
                                  {"grid_cells", ts.grid_cells},
                                  {"grid_corners", ts.grid_corners},
                                  {"grid_corners_inferred", ts.grid_corners_inferred},
                                  {"membership_queries", ts.membership_queries},
                                  {"membership_queries_remembered", ts.membership_queries_remembered},
                                  {"crossings_on_sheets", ts.crossings_on_sheets},
                                  {"crossings_off_superset", ts.crossings_off_superset},
                                  {"crease_vertices", ts.crease_vertices},
                                  {"crease_repairs", ts.crease_repairs},
                                  {"tags_corrected", ts.tags_corrected},
                                  {"tags_beyond_tolerance", ts.tags_beyond_tolerance},
                                  {"largest_tag_distance", ts.largest_tag_distance},
                                  {"closed", ts.closed},
                                  {"oriented", ts.oriented},
                                  {"self_intersection_free", ts.self_intersection_free},
                                  {"components", ts.components},
                                  {"volume", ts.volume},
                                  {"seconds", {{"grid", ts.seconds_refine}, {"classify", ts.seconds_classify}, {"checks", ts.seconds_checks}}}});
      // One volume: also "object", the key of the statistics before volumes were trimmed together.
      if (trimmed_objects.size() == 1) stats["objects"].back()["object"] = trimmed_objects[0];
      std::cout << (trimmed_objects.size() == 1 ? "object " + std::to_string(trimmed_objects[0])
                                                : std::to_string(trimmed_objects.size()) + " volumes")
                << ": trimmed boundary" << (trimmed_objects.size() == 1 ? "" : " of their union") << ", " << ts.result_triangles
                << " triangles of " << t.superset_triangles << " in the superset, volume " << std::setprecision(6) << ts.volume << ", "
                << ts.components << " component" << (ts.components == 1 ? "" : "s") << (ts.closed ? ", closed" : ", open")
                << (ts.oriented ? ", oriented" : "") << (ts.self_intersection_free ? ", no self-intersections" : ", self-intersecting") << "\n";
      if (!ts.closed || !ts.self_intersection_free)
        std::cerr << "volspline: warning: the trimmed boundary is not a closed, self-intersection-free surface"
                  << (ts.open_at.empty() ? "" : " (open at " + ts.open_at + ")") << "\n";
      if (ts.tags_beyond_tolerance > 0)
        std::cerr << "volspline: warning: " << ts.tags_beyond_tolerance << " vertices' (u, v, w) could not be made to map within the "
                  << "superset's error of them (statistics: tags_beyond_tolerance)\n";
    } else {
      add_model_stats(stats);
    }
  }
  RenderOptions render;
  render.width = wh[0];
  render.height = wh[1];
  // Everything is prepared before anything is committed: stats, mesh and picture appear together.
  write_mesh_picture_and_stats(mesh, a.out, format, a.png, render, json_text(stats), a.stats, options.progress, nullptr,
                               trimmed_vertex_objects.values.empty() ? std::vector<PlyVertexProperty>{}
                                                                     : std::vector<PlyVertexProperty>{trimmed_vertex_objects});
  if (!a.html.empty()) {
    InteractivePage page;
    page.title = "boundary of " + a.input->path;
    page.mesh = mesh;
    page.info = model_page_info(model, a.input->path);
    page.info["boundary"] = stats;
    add_model_probes(page, model, {}, a.input->path);
    write_html_page(a.html, std::move(page));
  }
}

}  // namespace

void add_boundary_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("boundary",
                                 "The boundary of every volume (Joy–Duchaineau Theorem 4.1): the six face patches (parts 0..5) "
                                 "plus the implicit surface where the Jacobian vanishes (part 6); of a simplex spline volume, the image "
                                 "of its domain's boundary (part 17) and, with --iso-attribute, attribute isosurfaces (part 16)");
  auto a = std::make_shared<BoundaryArguments>();
  a->input = add_model_input(cmd);
  cmd->add_option("-o,--output", a->out, "mesh file: .ply (x y z u v w, face part), .obj or .stl")->required();
  cmd->add_option("--tol", a->tol, "relative tolerance of the adaptive subdivision (default 1e-3; see --stop)");
  cmd->add_option("--max-cells", a->max_cells, "budget of cells examined per volume (default 200000)")->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--bounds", a->bounds, "bezier (certified Bernstein coefficients, default) or cone (Joy–Duchaineau §5)");
  cmd->add_option("--method", a->method, "adaptive (default) or uniform (marching tetrahedra on a resolution^3 grid, the baseline)");
  cmd->add_option("--stop", a->stop, "flatness (J within TOL of affine on a cell, default) or width (the paper's: bound of J narrower than TOL)");
  cmd->add_option("--resolution", a->resolution, "uniform method: grid cells per direction (default 64)")->check(CLI::Range(1, 1024));
  cmd->add_option("--min-level", a->min_level, "adaptive: split cells the surface may cross to at least 2^-L of their Bézier piece (default 3)")->check(CLI::Range(0, 20));
  cmd->add_option("--face-resolution", a->face_resolution, "segments per direction of the face patches (default 24)")->check(CLI::Range(1, 1024));
  cmd->add_flag("--snap", a->snap, "move implicit vertices onto J = 0 by Newton steps in the domain");
  cmd->add_flag("--trim", a->trim,
                "tensor-product volumes: the true boundary of V([0,1]^3), the superset's parts inside a folded solid removed "
                "(certified membership contoured on a grid; closed and oriented)");
  cmd->add_option("--trim-cell", a->trim_cell, "with --trim: grid spacing relative to the bounding-box diagonal (default 4e-3)")
      ->check(CLI::Range(1e-5, 0.25));
  cmd->add_option("--stats", a->stats, "write statistics as JSON");
  cmd->add_option("--png", a->png, "also render a picture (implicit surface in orange)");
  cmd->add_option("--size", a->size, "picture size W,H in pixels (default 800,600)");
  a->html = "";
  cmd->add_option("--html", a->html,
                  "also write an interactive page: the boundary in three.js with parts, probes, clipping and the model's "
                  "description, one self-contained file (docs/web-pages.md)");
  cmd->add_option("--iso-attribute", a->iso_attribute,
                  "a simplex_spline_volume: also its isosurface NAME:VALUE of an attribute (repeatable; the domain boundary s(dOmega) "
                  "is always written, part 17)");
  cmd->add_option("--iso-edge", a->iso_edge,
                  "a simplex_spline_volume: the longest sampling edge in the domain (default: its bounding-box diagonal / 40)")
      ->check(CLI::PositiveNumber);
  cmd->callback([a] { run_boundary(*a); });
}

}  // namespace volspline::cli
