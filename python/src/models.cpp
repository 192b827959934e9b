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

namespace volspline::python {
namespace {

// The tensor-product spline of an object as its Python class; None for a swept solid or a
// simplex spline volume, which the module does not bind yet (docs/python.md).
py::object spline_of(const ModelObject& object) {
  return std::visit(
      [](const auto& s) -> py::object {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, SweptSolid> || std::is_same_v<T, DmsSplineVolume>)
          return py::none();
        else
          return py::cast(s);
      },
      object.spline);
}

ModelObject object_of(SplineObject spline) { return ModelObject{std::string(), false, std::move(spline), nullptr, {}}; }

ModelObject object_from(const py::handle& item) {
  if (py::isinstance<ModelObject>(item)) return item.cast<ModelObject>();
  if (py::isinstance<TensorSpline<1>>(item)) return object_of(item.cast<TensorSpline<1>>());
  if (py::isinstance<TensorSpline<2>>(item)) return object_of(item.cast<TensorSpline<2>>());
  if (py::isinstance<TensorSpline<3>>(item)) return object_of(item.cast<TensorSpline<3>>());
  if (py::isinstance<TensorSpline<4>>(item)) return object_of(item.cast<TensorSpline<4>>());
  throw InvalidInput("objects: expected Curve, Surface, Volume, Hypervolume or ModelObject items, got " +
                     std::string(py::str(item.get_type().attr("__name__"))));
}

}  // namespace

void bind_models(py::module_& m) {
  py::class_<ModelObject>(m, "ModelObject", "One object of a model file: a name, a spline and named attributes.")
      .def(py::init([](const py::object& spline, const std::string& name, const std::map<std::string, std::vector<double>>& attributes) {
             ModelObject object = object_from(spline);
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
      .def_property_readonly("spline", &spline_of, "The spline (Curve, Surface, Volume, Hypervolume), or None for a "
                                                   "swept solid or a simplex spline volume.")
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
        for (const py::handle& item : objects) model.objects.push_back(object_from(item));
        py::gil_scoped_release release;
        write_model_file(model, path, format);
      },
      py::arg("path"), py::arg("objects"), py::arg("format") = "",
      "Writes splines or ModelObjects to a model file (format by extension unless given), atomically: a failed "
      "write leaves no file behind.");
}

}  // namespace volspline::python
