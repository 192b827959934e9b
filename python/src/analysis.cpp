// Certified analysis of volumes (analysis/, extract/): volspline.check_jacobian and
// volspline.boundary (docs/jacobian.md, docs/boundary.md, docs/python.md).
#include <pybind11/stl.h>

#include <string>

#include "bindings.h"
#include "volspline/analysis/jacobian_validity.h"
#include "volspline/core/error.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/mesh/parts.h"

namespace volspline::python {
namespace {

JacobianBoundMethod bound_method(const std::string& name) {
  if (name == "bezier") return JacobianBoundMethod::Bezier;
  if (name == "cone") return JacobianBoundMethod::Cone;
  throw InvalidInput("bounds: expected bezier or cone, got '" + name + "'");
}

py::array_t<int> int_array(const std::vector<int>& values, py::ssize_t columns) {
  const auto rows = static_cast<py::ssize_t>(values.size()) / columns;
  py::array_t<int> a(columns == 1 ? std::vector<py::ssize_t>{rows} : std::vector<py::ssize_t>{rows, columns});
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def(
      "check_jacobian",
      [](const BSplineVolume& volume, const std::string& bounds, double tolerance, std::int64_t max_cells) {
        JacobianValidityOptions options;
        options.bounds = bound_method(bounds);
        options.tolerance = tolerance;
        options.max_cells = max_cells;
        JacobianValidity v;
        {
          py::gil_scoped_release release;
          v = check_jacobian(volume, options);
        }
        py::dict out;
        out["verdict"] = verdict_name(v.verdict);
        out["orientation"] = v.orientation;
        out["lower"] = v.lower;
        out["upper"] = v.upper;
        out["witness"] = v.witness ? py::cast(*v.witness) : py::none();
        out["witness_value"] = v.witness_value;
        out["reference_point"] = v.reference_point ? py::cast(*v.reference_point) : py::none();
        out["cells"] = v.cells;
        out["seconds"] = v.seconds;
        return out;
      },
      py::arg("volume"), py::arg("bounds") = "bezier", py::arg("tolerance") = 1e-12, py::arg("max_cells") = 200000,
      "Is J != 0 on the whole domain? A dict: verdict ('valid', 'invalid', 'undecided', certified), orientation "
      "(+1/-1 when valid), certified lower/upper bounds of J, a witness (u, v, w) for 'invalid', cells, seconds "
      "(volspline jacobian).");
  m.def(
      "boundary",
      [](const BSplineVolume& volume, double tolerance, std::int64_t max_cells, int face_resolution, bool snap,
         const std::string& bounds) {
        BoundaryOptions options;
        options.tolerance = tolerance;
        options.max_cells = max_cells;
        options.face_resolution = face_resolution;
        options.snap = snap;
        options.bounds = bound_method(bounds);
        SolidBoundary b;
        {
          py::gil_scoped_release release;
          b = solid_boundary(volume, options);
        }
        const auto n = static_cast<py::ssize_t>(b.mesh.num_vertices());
        std::vector<double> positions, parameters;
        positions.reserve(static_cast<std::size_t>(3 * n));
        parameters.reserve(static_cast<std::size_t>(3 * n));
        for (std::size_t i = 0; i < b.mesh.num_vertices(); ++i)
          for (int c = 0; c < 3; ++c) {
            positions.push_back(b.mesh.positions[i][c]);
            parameters.push_back(b.mesh.parameters[i][c]);
          }
        std::vector<int> triangles;
        triangles.reserve(3 * b.mesh.num_triangles());
        for (const auto& t : b.mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
        py::dict names;
        for (int part : b.mesh.parts)
          if (!names.contains(py::int_(part))) names[py::int_(part)] = part_name(part);
        py::dict stats;
        stats["cells_examined"] = b.stats.cells_examined;
        stats["cells_kept"] = b.stats.cells_kept;
        stats["max_domain_distance"] = b.stats.max_domain_distance;
        stats["seconds"] = b.stats.seconds_total;
        py::dict out;
        out["vertices"] = array_over(std::move(positions), {n, 3}, {3, 1});
        out["parameters"] = array_over(std::move(parameters), {n, 3}, {3, 1});
        out["triangles"] = int_array(triangles, 3);
        out["parts"] = int_array(b.mesh.parts, 1);
        out["part_names"] = names;
        out["stats"] = stats;
        return out;
      },
      py::arg("volume"), py::arg("tolerance") = 1e-3, py::arg("max_cells") = 200000, py::arg("face_resolution") = 24,
      py::arg("snap") = false, py::arg("bounds") = "bezier",
      "The boundary of the solid (Joy-Duchaineau): the six faces and the surface J = 0, as a dict of vertices "
      "(V, 3), parameters (u, v, w) (V, 3), triangles (F, 3), parts (F,), part_names and stats (volspline "
      "boundary).");
}

}  // namespace volspline::python
