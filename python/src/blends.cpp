// Implicit primitives blended by the 7-direction box spline (Peters–Wittman 1995) from Python:
// volspline.blend, as `volspline blend` (boxspline/zero_set.h, docs/blend.md,
// docs/scene-format.md).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>

#include "bindings.h"
#include "volspline/boxspline/scene_file.h"
#include "volspline/boxspline/scene_ingredients.h"
#include "volspline/boxspline/zero_set.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline::python {
namespace {

// A scene from a path, JSON text, or a dict in the scene format (serialised and parsed by the one
// strict parser, so every scene is checked the same way).
Scene scene_from(const py::handle& scene) {
  if (py::isinstance<py::dict>(scene) || py::isinstance<py::list>(scene)) {
    const std::string text = py::module_::import("json").attr("dumps")(scene).cast<std::string>();
    return parse_scene(text, "scene");
  }
  if (py::isinstance<py::str>(scene)) {
    const std::string text = scene.cast<std::string>();
    if (text.find('{') != std::string::npos) return parse_scene(text, "scene");
  }
  if (py::isinstance<py::str>(scene) || py::hasattr(scene, "__fspath__")) return read_scene(scene.cast<std::filesystem::path>());
  throw InvalidInput("scene: expected a scene file's path, its JSON text or a dict in the scene format (docs/scene-format.md)");
}

}  // namespace

void bind_blends(py::module_& m) {
  m.def(
      "blend",
      [](const py::object& scene, int levels, const std::string& method, bool project, bool statistics, const std::string& show,
         double spacing, const py::object& progress) {
        if (method != "control" && method != "exact") throw InvalidInput("method: expected control or exact, got '" + method + "'");
        if (show != "blend" && show != "spline" && show != "union" && show != "primitives")
          throw InvalidInput("show: expected blend, spline, union or primitives, got '" + show + "'");
        const bool ingredients = show == "union" || show == "primitives";
        if (spacing != 0.0 && !ingredients) throw InvalidInput("spacing: is for show='union' or 'primitives'");
        if (spacing < 0.0 || !std::isfinite(spacing)) throw InvalidInput("spacing: expected a positive grid spacing, got " + std::to_string(spacing));
        if (project && method != "exact") throw InvalidInput("project: needs method='exact'");
        if (levels < 0 || levels > 8) throw InvalidInput("levels: expected 0 to 8, got " + std::to_string(levels));
        const Scene parsed = scene_from(scene);
        PythonProgress listener(progress);
        ZeroSetOptions options;
        options.levels = levels;
        options.method = method == "exact" ? ZeroSetMethod::Exact : ZeroSetMethod::Control;
        options.project = project;
        options.statistics = statistics;
        options.progress = listener.get();
        if (ingredients) {
          // The CSG ingredients, without the spline (boxspline/scene_ingredients.h).
          const double h = spacing > 0.0 ? spacing : default_ingredient_spacing(parsed, levels);
          const auto start = std::chrono::steady_clock::now();
          TriangleMesh mesh;
          {
            py::gil_scoped_release release;
            mesh = scene_ingredients_mesh(parsed, show == "union" ? SceneIngredients::Union : SceneIngredients::Primitives, h);
          }
          const EdgeStatistics edges = edge_statistics(mesh);
          py::dict stats;
          stats["show"] = show;
          stats["grid_spacing"] = h;
          stats["vertices"] = mesh.num_vertices();
          stats["triangles"] = mesh.num_triangles();
          stats["closed"] = edges.closed();
          stats["boundary_edges"] = edges.boundary_edges;
          stats["nonmanifold_edges"] = edges.nonmanifold_edges;
          stats["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          py::dict out = mesh_dict(mesh);
          out["stats"] = stats;
          return out;
        }
        ZeroSet result;
        {
          py::gil_scoped_release release;
          result = scene_zero_set(parsed, options);
        }
        listener.rethrow();
        const ZeroSetStats& s = result.stats;
        py::dict stats;
        stats["show"] = show;
        stats["grid_spacing"] = s.grid_spacing;
        stats["vertices"] = s.vertices;
        stats["triangles"] = s.triangles;
        stats["max_abs_value"] = s.max_abs_value;
        stats["max_distance"] = s.max_distance ? py::cast(*s.max_distance) : py::none();
        stats["seam_value_difference"] = s.seam_value_difference;
        stats["closed"] = s.closed;
        stats["boundary_edges"] = s.boundary_edges;
        stats["nonmanifold_edges"] = s.nonmanifold_edges;
        stats["seconds"] = s.seconds;
        py::dict out = mesh_dict(show == "spline" ? triangles_of_part(result.mesh, Part::BlendSpline) : result.mesh);
        out["stats"] = stats;
        return out;
      },
      py::arg("scene"), py::arg("levels") = 2, py::arg("method") = "control", py::arg("project") = false,
      py::arg("statistics") = true, py::arg("show") = "blend", py::arg("spacing") = 0.0, py::arg("progress") = py::none(),
      R"(Blends implicit primitives with the 7-direction box spline (Peters-Wittman 1995) and meshes the zero
set, as `volspline blend`. scene: a scene file's path, its JSON text, or a dict in the scene format
(docs/scene-format.md). levels: lattice refinements before marching (0..8); method: 'control' (the
paper's control polyhedron) or 'exact' (spline values; project=True moves vertices onto the zero
set). show: 'blend' (default), 'spline' (the box-spline part alone), 'union' (the pointwise minimum
of the root's children) or 'primitives' (each child on its own), the last two marched on a grid of
`spacing` (default the lattice spacing / 2**levels), as `volspline blend --show`. Returns a mesh
dict (part 11 the spline, 12 the primitives outside the box) with stats: vertices, triangles,
max_abs_value, max_distance (one known primitive), closed, seconds, ...)");
}

}  // namespace volspline::python
