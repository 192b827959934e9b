// volspline blend SCENE.json -o OUT.(ply|obj|stl|glb) [--levels K] [--method control|exact]
//   [--project] [--show blend|spline|union|primitives] [--spacing H] [--stats STATS.json]
//   [--png IMAGE.png] [--view DX,DY,DZ] [--html PAGE.html]
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/boxspline/scene_ingredients.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_writer.h"

namespace volspline::cli {

void add_blend_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "blend", "Blend implicit primitives with the 7-direction box spline (Peters-Wittman 1995) and mesh the zero set");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto png = std::make_shared<std::string>();
  auto stats = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>("control");
  auto levels = std::make_shared<int>(2);
  auto project = std::make_shared<bool>(false);
  auto ascii = std::make_shared<bool>(false);
  auto edges = std::make_shared<bool>(false);
  auto size = std::make_shared<std::string>("800,600");
  auto show = std::make_shared<std::string>("blend");
  auto spacing = std::make_shared<double>(0.0);
  auto view = std::make_shared<std::string>();
  cmd->add_option("SCENE", *in, "scene file (docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", *out, "mesh file: .ply, .obj, .stl or .glb")->required();
  cmd->add_option("--levels", *levels, "refinements of the lattice before marching (default 2)")->check(CLI::Range(0, 8));
  cmd->add_option("--method", *method, "control: the paper's control polyhedron (default); exact: exact spline values")
      ->check(CLI::IsMember({"control", "exact"}));
  cmd->add_flag("--project", *project, "with --method exact: move every vertex onto the zero set (Newton)");
  cmd->add_option("--show", *show,
                  "blend: the blended zero set (default); spline: its box-spline part alone; union: the pointwise minimum of the "
                  "root's children, creased; primitives: each child of the root on its own (Peters-Wittman Figs. 2a, 2b, 4b)")
      ->check(CLI::IsMember({"blend", "spline", "union", "primitives"}));
  cmd->add_option("--spacing", *spacing, "grid spacing of --show union and primitives (default the lattice spacing / 2^levels)");
  cmd->add_option("--stats", *stats, "write statistics as JSON: triangles, largest |f| at vertices, distances, seconds");
  cmd->add_option("--png", *png, "also render a picture (spline surface orange, primitives grey)");
  cmd->add_flag("--ascii", *ascii, "write PLY or STL as text");
  cmd->add_flag("--edges", *edges, "draw the triangle edges in the picture");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  cmd->add_option("--view", *view, "DX,DY,DZ: the direction the camera of --png looks in (default -1,-1.3,-0.8)");
  const auto html = add_html_option(cmd);
  cmd->callback([=] {
    const MeshFormat format = mesh_format_from_path(*out);
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    if (*project && *method != "exact") throw InvalidInput("--project needs --method exact", "--project");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + *size + "'", "--size");
    check_html_option(*html);
    const bool ingredients = *show == "union" || *show == "primitives";
    if (*spacing != 0.0 && !ingredients) throw InvalidInput("--spacing is for --show union or primitives", "--spacing");
    if (*spacing < 0.0 || !std::isfinite(*spacing))
      throw InvalidInput("expected a positive grid spacing, got " + std::to_string(*spacing), "--spacing");
    RenderOptions render;
    if (!view->empty()) render.view_direction = parse_view_direction(*view, "--view");
    const Scene scene = read_scene(*in);
    const ZeroSetOptions options{.levels = *levels,
                                 .method = *method == "exact" ? ZeroSetMethod::Exact : ZeroSetMethod::Control,
                                 .project = *project,
                                 .progress = command_progress()};
    TriangleMesh mesh;
    nlohmann::json stats_json{{"show", *show}};
    if (ingredients) {
      // The ingredients have no spline: the CSG function itself is marched (docs/blend.md).
      const auto start = std::chrono::steady_clock::now();
      const double h = *spacing > 0.0 ? *spacing : default_ingredient_spacing(scene, *levels);
      {
        const ProgressPhase phase(options.progress, "marching");
        mesh = scene_ingredients_mesh(scene, *show == "union" ? SceneIngredients::Union : SceneIngredients::Primitives, h);
      }
      const EdgeStatistics edges = edge_statistics(mesh);
      stats_json.update({{"grid_spacing", h},
                         {"vertices", mesh.num_vertices()},
                         {"triangles", mesh.num_triangles()},
                         {"closed", edges.closed()},
                         {"boundary_edges", edges.boundary_edges},
                         {"nonmanifold_edges", edges.nonmanifold_edges},
                         {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}});
    } else {
      const ZeroSet result = scene_zero_set(scene, options);
      const ZeroSetStats& s = result.stats;
      mesh = *show == "spline" ? triangles_of_part(result.mesh, Part::BlendSpline) : result.mesh;
      stats_json.update({{"method", *method},
                         {"levels", *levels},
                         {"projected", *project},
                         {"grid_spacing", s.grid_spacing},
                         {"vertices", s.vertices},
                         {"triangles", s.triangles},
                         {"max_abs_value", s.max_abs_value},
                         {"max_distance", s.max_distance ? nlohmann::json(*s.max_distance) : nlohmann::json(nullptr)},
                         {"seam_value_difference", s.seam_value_difference},
                         {"closed", s.closed},
                         {"boundary_edges", s.boundary_edges},
                         {"nonmanifold_edges", s.nonmanifold_edges},
                         {"seconds", s.seconds}});
      if (*show == "spline") stats_json["spline_triangles"] = mesh.num_triangles();
    }
    if (mesh.num_triangles() == 0)
      reporter().warn(*show == "blend" ? std::string("the zero set does not cross the meshed region; writing an empty mesh")
                                       : "the --show " + *show + " surface does not cross the meshed region; writing an empty mesh");
    const std::string stats_text = json_text(stats_json) + "\n";
    render.width = wh[0];
    render.height = wh[1];
    render.edges = *edges;
    {
      const ProgressPhase phase(options.progress, "writing");
      write_mesh_and_picture(mesh, *out, format, *ascii, *png, render);
      if (!stats->empty()) write_file_atomically(*stats, stats_text);
      if (!html->empty()) {
        InteractivePage page;
        page.title = (*show == "blend" ? "blend of " : *show + " of ") + *in;
        page.mesh = mesh;
        page.info = {{"scene", *in}, {"blend", stats_json}};
        write_html_page(*html, std::move(page));
      }
    }
    const bool closed = stats_json["closed"].get<bool>();
    std::cout << "wrote " << *out << ": " << mesh.num_vertices() << " vertices, " << mesh.num_triangles() << " triangles";
    if (*show != "spline")
      std::cout << " (" << (closed ? "closed" : "not closed: " + std::to_string(stats_json["boundary_edges"].get<std::size_t>()) + " boundary edges")
                << ")";
    std::cout << ", grid spacing " << stats_json["grid_spacing"].get<double>();
    if (!ingredients) {
      std::cout << ", largest |f| at a vertex " << stats_json["max_abs_value"].get<double>();
      if (!stats_json["max_distance"].is_null()) std::cout << ", largest distance to the surface " << stats_json["max_distance"].get<double>();
    }
    std::cout << ", " << stats_json["seconds"].get<double>() << " s\n";
    if (!png->empty()) std::cout << "wrote " << *png << "\n";
    if (!stats->empty()) std::cout << "wrote " << *stats << "\n";
  });
}

}  // namespace volspline::cli
