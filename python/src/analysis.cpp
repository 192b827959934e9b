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

}  // namespace

void bind_analysis(py::module_& m) {
  m.def(
      "check_jacobian",
      [](const BSplineVolume& volume, const std::string& bounds, double tolerance, std::int64_t max_cells,
         const py::object& progress) {
        JacobianValidityOptions options;
        options.bounds = bound_method(bounds);
        options.tolerance = tolerance;
        options.max_cells = max_cells;
        PythonProgress listener(progress);
        options.progress = listener.get();
        JacobianValidity v;
        {
          py::gil_scoped_release release;
          v = check_jacobian(volume, options);
        }
        listener.rethrow();
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
      py::arg("progress") = py::none(),
      "Is J != 0 on the whole domain? A dict: verdict ('valid', 'invalid', 'undecided', certified), orientation "
      "(+1/-1 when valid), certified lower/upper bounds of J, a witness (u, v, w) for 'invalid', cells, seconds "
      "(volspline jacobian). progress: None or a callable progress(phase, fraction).");
  m.def(
      "boundary",
      [](const BSplineVolume& volume, double tolerance, std::int64_t max_cells, int face_resolution, bool snap,
         const std::string& bounds, const py::object& progress) {
        BoundaryOptions options;
        options.tolerance = tolerance;
        options.max_cells = max_cells;
        options.face_resolution = face_resolution;
        options.snap = snap;
        options.bounds = bound_method(bounds);
        PythonProgress listener(progress);
        options.progress = listener.get();
        SolidBoundary b;
        {
          py::gil_scoped_release release;
          b = solid_boundary(volume, options);
        }
        listener.rethrow();
        py::dict stats;
        stats["cells_examined"] = b.stats.cells_examined;
        stats["cells_kept"] = b.stats.cells_kept;
        stats["max_domain_distance"] = b.stats.max_domain_distance;
        stats["seconds"] = b.stats.seconds_total;
        py::dict out = mesh_dict(b.mesh);
        out["stats"] = stats;
        return out;
      },
      py::arg("volume"), py::arg("tolerance") = 1e-3, py::arg("max_cells") = 200000, py::arg("face_resolution") = 24,
      py::arg("snap") = false, py::arg("bounds") = "bezier", py::arg("progress") = py::none(),
      "The boundary of the solid (Joy-Duchaineau): the six faces and the surface J = 0, as a dict of vertices "
      "(V, 3), parameters (u, v, w) (V, 3), triangles (F, 3), parts (F,), part_names and stats (volspline "
      "boundary). progress: None or a callable progress(phase, fraction).");
}

}  // namespace volspline::python
