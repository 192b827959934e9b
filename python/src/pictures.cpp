// Looking inside solids (Lasser 1994 §IV) from Python: volspline.view, the whole `volspline view`
// pipeline (pipeline/solid_view_picture.h) returning the picture as an array and the mesh as a
// dict (docs/view.md, docs/python.md).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/pipeline/solid_view_picture.h"

namespace volspline::python {
namespace {

// "u", "v", "w" (or "x", "y", "z") as 0, 1, 2.
int axis_index(const std::string& name, const char* names, const std::string& what) {
  if (name.size() == 1)
    for (int i = 0; i < 3; ++i)
      if (name[0] == names[i]) return i;
  throw InvalidInput(what + ": expected '" + std::string(1, names[0]) + "', '" + std::string(1, names[1]) + "' or '" +
                     std::string(1, names[2]) + "', got '" + name + "'");
}

int surface_count(int count, const std::string& what) {
  if (count < 1 || count > 1000) throw InvalidInput(what + ": expected 1 to 1000 surfaces, got " + std::to_string(count));
  return count;
}

}  // namespace

void bind_pictures(py::module_& m) {
  using Family = std::pair<std::string, int>;
  using PlaneSpec = std::pair<Eigen::Vector3d, double>;
  m.def(
      "view",
      [](const py::object& model, const std::vector<Family>& iso, const std::optional<std::array<double, 3>>& through,
         const std::vector<Family>& slices, const std::vector<PlaneSpec>& planes, const std::optional<Eigen::Vector3d>& core,
         const std::vector<Family>& paddlewheels, bool faces, bool cutaway, const std::string& color,
         const std::optional<std::array<double, 2>>& range, int resolution, std::array<int, 2> size,
         const Eigen::Vector3d& camera, const Eigen::Vector3d& up, bool edges, bool transparent,
         const std::optional<std::filesystem::path>& png, const py::object& progress) {
        SolidViewPictureRequest request;
        const Model objects = model_from(model);
        if (py::isinstance<py::str>(model) || py::hasattr(model, "__fspath__")) request.source_name = py::str(model);
        SolidViewRequest& v = request.view;
        v.resolution = resolution;
        v.faces = faces;
        v.cutaway = cutaway;
        for (const auto& [name, count] : iso) v.families.push_back({axis_index(name, "uvw", "iso"), surface_count(count, "iso")});
        v.through = through;
        for (const auto& [name, count] : slices) v.series.push_back({axis_index(name, "xyz", "slices"), surface_count(count, "slices")});
        for (const auto& [normal, offset] : planes) {
          if (normal.norm() == 0) throw InvalidInput("planes: the normal must not be zero");
          v.planes.push_back({normal, offset});
        }
        v.core = core;
        for (const auto& [name, count] : paddlewheels)
          v.paddlewheels.push_back({axis_index(name, "xyz", "paddlewheels"), surface_count(count, "paddlewheels"), std::nullopt});
        if (cutaway && planes.empty() && !core) throw InvalidInput("cutaway: needs a cross section (planes) or a core section (core) to cut along");
        if (v.probes_empty()) v.faces = true;
        if (!color.empty()) request.color = scalar_field_named(color);
        if (range) {
          if (!((*range)[0] < (*range)[1])) throw InvalidInput("range: expected (min, max) with min < max");
          request.range = std::pair((*range)[0], (*range)[1]);
        }
        request.render.width = size[0];
        request.render.height = size[1];
        if (camera.norm() == 0) throw InvalidInput("camera: the view direction must not be zero");
        request.render.view_direction = camera;
        request.render.up = up;
        request.render.edges = edges;
        request.render.transparent_background = transparent;
        PythonProgress listener(progress);
        SolidViewPicture picture;
        {
          py::gil_scoped_release release;
          picture = solid_view_picture(objects, request, listener.get());
          if (png) write_png(picture.image, *png);
        }
        listener.rethrow();
        py::dict out;
        out["image"] = image_array(picture.image);
        out["mesh"] = mesh_dict(picture.mesh);
        if (!picture.render.vertex_scalars.empty()) {
          out["scalars"] = py::array_t<double>(static_cast<py::ssize_t>(picture.render.vertex_scalars.size()),
                                               picture.render.vertex_scalars.data());
          out["range"] = py::make_tuple(picture.render.scalar_min, picture.render.scalar_max);
        } else {
          out["scalars"] = py::none();
          out["range"] = py::none();
        }
        std::vector<py::tuple> plane_list;
        for (const auto& p : picture.planes) plane_list.push_back(py::make_tuple(p.normal, p.offset));
        out["planes"] = plane_list;
        out["volumes"] = picture.volumes;
        return out;
      },
      py::arg("model"), py::kw_only(), py::arg("iso") = std::vector<Family>{}, py::arg("through") = py::none(),
      py::arg("slices") = std::vector<Family>{}, py::arg("planes") = std::vector<PlaneSpec>{}, py::arg("core") = py::none(),
      py::arg("paddlewheels") = std::vector<Family>{}, py::arg("faces") = false, py::arg("cutaway") = false,
      py::arg("color") = "", py::arg("range") = py::none(), py::arg("resolution") = 32,
      py::arg("size") = std::array<int, 2>{800, 600}, py::arg("camera") = Eigen::Vector3d(-1.0, -1.3, -0.8),
      py::arg("up") = Eigen::Vector3d(0.0, 0.0, 1.0), py::arg("edges") = false, py::arg("transparent") = false,
      py::arg("png") = py::none(), py::arg("progress") = py::none(),
      R"(Looking inside solids (Lasser 1994 §IV), as `volspline view`.

model: a model file's path, a Volume, or a list of Volumes / ModelObjects (attributes travel with
ModelObjects). What to show (all optional; nothing asked for shows the solid):
  iso=[("u", 5)]           isoparametric surfaces u = const (u, v or w), N evenly spaced
  through=(u, v, w)        the three isoparametric surfaces through one point (Lasser Fig. 10)
  slices=[("x", 5)]        a series of N planar slices normal to x, y or z
  planes=[((nx, ny, nz), d)]  cross sections n . x = d
  core=(x, y, z)           three orthogonal slices through a point
  paddlewheels=[("z", 6)]  N planes through a line parallel to an axis through the centre
  faces, cutaway           the six faces too; a wedge cut away along planes/core
color: "jacobian", "u", "v", "w" or an attribute name; range=(min, max) of the colour map.
size=(width, height), camera (view direction), up, edges, transparent; png: also write the
picture there. Returns a dict: image (height, width, 4) uint8, mesh (a mesh dict), scalars (per
vertex, or None), range, planes [(normal, offset)], volumes.)");
}

}  // namespace volspline::python
