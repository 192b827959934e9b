// volspline blend SCENE.json -o OUT.(ply|obj|stl|glb) [--levels K] [--method control|exact]
//   [--project] [--stats STATS.json] [--png IMAGE.png]
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
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
  cmd->add_option("SCENE", *in, "scene file (docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", *out, "mesh file: .ply, .obj, .stl or .glb")->required();
  cmd->add_option("--levels", *levels, "refinements of the lattice before marching (default 2)")->check(CLI::Range(0, 8));
  cmd->add_option("--method", *method, "control: the paper's control polyhedron (default); exact: exact spline values")
      ->check(CLI::IsMember({"control", "exact"}));
  cmd->add_flag("--project", *project, "with --method exact: move every vertex onto the zero set (Newton)");
  cmd->add_option("--stats", *stats, "write statistics as JSON: triangles, largest |f| at vertices, distances, seconds");
  cmd->add_option("--png", *png, "also render a picture (spline surface orange, primitives grey)");
  cmd->add_flag("--ascii", *ascii, "write PLY or STL as text");
  cmd->add_flag("--edges", *edges, "draw the triangle edges in the picture");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  const auto html = add_html_option(cmd);
  cmd->callback([=] {
    const MeshFormat format = mesh_format_from_path(*out);
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    if (*project && *method != "exact") throw InvalidInput("--project needs --method exact", "--project");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + *size + "'", "--size");
    check_html_option(*html);
    const Scene scene = read_scene(*in);
    const ZeroSetOptions options{.levels = *levels,
                                 .method = *method == "exact" ? ZeroSetMethod::Exact : ZeroSetMethod::Control,
                                 .project = *project,
                                 .progress = command_progress()};
    const ZeroSet result = scene_zero_set(scene, options);
    if (result.mesh.num_triangles() == 0)
      reporter().warn("the zero set does not cross the meshed region; writing an empty mesh");
    const ZeroSetStats& s = result.stats;
    const nlohmann::json stats_json{{"method", *method},
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
                       {"seconds", s.seconds}};
    const std::string stats_text = json_text(stats_json) + "\n";
    RenderOptions render;
    render.width = wh[0];
    render.height = wh[1];
    render.edges = *edges;
    {
      const ProgressPhase phase(options.progress, "writing");
      write_mesh_and_picture(result.mesh, *out, format, *ascii, *png, render);
      if (!stats->empty()) write_file_atomically(*stats, stats_text);
      if (!html->empty()) {
        InteractivePage page;
        page.title = "blend of " + *in;
        page.mesh = result.mesh;
        page.info = {{"scene", *in}, {"blend", stats_json}};
        write_html_page(*html, std::move(page));
      }
    }
    std::cout << "wrote " << *out << ": " << s.vertices << " vertices, " << s.triangles << " triangles ("
              << (s.closed ? "closed" : "not closed: " + std::to_string(s.boundary_edges) + " boundary edges") << "), grid spacing "
              << s.grid_spacing << ", largest |f| at a vertex " << s.max_abs_value;
    if (s.max_distance) std::cout << ", largest distance to the surface " << *s.max_distance;
    std::cout << ", " << s.seconds << " s\n";
    if (!png->empty()) std::cout << "wrote " << *png << "\n";
    if (!stats->empty()) std::cout << "wrote " << *stats << "\n";
  });
}

}  // namespace volspline::cli
