// volspline sweep-envelope S.json -o OUT.(ply|obj|stl|glb) [--tol T] [--bounds bezier|cone]
//   [--superset] [--stats S.json] [--png P.png] [--view DX,DY,DZ] [--cut-open NX,NY,NZ,D] [--html PAGE.html]: the boundary of the volume a swept solid sweeps
//   (extract/swept_envelope.h, docs/envelopes.md).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/core/error.h"
#include "volspline/extract/swept_envelope.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_volumes.h"
#include "volspline/mesh/mesh_clipping.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/parts.h"
#include "volspline/pipeline/interactive_model_page.h"

namespace volspline::cli {

namespace {

struct SweepEnvelopeArguments {
  std::shared_ptr<ModelInput> input;
  std::string out, bounds = "bezier", trimming = "auto", stats, png, size = "800,600", view, cut_open, html;
  double tol = 1e-3, coarse_cells = 0, refine = 0.25;
  std::int64_t max_cells = 2000000;
  int adaptive_cells = 4;
  CLI::Option* adaptive_cells_option = nullptr;
  bool superset = false;
};

nlohmann::json envelope_stats(const SweptEnvelopeStats& s, bool trimmed) {
  nlohmann::json j = {
      {"superset_triangles",
       {{"cap_faces", s.cap_face_triangles},
        {"edge_sweeps", s.edge_sweep_triangles},
        {"cap_folds", s.cap_fold_triangles},
        {"face_sweep_folds", s.face_sweep_fold_triangles},
        {"rank_deficient", s.rank_deficient_triangles}}},
      {"three_faces_degenerate", s.degenerate_three_faces},
      {"three_faces_without_fold", s.fold_free_three_faces},
      {"three_faces_interior", s.interior_face_sweeps},
      {"fold_cells_examined", s.cells_examined},
      {"fold_cells_kept", s.cells_kept},
      {"rank_cells_examined", s.rank_cells_examined},
      {"rank_cells_kept", s.rank_cells_kept},
      {"rank_part_cells_examined", s.rank_part_cells_examined},
      {"rank_minors_divided_by_faces", s.rank_minors_divided_by_faces},
      {"rank_lattice_face_triangles", s.rank_lattice_face_triangles},
      {"budget_reached", s.budget_reached},
      {"samples", s.samples},
      {"seconds", {{"faces", s.seconds_faces}, {"folds", s.seconds_folds}, {"rank_deficient", s.seconds_rank_deficient}, {"total", s.seconds_total}}}};
  if (trimmed) {
    const SupersetTrimmingStats& t = s.trimming;
    j["trimming"] = {{"refined_triangles", t.refined_triangles},
                     {"pieces", t.pieces},
                     {"pieces_boundary", t.pieces_boundary},
                     {"pieces_inside", t.pieces_inside},
                     {"pieces_outside", t.pieces_outside},
                     {"pieces_duplicate", t.pieces_duplicate},
                     {"pieces_undecided", t.pieces_undecided},
                     {"membership_queries", t.membership_queries},
                     {"membership_queries_remembered", t.membership_queries_remembered},
                     {"tags_corrected", t.tags_corrected},
                     {"tags_beyond_tolerance", t.tags_beyond_tolerance},
                     {"largest_tag_distance", t.largest_tag_distance},
                     {"method", s.trimmed_by == EnvelopeTrimming::Arrangement ? "arrangement" : "contouring"},
                     {"grid_cell_size", t.cell_size},
                     {"grid_cells", t.grid_cells},
                     {"grid_cells_refined", t.grid_cells_refined},
                     {"grid_coarse_ratio", t.coarse_ratio},
                     {"grid_crease_width", t.crease_width},
                     {"grid_adaptations", t.grid_adaptations},
                     {"grid_adaptation_refused", t.grid_adaptation_refused},
                     {"grid_corners", t.grid_corners},
                     {"grid_corners_inferred", t.grid_corners_inferred},
                     {"crossings_off_superset", t.crossings_off_superset},
                     {"crossings_on_sheets", t.crossings_on_sheets},
                     {"crossings_after_bisection", t.crossings_after_bisection},
                     {"crease_vertices", t.crease_vertices},
                     {"crease_flips", t.crease_flips},
                     {"crease_repairs", t.crease_repairs},
                     {"crease_cells_unsnapped", t.crease_cells_unsnapped},
                     {"grid_passes", t.grid_passes},
                     {"coarse_grid_rejected", t.coarse_grid_rejected},
                     {"refinement",
                      {{"tolerance", t.refinement_tolerance},
                       {"rounds", t.refinement_rounds},
                       {"split_edges", t.refinement_splits},
                       {"failed_edges", t.refinement_failed_edges},
                       {"unresolved_edges", t.refinement_unresolved_edges},
                       {"edges_verified", t.refinement_edges_verified},
                       {"edges_beyond_tolerance", t.refinement_edges_beyond_tolerance},
                       {"edges_above_tolerance", t.refinement_edges_above_tolerance},
                       {"largest_remaining_distance", t.refinement_largest_remaining}}},
                     {"seconds",
                      {{"grid", t.seconds_refine},
                       {"classify", t.seconds_classify},
                       {"refinement", t.seconds_sheet_refinement},
                       {"checks", t.seconds_checks}}}};
    j["closed"] = t.closed;
    j["oriented"] = t.oriented;
    j["self_intersection_free"] = t.self_intersection_free;
    j["self_intersecting_pairs"] = t.self_intersecting_pairs;
    j["boundary_edges"] = t.boundary_edges;
    j["nonmanifold_edges"] = t.nonmanifold_edges;
    j["components"] = t.components;
    j["volume"] = t.volume;
    if (!t.open_at.empty()) j["open_at"] = t.open_at;
  }
  return j;
}

void run_sweep_envelope(const SweepEnvelopeArguments& a) {
  const MeshFormat format = mesh_format_from_path(a.out);
  if (!a.png.empty() && std::filesystem::path(a.png).extension() != ".png")
    throw InvalidInput("expected a file name ending in .png, got '" + a.png + "'", "--png");
  const auto wh = parse_integers(a.size, 2, 16, "--size");
  if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + a.size + "'", "--size");
  if (!(a.tol > 0 && a.tol < 0.5)) throw InvalidInput("expected a number in (0, 0.5)", "--tol");
  RenderOptions render;
  render.width = wh[0];
  render.height = wh[1];
  if (!a.view.empty()) render.view_direction = parse_view_direction(a.view, "--view");
  std::optional<Plane> cut;
  if (!a.cut_open.empty()) {
    if (a.png.empty()) throw InvalidInput("--cut-open shapes the picture; give --png too", "--cut-open");
    cut = parse_plane(a.cut_open, "--cut-open");
  }
  SweptEnvelopeOptions options;
  options.tolerance = a.tol;
  options.max_cells = a.max_cells;
  if (!(a.coarse_cells >= 0 && a.coarse_cells * a.tol < 0.5))
    throw InvalidInput("expected 0 (off) or a positive multiple of --tol below 0.5 / tol", "--coarse-cells");
  if (!(a.refine > 0 && a.refine <= 1)) throw InvalidInput("expected a multiple of --tol in (0, 1]", "--refine");
  if (a.adaptive_cells != 0 && (a.adaptive_cells < 2 || a.adaptive_cells > 64 || a.adaptive_cells % 2 != 0))
    throw InvalidInput("expected 0 (off) or an even number from 2 to 64", "--adaptive-cells");
  const bool adaptive_cells_given = a.adaptive_cells_option != nullptr && a.adaptive_cells_option->count() > 0;
  if (adaptive_cells_given && a.coarse_cells > 0) throw InvalidInput("give --coarse-cells or --adaptive-cells, not both", "--adaptive-cells");
  if (adaptive_cells_given && a.adaptive_cells * 3 * a.tol >= 0.25)
    throw InvalidInput("expected --adaptive-cells x 3 x --tol below 0.25", "--adaptive-cells");
  options.coarse_cell_factor = a.coarse_cells;
  options.adaptive_ratio = a.coarse_cells > 0 ? 0 : adaptive_cells_given ? a.adaptive_cells : SweptEnvelopeOptions::kAutomaticRatio;
  options.refinement_factor = a.refine;
  options.trim = !a.superset;
  if (a.bounds == "bezier") options.bounds = JacobianBoundMethod::Bezier;
  else if (a.bounds == "cone") options.bounds = JacobianBoundMethod::Cone;
  else throw InvalidInput("expected 'bezier' or 'cone', got '" + a.bounds + "'", "--bounds");
  if (a.trimming == "auto") options.trimming_method = EnvelopeTrimming::Automatic;
  else if (a.trimming == "arrangement") options.trimming_method = EnvelopeTrimming::Arrangement;
  else if (a.trimming == "contouring") options.trimming_method = EnvelopeTrimming::Contouring;
  else throw InvalidInput("expected 'auto', 'arrangement' or 'contouring', got '" + a.trimming + "'", "--trimming");
  check_html_option(a.html);
  options.progress = command_progress();
  const Model model = [&] {
    const ProgressPhase phase(options.progress, "reading");
    return a.input->read();
  }();
  TriangleMesh mesh;
  // Per vertex: t and the generator patch (SweptEnvelope::times, patches), after u, v, w in PLY.
  // Patch numbers count within each object: the object says which.
  PlyVertexProperty times{"t", {}, false}, patches{"patch", {}, true}, objects{"object", {}, true};
  nlohmann::json stats = {{"objects", nlohmann::json::array()}};
  bool open = false, beyond_tolerance = false, adaptation_refused = false, tags_off = false;
  std::size_t solids = 0;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    // A swept solid, or a 4-variate spline given as it is (its image is the swept volume).
    std::vector<BSplineHypervolume> maps;
    if (is_swept_solid(model.objects[i])) maps = swept_patches(std::get<SweptSolid>(model.objects[i].spline));
    else if (const auto* h = std::get_if<BSplineHypervolume>(&model.objects[i].spline)) maps.push_back(*h);
    else continue;
    ++solids;
    const SweptEnvelope e = [&] {
      try {
        return swept_envelope(maps, options);
      } catch (const InvalidInput& error) {
        throw InvalidInput(std::string(error.what()), object_location(a.input->path, i));
      }
    }();
    mesh.append(e.mesh);
    times.values.insert(times.values.end(), e.times.begin(), e.times.end());
    patches.values.insert(patches.values.end(), e.patches.begin(), e.patches.end());
    objects.values.insert(objects.values.end(), e.mesh.num_vertices(), static_cast<double>(i));
    nlohmann::json s = envelope_stats(e.stats, options.trim);
    s["object"] = i;
    if (options.trim) {
      std::int64_t caps = 0, faces = 0, rank = 0;
      for (const int part : e.mesh.parts) {
        caps += part == static_cast<int>(Part::SweepCap);
        faces += part == static_cast<int>(Part::SweepFace);
        rank += part == static_cast<int>(Part::SweepRankDeficient);
      }
      s["result_triangles"] = {{"caps", caps}, {"face_sweeps", faces}, {"rank_deficient", rank}, {"total", e.mesh.num_triangles()}};
      if (e.stats.trimming.tags_beyond_tolerance > 0) tags_off = true;
    }
    stats["objects"].push_back(s);
    const auto& t = e.stats.trimming;
    std::cout << "object " << i << ": " << e.mesh.num_triangles() << " triangles";
    if (options.trim) {
      if (e.stats.trimmed_by == EnvelopeTrimming::Arrangement)
        std::cout << ", " << t.pieces << " pieces (" << t.pieces_boundary << " on the boundary, " << t.pieces_inside << " inside, "
                  << t.pieces_duplicate << " duplicate)";
      else
        std::cout << ", contoured on " << t.grid_cells << " grid cells of " << std::setprecision(3) << t.cell_size;
      std::cout << ", volume " << std::setprecision(6) << t.volume << ", " << t.components << " component" << (t.components == 1 ? "" : "s") << ", "
                << (t.closed ? "closed" : "open") << (t.oriented ? ", oriented" : "")
                << (t.self_intersection_free ? ", no self-intersections" : ", self-intersecting");
      if (!t.closed || !t.self_intersection_free) open = true;
      if (t.refinement_edges_beyond_tolerance > 0) beyond_tolerance = true;
      if (t.grid_adaptation_refused) adaptation_refused = true;
      // Adaptive cells by default (kAutomaticRatio) or as asked; the coarse grid of --coarse-cells.
      const bool adaptive = options.coarse_cell_factor == 0 && options.adaptive_ratio != 0;
      if (e.stats.trimmed_by == EnvelopeTrimming::Contouring && (options.coarse_cell_factor > 0 || adaptive)) {
        if (t.grid_passes == 2)
          std::cout << "; the " << (adaptive ? "adaptive cells were" : "coarse grid was") << " not kept ("
                    << t.coarse_grid_rejected << ")";
        else
          std::cout << "; " << (adaptive ? std::to_string(t.grid_cells_refined) + " coarse cells refined (" + std::to_string(t.coarse_ratio) +
                                               " fine cells wide), "
                                         : std::string("coarse grid "))
                    << "refined toward the sheets: " << t.refinement_splits << " edges split, "
                    << t.refinement_edges_beyond_tolerance << " of " << t.refinement_edges_verified
                    << " edges it could not refine farther than the tolerance from the boundary";
      }
    }
    std::cout << ", " << std::setprecision(3) << e.stats.seconds_total << " s\n";
    if (!t.open_at.empty()) std::cout << "  open at " << t.open_at << "\n";
  }
  if (solids == 0)
    throw InvalidInput(a.input->path + " has no swept_solid or bspline_hypervolume object (make one with `volspline make swept-solid`)",
                       "objects");
  // A cut-open picture: the part where normal·x > offset is left out of the picture only
  // (Conkey–Joy's superset shows its sheets inside the swept volume, the trimmed result is a shell).
  const std::optional<TriangleMesh> shown = cut ? std::optional(remove_convex_region(mesh, {*cut})) : std::nullopt;
  write_mesh_picture_and_stats(mesh, a.out, format, a.png, render, stats.dump(2), a.stats, options.progress, shown ? &*shown : nullptr,
                               {times, patches, objects});
  InteractivePage page;
  page.title = "envelope of " + a.input->path;
  page.mesh = mesh;
  page.info = model_page_info(model, a.input->path);
  page.info["envelope"] = stats;
  write_html_page(a.html, std::move(page));
  if (open)
    std::cerr << "volspline: warning: the trimmed envelope is not a closed, self-intersection-free surface (see above and "
                 "docs/envelopes.md, \"Limits\")\n";
  if (beyond_tolerance)
    std::cerr << "volspline: warning: the membership tests find some edges that refinement could not check farther than the "
                 "tolerance from the boundary (creases or thin features the coarse cells missed; see above); --adaptive-cells 0 "
                 "contours on the uniform fine grid instead, slower (docs/envelopes.md, \"Adaptive cells\")\n";
  if (tags_off)
    std::cerr << "volspline: warning: some vertices' (u, v, w, t) could not be made to map within the tolerance of them "
                 "(statistics: tags_beyond_tolerance, largest_tag_distance)\n";
  if (adaptation_refused)
    std::cerr << "volspline: warning: so many edges lie beyond the tolerance that splitting the cells around them would more than "
                 "quadruple the grid; they were left as they are (statistics: grid_adaptation_refused; the superset likely misses "
                 "the boundary there: docs/envelopes.md, \"Adaptive cells\")\n";
}

}  // namespace

void add_sweep_envelope_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep-envelope",
                                 "The boundary of the volume a swept solid sweeps (Conkey–Joy 2000), trimmed to the true boundary: "
                                 "caps (part 13), face and edge sweeps (part 14), the rank-deficient set (part 15)");
  auto a = std::make_shared<SweepEnvelopeArguments>();
  a->input = add_model_input(cmd);
  cmd->add_option("-o,--output", a->out, "mesh file: .ply (x y z u v w t patch object per vertex, part per face), .obj, .stl or .glb")->required();
  cmd->add_option("--tol", a->tol, "tolerance relative to the bounding-box diagonal (default 1e-3)");
  cmd->add_option("--max-cells", a->max_cells, "budget of cells per subdivision (default 2000000)")->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--bounds", a->bounds, "bezier (certified Bernstein coefficients, default) or cone (the paper's cone bounds)");
  cmd->add_option("--trimming", a->trimming,
                  "auto (default: the arrangement for polyhedral sweeps when it closes, else contouring), arrangement or contouring");
  cmd->add_flag("--superset", a->superset, "write the paper's untrimmed superset instead of the true boundary");
  cmd->add_option("--coarse-cells", a->coarse_cells,
                  "contour on a grid of this many multiples of --tol (e.g. 16) and refine its edges toward the sheets' equations "
                  "instead of the default fine grid (3 x tol): much faster on smooth sweeps, creases it cannot resolve are "
                  "chamfered and counted (docs/envelopes.md, \"Refinement toward the sheets\"; default 0: off)");
  a->adaptive_cells_option = cmd->add_option("--adaptive-cells", a->adaptive_cells,
                  "contour on cells this many times the fine grid (3 x tol; an even number up to 64), split into fine "
                  "cells only where the boundary bends sharply (creases) or the check of the result asks for it, edges refined "
                  "toward the sheets' equations (docs/envelopes.md, \"Adaptive cells\"; default: 4 at --tol 1e-3 and above, "
                  "4 x the power of two nearest 1e-3 / tol below, at most 64: 32 at 1e-4; 0: the uniform fine grid)");
  cmd->add_option("--refine", a->refine, "with --coarse-cells or --adaptive-cells: split edges until their midpoints are within this multiple of --tol of the sheet (default 0.25)");
  cmd->add_option("--stats", a->stats, "write statistics as JSON");
  cmd->add_option("--png", a->png, "also render a picture (parts coloured by source)");
  cmd->add_option("--size", a->size, "picture size W,H in pixels (default 800,600)");
  cmd->add_option("--view", a->view, "DX,DY,DZ: the direction the camera of --png looks in (default -1,-1.3,-0.8)");
  cmd->add_option("--cut-open", a->cut_open,
                  "NX,NY,NZ,D: leave the part where NX x + NY y + NZ z > D out of the picture (the mesh file and page stay whole)");
  cmd->add_option("--html", a->html,
                  "also write an interactive page: the envelope in three.js with its parts, clipping and the model's "
                  "description, one self-contained file (docs/web-pages.md)");
  cmd->callback([a] { run_sweep_envelope(*a); });
}

}  // namespace volspline::cli
