// Model files in every format the command line reads and writes (io/model_formats.h):
// volspline.read, volspline.write and ModelObject (docs/python.md, docs/formats.md).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <map>
#include <string>

#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/io/vtk_xml.h"

namespace volspline::python {
namespace {

// The spline of an object as its Python class: Curve .. Hypervolume, SweptSolid or
// SimplexSplineVolume.
py::object spline_of(const ModelObject& object) {
  return std::visit([](const auto& s) -> py::object { return py::cast(s); }, object.spline);
}

ModelObject object_of(SplineObject spline) { return ModelObject{std::string(), false, std::move(spline), nullptr, {}}; }

}  // namespace

ModelObject model_object_from(const py::handle& item) {
  if (py::isinstance<ModelObject>(item)) return item.cast<ModelObject>();
  if (py::isinstance<SweptSolid>(item)) return object_of(item.cast<SweptSolid>());
  if (py::isinstance<DmsSplineVolume>(item)) return object_of(item.cast<DmsSplineVolume>());
  if (py::isinstance<TensorSpline<1>>(item)) return object_of(item.cast<TensorSpline<1>>());
  if (py::isinstance<TensorSpline<2>>(item)) return object_of(item.cast<TensorSpline<2>>());
  if (py::isinstance<TensorSpline<3>>(item)) return object_of(item.cast<TensorSpline<3>>());
  if (py::isinstance<TensorSpline<4>>(item)) return object_of(item.cast<TensorSpline<4>>());
  throw InvalidInput("objects: expected Curve, Surface, Volume, Hypervolume, SweptSolid, SimplexSplineVolume or "
                     "ModelObject items, got " + std::string(py::str(item.get_type().attr("__name__"))));
}

Model model_from(const py::handle& model) {
  if (py::isinstance<py::str>(model) || py::hasattr(model, "__fspath__")) {
    const auto path = model.cast<std::filesystem::path>();
    py::gil_scoped_release release;
    return read_model_file(path);
  }
  Model out;
  if (py::isinstance<py::list>(model) || py::isinstance<py::tuple>(model)) {
    for (const py::handle& item : model) out.objects.push_back(model_object_from(item));
  } else {
    out.objects.push_back(model_object_from(model));
  }
  if (out.objects.empty()) throw InvalidInput("model: expected at least one object");
  return out;
}

void bind_models(py::module_& m) {
  py::class_<ModelObject>(m, "ModelObject", "One object of a model file: a name, a spline and named attributes.")
      .def(py::init([](const py::object& spline, const std::string& name, const std::map<std::string, std::vector<double>>& attributes) {
             ModelObject object = model_object_from(spline);
             object.name = name;
             object.attributes = attributes;
             validate_attributes(object);
             return object;
           }),
           py::arg("spline"), py::arg("name") = "", py::arg("attributes") = std::map<std::string, std::vector<double>>{},
           "attributes: name -> one value per control point, first index fastest. Raises InvalidInput for a wrong count.")
      .def_readonly("name", &ModelObject::name)
      .def_property_readonly("type", [](const ModelObject& o) { return object_type_name(o); },
                             "The model-format type, e.g. bspline_volume, swept_solid, simplex_spline_volume.")
      .def_property_readonly("spline", &spline_of, "The spline: Curve, Surface, Volume, Hypervolume, SweptSolid or "
                                                   "SimplexSplineVolume.")
      .def_property_readonly("attributes", [](const ModelObject& o) { return o.attributes; })
      .def("__repr__", [](const ModelObject& o) {
        return "<volspline.ModelObject " + object_type_name(o) + (o.name.empty() ? "" : " '" + o.name + "'") + ">";
      });

  m.def(
      "read",
      [](const std::filesystem::path& path, const std::string& format) {
        Model model;
        {
          py::gil_scoped_release release;
          model = read_model_file(path, format);
        }
        return model.objects;
      },
      py::arg("path"), py::arg("format") = "",
      "The objects of a model file in any format the command line reads (JSON model, G+Smo XML, IRIT .itd, "
      "...; chosen by extension unless format is given). Raises InvalidInput naming the file and the place, "
      "IoError if it cannot be read.");
  m.def(
      "write",
      [](const std::filesystem::path& path, const py::iterable& objects, const std::string& format) {
        Model model;
        for (const py::handle& item : objects) model.objects.push_back(model_object_from(item));
        py::gil_scoped_release release;
        write_model_file(model, path, format);
      },
      py::arg("path"), py::arg("objects"), py::arg("format") = "",
      "Writes splines or ModelObjects to a model file (format by extension unless given), atomically: a failed "
      "write leaves no file behind.");
  m.def(
      "vtu_text",
      [](const py::object& model) {
        const Model objects = model_from(model);
        py::gil_scoped_release release;
        return vtu_text(objects);
      },
      py::arg("model"),
      "The VTK XML unstructured grid (.vtu) text of a model, as `volspline convert -o OUT.vtu` writes it: rational "
      "Bezier cells for tensor-product volumes, Lagrange tetrahedra for simplex spline volumes (docs/formats.md).");
}

}  // namespace volspline::python
