#pragma once
// The Python module's parts (docs/python.md): each file binds one layer of the library.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

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

void bind_tensor_splines(py::module_& m);
void bind_constructions(py::module_& m);
void bind_models(py::module_& m);
void bind_analysis(py::module_& m);

}  // namespace volspline::python
