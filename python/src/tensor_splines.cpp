// TensorSpline<D> as volspline.Curve, Surface, Volume and Hypervolume (docs/python.md).
//
// Array layout: control points are an array of shape (n_u, n_v, n_w, dim) indexed [i, j, k, c]
// (fewer or more leading axes for other D), or (n, dim) in the library's own order (u fastest,
// core/conventions.h). The library stores dim fastest, then u, then v, so the control_points
// property is a view of that storage with strides, not a copy. Evaluation results are moved into
// the arrays that return them.
#include <pybind11/stl.h>

#include <array>
#include <cstring>
#include <numeric>
#include <string>
#include <utility>

#include "bindings.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/derivative_spline.h"
#include "volspline/spline/knot_insertion.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline::python {
namespace {

py::array_t<double> as_doubles(const py::handle& object) {
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
}

// The library's order from an array indexed [i0, ..., i_{D-1}, (c)]: reversing the index axes
// makes C order equal to "first index fastest", which is the library's.
template <int D>
std::vector<double> library_order(const py::array& a, const std::array<int, D>& counts, int trailing, const char* what) {
  const int want_axes = D + (trailing > 0 ? 1 : 0);
  long total = 1;
  for (int c : counts) total *= c;
  if (a.ndim() == want_axes) {
    for (int d = 0; d < D; ++d)
      if (a.shape(d) != counts[static_cast<std::size_t>(d)])
        throw InvalidInput(std::string(what) + ": axis " + std::to_string(d) + " has " + std::to_string(a.shape(d)) +
                           " entries, the knot vectors give " + std::to_string(counts[static_cast<std::size_t>(d)]));
    py::list axes;
    for (int d = D - 1; d >= 0; --d) axes.append(d);
    if (trailing > 0) axes.append(D);
    py::module_ np = py::module_::import("numpy");
    py::array flat = as_doubles(np.attr("ascontiguousarray")(a.attr("transpose")(py::tuple(axes)), "float64"));
    std::vector<double> out(static_cast<std::size_t>(flat.size()));
    if (!out.empty()) std::memcpy(out.data(), flat.data(), out.size() * sizeof(double));
    return out;
  }
  const int flat_axes = trailing > 0 ? 2 : 1;
  if (a.ndim() == flat_axes && a.shape(0) == total) {
    py::array flat = as_doubles(a);
    std::vector<double> out(static_cast<std::size_t>(flat.size()));
    if (!out.empty()) std::memcpy(out.data(), flat.data(), out.size() * sizeof(double));
    return out;
  }
  std::string expected = "(";
  for (int d = 0; d < D; ++d) expected += std::to_string(counts[static_cast<std::size_t>(d)]) + ", ";
  expected += trailing > 0 ? "dim)" : ")";
  throw InvalidInput(std::string(what) + ": expected an array of shape " + expected + " or (" + std::to_string(total) +
                     (trailing > 0 ? ", dim)" : ",)") + ", got " + std::to_string(a.ndim()) + " axes");
}

template <int D>
std::vector<std::array<double, D>> parameters_from(const py::handle& object, bool& single) {
  py::array_t<double> a = as_doubles(object);
  single = a.ndim() == 1;
  if (!((a.ndim() == 2 && a.shape(1) == D) || (a.ndim() == 1 && a.shape(0) == D)))
    throw InvalidInput("params: expected an array of shape (N, " + std::to_string(D) + ") or (" + std::to_string(D) +
                       ",)");
  const long n = single ? 1 : a.shape(0);
  std::vector<std::array<double, D>> t(static_cast<std::size_t>(n));
  const double* p = a.data();
  for (long i = 0; i < n; ++i)
    for (int d = 0; d < D; ++d) t[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)] = p[i * D + d];
  return t;
}

template <int D, std::size_t... I>
std::array<KnotVector, D> knot_array(std::vector<KnotVector>& v, std::index_sequence<I...>) {
  return {std::move(v[I])...};
}

template <int D>
TensorSpline<D> make_spline(const std::vector<int>& degrees, const std::vector<py::object>& knots,
                            const py::object& control_points, const py::object& weights) {
  if (degrees.size() != static_cast<std::size_t>(D) || knots.size() != static_cast<std::size_t>(D))
    throw InvalidInput("degrees and knots: expected " + std::to_string(D) + " of each, got " +
                       std::to_string(degrees.size()) + " and " + std::to_string(knots.size()));
  std::vector<KnotVector> vectors;
  std::array<int, D> counts{};
  for (int d = 0; d < D; ++d) {
    py::array_t<double> k = as_doubles(knots[static_cast<std::size_t>(d)]);
    if (k.ndim() != 1) throw InvalidInput("knots[" + std::to_string(d) + "]: expected a 1-D array");
    try {
      vectors.emplace_back(degrees[static_cast<std::size_t>(d)], std::vector<double>(k.data(), k.data() + k.size()));
    } catch (const InvalidInput& e) {
      throw InvalidInput("knots[" + std::to_string(d) + "]: " + e.what());
    }
    counts[static_cast<std::size_t>(d)] = vectors.back().num_basis();
  }
  py::array cp = as_doubles(control_points);
  if (cp.ndim() < 2) throw InvalidInput("control_points: expected at least 2 axes (points, dim)");
  const int dimension = static_cast<int>(cp.shape(cp.ndim() - 1));
  std::vector<double> points = library_order<D>(cp, counts, dimension, "control_points");
  std::vector<double> w;
  if (!weights.is_none()) w = library_order<D>(as_doubles(weights), counts, 0, "weights");
  return TensorSpline<D>(knot_array<D>(vectors, std::make_index_sequence<D>{}), dimension, std::move(points), std::move(w));
}

template <int D>
py::array control_point_view(const py::object& self) {
  const auto& s = self.cast<const TensorSpline<D>&>();
  std::vector<py::ssize_t> shape, strides;
  py::ssize_t stride = s.dimension();
  for (int d = 0; d < D; ++d) {
    shape.push_back(s.num_control_points()[static_cast<std::size_t>(d)]);
    strides.push_back(stride * static_cast<py::ssize_t>(sizeof(double)));
    stride *= s.num_control_points()[static_cast<std::size_t>(d)];
  }
  shape.push_back(s.dimension());
  strides.push_back(sizeof(double));
  py::array view(py::dtype::of<double>(), shape, strides, s.points().data(), self);
  view.attr("flags").attr("writeable") = false;
  return view;
}

template <int D>
py::array weight_view(const py::object& self) {
  const auto& s = self.cast<const TensorSpline<D>&>();
  if (!s.is_rational()) return py::array_t<double>(0);
  std::vector<py::ssize_t> shape, strides;
  py::ssize_t stride = 1;
  for (int d = 0; d < D; ++d) {
    shape.push_back(s.num_control_points()[static_cast<std::size_t>(d)]);
    strides.push_back(stride * static_cast<py::ssize_t>(sizeof(double)));
    stride *= s.num_control_points()[static_cast<std::size_t>(d)];
  }
  py::array view(py::dtype::of<double>(), shape, strides, s.weights().data(), self);
  view.attr("flags").attr("writeable") = false;
  return view;
}

template <int D>
py::array evaluate(const TensorSpline<D>& s, const py::object& params, int order) {
  bool single = false;
  std::vector<std::array<double, D>> t = parameters_from<D>(params, single);
  std::vector<double> values;
  {
    py::gil_scoped_release release;
    values = s.evaluate_points(t, order);
  }
  const auto n = static_cast<py::ssize_t>(t.size());
  const auto dim = static_cast<py::ssize_t>(s.dimension());
  const auto m = static_cast<py::ssize_t>(derivative_multi_indices<D>(order).size());
  if (order == 0) {
    if (single) return array_over(std::move(values), {dim}, {1});
    return array_over(std::move(values), {n, dim}, {dim, 1});
  }
  if (single) return array_over(std::move(values), {m, dim}, {dim, 1});
  return array_over(std::move(values), {n, m, dim}, {m * dim, dim, 1});
}

template <int D>
py::array evaluate_grid(const TensorSpline<D>& s, const std::vector<py::object>& samples, int order) {
  if (samples.size() != static_cast<std::size_t>(D))
    throw InvalidInput("evaluate_grid: expected " + std::to_string(D) + " sample arrays, got " +
                       std::to_string(samples.size()));
  std::array<std::vector<double>, D> grid;
  for (int d = 0; d < D; ++d) {
    py::array_t<double> a = as_doubles(samples[static_cast<std::size_t>(d)]);
    if (a.ndim() != 1) throw InvalidInput("evaluate_grid: sample array " + std::to_string(d) + " must be 1-D");
    grid[static_cast<std::size_t>(d)].assign(a.data(), a.data() + a.size());
  }
  std::vector<double> values;
  {
    py::gil_scoped_release release;
    values = s.evaluate_grid(grid, order);
  }
  // Library layout: [alpha][point, first parameter fastest][c]; as numpy [alpha, i0, ..., c].
  const auto dim = static_cast<py::ssize_t>(s.dimension());
  std::vector<py::ssize_t> shape, strides;
  py::ssize_t stride = dim;
  for (int d = 0; d < D; ++d) {
    shape.push_back(static_cast<py::ssize_t>(grid[static_cast<std::size_t>(d)].size()));
    strides.push_back(stride);
    stride *= shape.back();
  }
  shape.push_back(dim);
  strides.push_back(1);
  if (order > 0) {
    shape.insert(shape.begin(), static_cast<py::ssize_t>(derivative_multi_indices<D>(order).size()));
    strides.insert(strides.begin(), stride);
  }
  return array_over(std::move(values), shape, strides);
}

template <int D>
void bind_tensor_spline(py::module_& m, const char* name, const char* what) {
  using S = TensorSpline<D>;
  const std::string axes = D == 1 ? "(n_u, dim)" : D == 2 ? "(n_u, n_v, dim)" : D == 3 ? "(n_u, n_v, n_w, dim)" : "(n_u, n_v, n_w, n_t, dim)";
  py::class_<S>(m, name, (std::string("A tensor-product B-spline ") + what +
                          ", polynomial or rational. Control points index [i0, ..., c]; see docs/python.md.")
                             .c_str())
      .def(py::init(&make_spline<D>), py::arg("degrees"), py::arg("knots"), py::arg("control_points"),
           py::arg("weights") = py::none(),
           (std::string("degrees: ") + std::to_string(D) + " ints; knots: " + std::to_string(D) +
            " 1-D arrays (clamped or not); control_points: an array of shape " + axes +
            ", or (n, dim) with the first index fastest; weights: None (polynomial) or one per control point. "
            "Raises InvalidInput naming the argument and what was expected.")
               .c_str())
      .def_property_readonly("dimension", &S::dimension, "Coordinates per point.")
      .def_property_readonly("is_rational", &S::is_rational)
      .def_property_readonly(
          "degrees", [](const S& s) { auto d = s.degrees(); return std::vector<int>(d.begin(), d.end()); })
      .def_property_readonly("num_control_points", [](const S& s) {
        auto c = s.num_control_points();
        return std::vector<int>(c.begin(), c.end());
      })
      .def_property_readonly(
          "knots",
          [](const S& s) {
            py::list out;
            for (int d = 0; d < D; ++d) {
              std::vector<double> k = s.knot_vector(d).knots();
              const auto n = static_cast<py::ssize_t>(k.size());
              out.append(array_over(std::move(k), {n}, {1}));
            }
            return out;
          },
          "The knot vectors (copies).")
      .def_property_readonly("control_points", &control_point_view<D>,
                             ("A read-only view of the control points, shape " + axes + ", without a copy.").c_str())
      .def_property_readonly("weights", &weight_view<D>, "A read-only view of the weights; empty if polynomial.")
      .def_property_readonly(
          "domain",
          [](const S& s) {
            std::vector<std::pair<double, double>> out;
            for (int d = 0; d < D; ++d) out.emplace_back(s.domain_min(d), s.domain_max(d));
            return out;
          },
          "(min, max) per parameter.")
      .def("evaluate", &evaluate<D>, py::arg("params"), py::arg("order") = 0,
           "Points at params, an (N, D) array (or one (D,) point): (N, dim). With order > 0 every partial "
           "derivative up to that order: (N, M, dim), in the order of multi_indices(order). Runs in parallel "
           "without the GIL. Raises InvalidInput for a parameter outside the domain.")
      .def("evaluate_grid", &evaluate_grid<D>, py::arg("samples"), py::arg("order") = 0,
           "Values on the tensor grid samples[0] x ... : shape (n0, ..., dim), or (M, n0, ..., dim) with "
           "derivatives, by sum factorisation.")
      .def_static("multi_indices", &derivative_multi_indices<D>, py::arg("order"),
                  "The partial derivatives evaluate(order=...) returns, in order (the point itself first).")
      .def("insert_knot", [](const S& s, int direction, double t, int times) { return insert_knot(s, direction, t, times); },
           py::arg("direction"), py::arg("t"), py::arg("times") = 1, "A new spline with the knot inserted; same geometry.")
      .def("refine_knots", [](const S& s, int direction, const std::vector<double>& k) { return refine_knots(s, direction, k); },
           py::arg("direction"), py::arg("knots"))
      .def("elevate_degree", [](const S& s, int direction, int times) { return elevate_degree(s, direction, times); },
           py::arg("direction"), py::arg("times") = 1, "A new spline of higher degree; same geometry.")
      .def("bezier_pieces", [](const S& s) { return bezier_pieces(s); },
           "The Bézier pieces (Bézier extraction), first index fastest.")
      .def("split", [](const S& s, int direction, double t) { return split(s, direction, t); }, py::arg("direction"),
           py::arg("t"))
      .def("derivative", [](const S& s, int direction) { return derivative_spline(s, direction); },
           py::arg("direction"), "The partial derivative as a spline (polynomial splines).")
      .def("__repr__", [name](const S& s) {
        std::string r = std::string("<volspline.") + name + " degrees (";
        for (int d = 0; d < D; ++d) r += (d ? ", " : "") + std::to_string(s.degrees()[static_cast<std::size_t>(d)]);
        r += "), control points (";
        for (int d = 0; d < D; ++d) r += (d ? ", " : "") + std::to_string(s.num_control_points()[static_cast<std::size_t>(d)]);
        return r + "), dim " + std::to_string(s.dimension()) + (s.is_rational() ? ", rational>" : ">");
      });
}

}  // namespace

void bind_tensor_splines(py::module_& m) {
  bind_tensor_spline<1>(m, "Curve", "curve");
  bind_tensor_spline<2>(m, "Surface", "surface");
  bind_tensor_spline<3>(m, "Volume", "volume");
  bind_tensor_spline<4>(m, "Hypervolume", "hypervolume (4 parameters: swept solids)");
}

}  // namespace volspline::python
