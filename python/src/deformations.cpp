// Free-form deformation (docs/ffd.md): lattices around meshes or points, and the deformation of
// points, meshes, curves, surfaces and models through them (the command line's lattice and ffd).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <optional>

#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/lattice.h"
#include "volspline/pipeline/model_deformation.h"

namespace volspline::python {
namespace {

// A Lattice given as itself, or as what volspline.read takes (a path, or the objects of a
// lattice model file).
Lattice lattice_of(const py::handle& lattice) {
  if (py::isinstance<Lattice>(lattice)) return lattice.cast<Lattice>();
  const std::string source = py::isinstance<py::str>(lattice) || py::hasattr(lattice, "__fspath__")
                                 ? lattice.cast<std::filesystem::path>().string()
                                 : std::string("lattice");
  return lattice_from_model(model_from(lattice), source);
}

py::array_t<double> points_array(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> flat(points.size() * 3);
  if (!points.empty()) std::memcpy(flat.data(), points.front().data(), flat.size() * sizeof(double));
  return array_over(std::move(flat), {static_cast<py::ssize_t>(points.size()), 3}, {3, 1});
}

}  // namespace

void bind_deformations(py::module_& m) {
  py::class_<Lattice>(m, "Lattice",
                      "A free-form deformation lattice (docs/ffd.md): a B-spline volume over the box origin + axes * [0, 1]^3 "
                      "whose control points are moved to deform what lies in the box. Made by lattice(), read by "
                      "lattice_from(); to_objects() gives what volspline.write stores as a lattice file.")
      .def_readonly("volume", &Lattice::volume, "The lattice volume: the identity on the box until its points are moved.")
      .def_readonly("origin", &Lattice::origin, "The box corner at (u, v, w) = (0, 0, 0).")
      .def_readonly("axes", &Lattice::axes, "The box edges U, V, W as the columns of a 3 x 3 matrix.")
      .def(
          "with_volume",
          [](const Lattice& lattice, const BSplineVolume& volume) {
            Lattice moved = lattice;
            moved.volume = volume;
            validate_lattice(moved);
            return moved;
          },
          py::arg("volume"),
          "The same box with another volume (the lattice with its control points moved). Raises InvalidInput when the "
          "volume's degrees, knots or domain do not fit the box.")
      .def("to_objects", [](const Lattice& lattice) { return lattice_to_model(lattice).objects; },
           "The lattice as model objects (its volume with metadata.lattice), for volspline.write: the file the command "
           "line's lattice writes and ffd reads.")
      .def("coordinates", [](const Lattice& lattice, const Eigen::Vector3d& x) { return lattice_coordinates(lattice, x); },
           py::arg("point"), "The (s, t, u) of a point in the box: x = origin + axes * (s, t, u).");

  m.def(
      "lattice",
      [](const py::object& around, std::array<int, 3> degree, std::array<int, 3> divisions, double margin,
         const std::optional<Eigen::Matrix3d>& axes) {
        const Eigen::Matrix3d directions = axes ? *axes : Eigen::Matrix3d::Identity();
        if (py::isinstance<py::dict>(around)) return undeformed_lattice(mesh_from(around), degree, divisions, margin, directions);
        return undeformed_lattice(points_from(around, "around"), degree, divisions, margin, directions);
      },
      py::arg("around"), py::arg("degree"), py::arg("divisions") = std::array<int, 3>{1, 1, 1}, py::arg("margin") = 0.05,
      py::arg("axes") = py::none(),
      "The undeformed lattice (the identity map) around a mesh dict or points (N, 3) (lattice MESH): B-spline degree "
      "(p, q, r), divisions Bézier cells per direction, the box grown by margin times its longest edge on every "
      "side, its edges along the columns of axes (default the coordinate axes; need not be orthogonal).");
  m.def("lattice_from", &lattice_of, py::arg("lattice"),
        "The lattice of a lattice model file (a path) or of its objects. Raises InvalidInput naming what is missing.");
  m.def(
      "ffd",
      [](const py::object& lattice_like, const py::object& x) -> py::object {
        const Lattice lattice = lattice_of(lattice_like);
        if (py::isinstance<py::dict>(x)) {
          const TriangleMesh mesh = mesh_from(x);
          TriangleMesh deformed;
          {
            py::gil_scoped_release release;
            deformed = deform_mesh(lattice, mesh);
          }
          return mesh_dict(deformed);
        }
        if (py::isinstance<BSplineCurve>(x)) return py::cast(deform_curve(lattice, x.cast<BSplineCurve>()));
        if (py::isinstance<BSplineSurface>(x)) return py::cast(deform_surface(lattice, x.cast<BSplineSurface>()));
        if (py::isinstance<BSplineVolume>(x)) return py::cast(compose(lattice, x.cast<BSplineVolume>()));
        if (py::isinstance<py::str>(x) || py::hasattr(x, "__fspath__") || py::isinstance<py::list>(x) || py::isinstance<py::tuple>(x) ||
            py::isinstance<ModelObject>(x)) {
          const std::string source = py::isinstance<py::str>(x) || py::hasattr(x, "__fspath__") ? x.cast<std::filesystem::path>().string() : "";
          Model model = model_from(x);
          {
            py::gil_scoped_release release;
            model = deform_model(lattice, std::move(model), source);
          }
          return py::cast(model.objects);
        }
        const std::vector<Eigen::Vector3d> points = points_from(x, "points");
        std::vector<Eigen::Vector3d> moved;
        {
          py::gil_scoped_release release;
          moved = deform_points(lattice, points);
        }
        return points_array(moved);
      },
      py::arg("lattice"), py::arg("x"),
      "Free-form deformation through a lattice (a Lattice, or a lattice file or its objects) (ffd LATTICE INPUT): a "
      "mesh dict gives the deformed mesh; points (N, 3) the deformed points; a Curve, Surface or Volume its exact "
      "composition with the lattice map (degrees multiply); a model (a path, objects or a list of them) its deformed "
      "objects as the command line's ffd writes them (curves and surfaces composed exactly, simplex spline volumes by "
      "their control points). A point outside the box moves as the nearest point of the box does (docs/ffd.md).");
}

}  // namespace volspline::python
