#pragma once
// The Python module's parts (docs/python.md): each file binds one layer of the library.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <vector>

#include "volspline/core/progress.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/render/image.h"

namespace volspline::python {

namespace py = pybind11;

/// A numpy array over `data` without copying it: the vector moves into a capsule that the array
/// owns. `shape` and `strides` (in elements, not bytes) describe the layout.
inline py::array_t<double> array_over(std::vector<double>&& data, std::vector<py::ssize_t> shape,
                                      std::vector<py::ssize_t> strides) {
  auto* owner = new std::vector<double>(std::move(data));
  py::capsule capsule(owner, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  for (auto& s : strides) s *= static_cast<py::ssize_t>(sizeof(double));
  return py::array_t<double>(shape, strides, owner->data(), capsule);
}

/// A triangle mesh as the dict every mesh-returning function gives: vertices (V, 3), parameters
/// (V, 3) (each vertex's (u, v, w) where the producer knows them), triangles (F, 3) int32,
/// parts (F,) int32 and part_names (part number -> name, mesh/parts.h).
py::dict mesh_dict(const TriangleMesh& mesh);

/// The mesh of such a dict: vertices and triangles required, parameters and parts optional
/// (zeros). \throw InvalidInput naming the key for a missing key, a wrong shape or an index out of
/// range.
TriangleMesh mesh_from(const py::handle& mesh);

/// A library Progress that hands every report to a Python callable `callback(phase, fraction)`
/// (None: no Progress at all). The library reports from worker threads with the GIL released;
/// each call takes the GIL. An exception the callback raises is kept, later reports are dropped,
/// and rethrow() raises it once the library call has returned (the operation itself runs to its
/// end: the library has no cancellation point).
class PythonProgress {
 public:
  explicit PythonProgress(const py::object& callback);
  PythonProgress(const PythonProgress&) = delete;
  PythonProgress& operator=(const PythonProgress&) = delete;
  /// The Progress to give the library, or null without a callback.
  Progress* get() { return progress_.get(); }
  /// Raises what the callback raised, if anything. Call with the GIL held.
  void rethrow();

 private:
  py::object callback_;
  std::unique_ptr<Progress> progress_;
  std::unique_ptr<py::error_already_set> error_;
};

/// An Image as an array of shape (height, width, 4), uint8, rows top to bottom.
py::array_t<std::uint8_t> image_array(const Image& image);

/// Points from an array of shape (N, 3), or one point (3,). \throw InvalidInput naming `what`
/// for another shape.
std::vector<Eigen::Vector3d> points_from(const py::handle& object, const char* what);

/// The model object of a Curve .. Hypervolume, SweptSolid, SimplexSplineVolume or ModelObject.
/// \throw InvalidInput for anything else.
ModelObject model_object_from(const py::handle& item);
/// A model from a path (read in any format), one object, or a list or tuple of objects.
Model model_from(const py::handle& model);

void bind_meshes(py::module_& m);
void bind_pictures(py::module_& m);
void bind_blends(py::module_& m);
void bind_swept_solids(py::module_& m);
void bind_simplex_splines(py::module_& m);
void bind_tensor_splines(py::module_& m);
void bind_constructions(py::module_& m);
void bind_models(py::module_& m);
void bind_analysis(py::module_& m);
void bind_deformations(py::module_& m);

}  // namespace volspline::python
