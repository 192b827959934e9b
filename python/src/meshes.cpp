// Triangle meshes between the library and Python: the dict every mesh-returning function gives,
// volspline.render (a mesh to an RGBA array, as the command line's pictures) and
// volspline.write_mesh (PLY, OBJ, STL, glTF), and progress callbacks (docs/python.md).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <string>

#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/parts.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::python {

py::dict mesh_dict(const TriangleMesh& mesh) {
  const auto n = static_cast<py::ssize_t>(mesh.num_vertices());
  const auto f = static_cast<py::ssize_t>(mesh.num_triangles());
  std::vector<double> positions, parameters;
  positions.reserve(static_cast<std::size_t>(3 * n));
  parameters.reserve(static_cast<std::size_t>(3 * n));
  for (std::size_t i = 0; i < mesh.num_vertices(); ++i)
    for (int c = 0; c < 3; ++c) {
      positions.push_back(mesh.positions[i][c]);
      parameters.push_back(i < mesh.parameters.size() ? mesh.parameters[i][c] : 0.0);
    }
  py::array_t<std::int32_t> triangles({f, py::ssize_t{3}});
  py::array_t<std::int32_t> parts(f);
  for (py::ssize_t t = 0; t < f; ++t) {
    for (int c = 0; c < 3; ++c) triangles.mutable_at(t, c) = mesh.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)];
    parts.mutable_at(t) = mesh.parts[static_cast<std::size_t>(t)];
  }
  py::dict names;
  for (int part : mesh.parts)
    if (!names.contains(py::int_(part))) names[py::int_(part)] = part_name(part);
  py::dict out;
  out["vertices"] = array_over(std::move(positions), {n, 3}, {3, 1});
  out["parameters"] = array_over(std::move(parameters), {n, 3}, {3, 1});
  out["triangles"] = triangles;
  out["parts"] = parts;
  out["part_names"] = names;
  return out;
}

namespace {

// The entry `key` of a mesh dict (or attribute of a mesh object); None if absent and optional.
py::object mesh_entry(const py::handle& mesh, const char* key, bool required) {
  py::object value;
  if (py::isinstance<py::dict>(mesh)) {
    py::dict d = py::reinterpret_borrow<py::dict>(mesh);
    if (d.contains(key)) value = d[key];
  } else if (py::hasattr(mesh, key)) {
    value = mesh.attr(key);
  }
  if (!value || value.is_none()) {
    if (required) throw InvalidInput(std::string("mesh: expected a '") + key + "' entry (a dict as volspline.boundary returns)");
    return py::none();
  }
  return value;
}

}  // namespace

TriangleMesh mesh_from(const py::handle& mesh) {
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  using Ints = py::array_t<long long, py::array::c_style | py::array::forcecast>;
  const Doubles vertices = Doubles::ensure(mesh_entry(mesh, "vertices", true));
  const Ints triangles = Ints::ensure(mesh_entry(mesh, "triangles", true));
  if (!vertices || vertices.ndim() != 2 || vertices.shape(1) != 3) throw InvalidInput("mesh['vertices']: expected an array of shape (V, 3)");
  if (!triangles || triangles.ndim() != 2 || triangles.shape(1) != 3) throw InvalidInput("mesh['triangles']: expected an array of shape (F, 3)");
  const py::ssize_t n = vertices.shape(0), f = triangles.shape(0);
  const py::object parameters_entry = mesh_entry(mesh, "parameters", false);
  const py::object parts_entry = mesh_entry(mesh, "parts", false);
  Doubles parameters;
  Ints parts;
  if (!parameters_entry.is_none()) {
    parameters = Doubles::ensure(parameters_entry);
    if (!parameters || parameters.ndim() != 2 || parameters.shape(0) != n || parameters.shape(1) != 3)
      throw InvalidInput("mesh['parameters']: expected an array of shape (" + std::to_string(n) + ", 3)");
  }
  if (!parts_entry.is_none()) {
    parts = Ints::ensure(parts_entry);
    if (!parts || parts.ndim() != 1 || parts.shape(0) != f)
      throw InvalidInput("mesh['parts']: expected an array of shape (" + std::to_string(f) + ",)");
  }
  TriangleMesh out;
  out.positions.reserve(static_cast<std::size_t>(n));
  out.parameters.reserve(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    out.positions.emplace_back(vertices.at(i, 0), vertices.at(i, 1), vertices.at(i, 2));
    out.parameters.push_back(!parameters_entry.is_none() ? Eigen::Vector3d(parameters.at(i, 0), parameters.at(i, 1), parameters.at(i, 2))
                                        : Eigen::Vector3d::Zero());
  }
  for (py::ssize_t t = 0; t < f; ++t) {
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      const long long index = triangles.at(t, c);
      if (index < 0 || index >= n)
        throw InvalidInput("mesh['triangles'][" + std::to_string(t) + "]: vertex index " + std::to_string(index) +
                           " is not in 0.." + std::to_string(n - 1));
      corners[static_cast<std::size_t>(c)] = static_cast<int>(index);
    }
    out.triangles.push_back(corners);
    out.parts.push_back(!parts_entry.is_none() ? static_cast<int>(parts.at(t)) : 0);
  }
  return out;
}

PythonProgress::PythonProgress(const py::object& callback) : callback_(callback) {
  if (callback_.is_none()) return;
  if (!PyCallable_Check(callback_.ptr())) throw InvalidInput("progress: expected a callable progress(phase, fraction) or None");
  progress_ = std::make_unique<Progress>([this](const ProgressEvent& event) {
    py::gil_scoped_acquire gil;
    if (error_) return;
    try {
      callback_(std::string(event.phase), event.fraction);
    } catch (py::error_already_set& e) {
      error_ = std::make_unique<py::error_already_set>(std::move(e));
    }
  });
}

void PythonProgress::rethrow() {
  if (error_) {
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
  }
}

py::array_t<std::uint8_t> image_array(const Image& image) {
  py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width), py::ssize_t{4}});
  if (!image.rgba.empty()) std::memcpy(out.mutable_data(), image.rgba.data(), image.rgba.size());
  return out;
}

namespace {

Image image_from(const py::handle& rgba) {
  using Bytes = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
  const Bytes a = Bytes::ensure(rgba);
  if (!a || a.ndim() != 3 || (a.shape(2) != 4 && a.shape(2) != 3))
    throw InvalidInput("image: expected an array of shape (height, width, 4) or (height, width, 3), dtype uint8");
  Image image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  for (py::ssize_t y = 0; y < a.shape(0); ++y)
    for (py::ssize_t x = 0; x < a.shape(1); ++x) {
      std::uint8_t* p = image.pixel(static_cast<int>(x), static_cast<int>(y));
      for (py::ssize_t c = 0; c < 4; ++c) p[c] = c < a.shape(2) ? a.at(y, x, c) : 255;
    }
  return image;
}

}  // namespace

void bind_meshes(py::module_& m) {
  m.def(
      "render",
      [](const py::object& mesh, std::array<int, 2> size, const Eigen::Vector3d& view, const Eigen::Vector3d& up, bool edges,
         bool transparent, const std::optional<std::vector<double>>& scalars, const std::optional<std::array<double, 2>>& range,
         const std::string& title) {
        const TriangleMesh triangles = mesh_from(mesh);
        RenderOptions options;
        options.width = size[0];
        options.height = size[1];
        options.view_direction = view;
        options.up = up;
        options.edges = edges;
        options.transparent_background = transparent;
        if (scalars) {
          options.color = ColorMode::Scalar;
          options.vertex_scalars = *scalars;
          options.color_bar_title = title;
          if (range) {
            options.scalar_min = (*range)[0];
            options.scalar_max = (*range)[1];
          }
        }
        Image image;
        {
          py::gil_scoped_release release;
          image = render_mesh(triangles, options);
        }
        return image_array(image);
      },
      py::arg("mesh"), py::arg("size") = std::array<int, 2>{800, 600}, py::arg("view") = Eigen::Vector3d(-1.0, -1.3, -0.8),
      py::arg("up") = Eigen::Vector3d(0.0, 0.0, 1.0), py::arg("edges") = false, py::arg("transparent") = false,
      py::arg("scalars") = py::none(), py::arg("range") = py::none(), py::arg("title") = "",
      "The picture of a mesh (a dict as boundary, blend or view return) as an RGBA array of shape (height, width, 4), "
      "uint8, rendered as the command line's --png: each part in its colour, or coloured by `scalars` (one per vertex) "
      "over `range` (default: their extremes) with a colour bar titled `title`. size is (width, height); view is the "
      "direction the camera looks in.");
  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const py::object& mesh, bool ascii) {
        const TriangleMesh triangles = mesh_from(mesh);
        MeshWriteOptions options;
        options.ascii = ascii;
        mesh_format_from_path(path);
        py::gil_scoped_release release;
        write_mesh(triangles, path, options);
      },
      py::arg("path"), py::arg("mesh"), py::arg("ascii") = false,
      "Writes a mesh dict as PLY (positions, (u, v, w), parts), OBJ, STL or binary glTF (.glb, part colours), chosen by "
      "the extension, atomically: a failed write leaves no file behind.");
  m.def(
      "write_png",
      [](const std::filesystem::path& path, const py::object& rgba) {
        const Image image = image_from(rgba);
        py::gil_scoped_release release;
        write_png(image, path);
      },
      py::arg("path"), py::arg("image"), "Writes an RGBA (or RGB) uint8 array of shape (height, width, 4) as a PNG file, atomically.");
}

}  // namespace volspline::python
