// The Python module volspline._volspline (docs/python.md); volspline/__init__.py re-exports it.
#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/core/version.h"

PYBIND11_MODULE(_volspline, m) {
  namespace py = pybind11;
  m.doc() = "volspline: free-form trivariate spline solids (C++ library bindings)";
  m.attr("__version__") = volspline::kVersion;

  // volspline::Error and its kinds as Python exceptions, messages unchanged. Each kind is also
  // the built-in exception a Python user would catch: bad input a ValueError, a file that cannot
  // be read or written an OSError, a solver that did not converge a RuntimeError.
  static PyObject* const error = PyErr_NewExceptionWithDoc(
      "volspline.Error", "Any error volspline reports (the C++ volspline::Error).", PyExc_Exception, nullptr);
  auto kind = [&](const char* name, const char* doc, PyObject* builtin) {
    py::tuple bases = py::make_tuple(py::handle(error), py::handle(builtin));
    PyObject* type = PyErr_NewExceptionWithDoc(name, doc, bases.ptr(), nullptr);
    if (!type) throw py::error_already_set();
    return type;
  };
  static PyObject* const invalid_input =
      kind("volspline.InvalidInput", "Bad input: a model, an argument or data that volspline refuses.", PyExc_ValueError);
  static PyObject* const io_error = kind("volspline.IoError", "A file could not be read or written.", PyExc_OSError);
  static PyObject* const not_converged =
      kind("volspline.NotConverged", "An iteration did not reach its tolerance.", PyExc_RuntimeError);
  m.attr("Error") = py::handle(error);
  m.attr("InvalidInput") = py::handle(invalid_input);
  m.attr("IoError") = py::handle(io_error);
  m.attr("NotConverged") = py::handle(not_converged);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const volspline::InvalidInput& e) {
      PyErr_SetString(invalid_input, e.what());
    } catch (const volspline::IoError& e) {
      PyErr_SetString(io_error, e.what());
    } catch (const volspline::NotConverged& e) {
      PyErr_SetString(not_converged, e.what());
    } catch (const volspline::Error& e) {
      PyErr_SetString(error, e.what());
    }
  });

  // Classes first, so that the signatures in later docstrings name them.
  volspline::python::bind_tensor_splines(m);
  volspline::python::bind_swept_solids(m);
  volspline::python::bind_simplex_splines(m);
  volspline::python::bind_meshes(m);
  volspline::python::bind_constructions(m);
  volspline::python::bind_models(m);
  volspline::python::bind_analysis(m);
  volspline::python::bind_deformations(m);
  volspline::python::bind_pictures(m);
  volspline::python::bind_blends(m);
}
