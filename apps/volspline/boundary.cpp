// volspline boundary MODEL -o OUT.(ply|obj|stl) [--tol T] [--max-cells N] [--bounds bezier|cone]
//   [--method adaptive|uniform] [--resolution N] [--snap] [--stats STATS.json] [--png IMAGE.png]
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/mesh/mesh_writer.h"

namespace volspline::cli {

void add_boundary_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("boundary",
                                 "The boundary of every volume (Joy–Duchaineau Theorem 4.1): the six face patches (parts 0..5) "
                                 "plus the implicit surface where the Jacobian vanishes (part 6)");
  auto out = std::make_shared<std::string>();
  auto tol = std::make_shared<double>(1e-3);
  auto max_cells = std::make_shared<std::int64_t>(200000);
  auto bounds = std::make_shared<std::string>("bezier");
  auto method = std::make_shared<std::string>("adaptive");
  auto stop = std::make_shared<std::string>("flatness");
  auto resolution = std::make_shared<int>(64);
  auto face_resolution = std::make_shared<int>(24);
  auto min_level = std::make_shared<int>(3);
  auto snap = std::make_shared<bool>(false);
  auto stats_path = std::make_shared<std::string>();
  auto png = std::make_shared<std::string>();
  auto size = std::make_shared<std::string>("800,600");
  const auto input = add_model_input(cmd);
  const auto in = std::shared_ptr<std::string>(input, &input->path);
  cmd->add_option("-o,--output", *out, "mesh file: .ply (x y z u v w, face part), .obj or .stl")->required();
  cmd->add_option("--tol", *tol, "relative tolerance of the adaptive subdivision (default 1e-3; see --stop)");
  cmd->add_option("--max-cells", *max_cells, "budget of cells examined per volume (default 200000)")->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--bounds", *bounds, "bezier (certified Bernstein coefficients, default) or cone (Joy–Duchaineau §5)");
  cmd->add_option("--method", *method, "adaptive (default) or uniform (marching tetrahedra on a resolution^3 grid, the baseline)");
  cmd->add_option("--stop", *stop, "flatness (J within TOL of affine on a cell, default) or width (the paper's: bound of J narrower than TOL)");
  cmd->add_option("--resolution", *resolution, "uniform method: grid cells per direction (default 64)")->check(CLI::Range(1, 1024));
  cmd->add_option("--min-level", *min_level, "adaptive: split cells the surface may cross to at least 2^-L of their Bézier piece (default 3)")->check(CLI::Range(0, 20));
  cmd->add_option("--face-resolution", *face_resolution, "segments per direction of the face patches (default 24)")->check(CLI::Range(1, 1024));
  cmd->add_flag("--snap", *snap, "move implicit vertices onto J = 0 by Newton steps in the domain");
  cmd->add_option("--stats", *stats_path, "write statistics as JSON");
  cmd->add_option("--png", *png, "also render a picture (implicit surface in orange)");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  cmd->callback([=] {
    const MeshFormat format = mesh_format_from_path(*out);
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + *size + "'", "--size");
    BoundaryOptions options;
    if (*bounds == "bezier") options.bounds = JacobianBoundMethod::Bezier;
    else if (*bounds == "cone") options.bounds = JacobianBoundMethod::Cone;
    else throw InvalidInput("expected 'bezier' or 'cone', got '" + *bounds + "'", "--bounds");
    if (*method == "adaptive") options.method = ZeroSurfaceMethod::Adaptive;
    else if (*method == "uniform") options.method = ZeroSurfaceMethod::Uniform;
    else throw InvalidInput("expected 'adaptive' or 'uniform', got '" + *method + "'", "--method");
    if (*stop == "flatness") options.stop = StopCriterion::Flatness;
    else if (*stop == "width") options.stop = StopCriterion::Width;
    else throw InvalidInput("expected 'flatness' or 'width', got '" + *stop + "'", "--stop");
    if (!(*tol > 0) || !std::isfinite(*tol)) throw InvalidInput("expected a finite number > 0", "--tol");
    options.tolerance = *tol;
    options.max_cells = *max_cells;
    options.resolution = *resolution;
    options.face_resolution = *face_resolution;
    options.min_level = *min_level;
    options.snap = *snap;
    options.progress = command_progress();
    const Model model = [&] {
      const ProgressPhase phase(options.progress, "reading");
      return input->read();
    }();
    int volume_count = 0;
    for (const auto& object : model.objects) volume_count += std::holds_alternative<BSplineVolume>(object.spline);
    TriangleMesh mesh;
    nlohmann::json stats = {{"objects", nlohmann::json::array()}};
    int volumes = 0;
    std::array<std::int64_t, 7> total{};
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      const auto* v = std::get_if<BSplineVolume>(&model.objects[i].spline);
      if (!v) continue;
      ++volumes;
      if (volume_count > 1) reporter().set_label("object " + std::to_string(i));
      SolidBoundary b;
      try {
        b = solid_boundary(*v, options);
      } catch (const InvalidInput& e) {
        throw e.located(*in + ": objects[" + std::to_string(i) + "]");
      }
      mesh.append(b.mesh);
      const BoundaryStats& s = b.stats;
      nlohmann::json triangles = nlohmann::json::object();
      for (int p = 0; p < 7; ++p) {
        triangles[p < 6 ? "face_" + std::to_string(p) : "implicit"] = s.triangles[static_cast<std::size_t>(p)];
        total[static_cast<std::size_t>(p)] += s.triangles[static_cast<std::size_t>(p)];
      }
      stats["objects"].push_back({{"object", i},
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
                                    {"total", s.seconds_total}}}});
      std::cout << "object " << i << ": " << s.cells_examined << " cells examined, " << s.cells_kept << " kept, "
                << s.triangles[6] << " implicit triangles, max |J| at implicit vertices " << std::setprecision(3)
                << s.max_rel_jacobian_at_vertices << " of max |J|, " << s.seconds_total * 1e3 << " ms\n";
    }
    reporter().set_label("");
    if (volumes == 0) throw InvalidInput("the model has no volume objects (bspline_volume or bezier_volume)", *in);
    // The whole-model figures, with the keys the issue names at the top level.
    const auto& first = stats["objects"][0];
    for (const char* key : {"cells_examined", "cells_kept", "max_rel_jacobian_at_vertices", "max_domain_distance", "seconds"}) {
      stats[key] = first[key];
    }
    nlohmann::json triangles = nlohmann::json::object();
    for (int p = 0; p < 7; ++p) triangles[p < 6 ? "face_" + std::to_string(p) : "implicit"] = total[static_cast<std::size_t>(p)];
    stats["triangles"] = triangles;
    if (volumes > 1) {
      std::int64_t examined = 0, kept = 0;
      double rel = 0, dist = 0;
      for (const auto& o : stats["objects"]) {
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
    RenderOptions render;
    render.width = wh[0];
    render.height = wh[1];
    // Everything is prepared before anything is committed: stats, mesh and picture appear together.
    std::unique_ptr<AtomicFile> stats_file;
    if (!stats_path->empty()) {
      stats_file = std::make_unique<AtomicFile>(*stats_path, false);
      stats_file->stream() << stats.dump(2) << "\n";
    }
    {
      const ProgressPhase phase(options.progress, "writing");
      write_mesh_and_picture(mesh, *out, format, false, *png, render);
      if (stats_file) stats_file->commit();
    }
    std::cout << "wrote " << *out << ": " << mesh.num_vertices() << " vertices, " << mesh.num_triangles() << " triangles\n";
    if (!png->empty()) std::cout << "wrote " << *png << "\n";
    if (stats_file) std::cout << "wrote " << *stats_path << "\n";
  });
}

}  // namespace volspline::cli
