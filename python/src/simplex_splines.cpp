// Trivariate DMS simplex spline volumes (Hua–He–Qin) from Python: volspline.SimplexSplineVolume,
// volspline.simplex_spline (as `volspline make simplex-spline`), volspline.fit (as
// `volspline fit`), volspline.xray (§6.1) and attribute isosurfaces and slices (§6.2);
// docs/simplex-splines.md, docs/fitting.md, docs/python.md.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "bindings.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/extract/simplex_boundary.h"
#include "volspline/extract/simplex_isosurface.h"
#include "volspline/extract/simplex_slices.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/io/volume_data.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/surface_tetrahedralization.h"
#include "volspline/mesh/tetrahedral_mesh_reader.h"
#include "volspline/render/xray_image.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/attribute_assignment.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/simplex/knot_clouds.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline::python {

std::vector<Eigen::Vector3d> points_from(const py::handle& object, const char* what) {
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Doubles a = Doubles::ensure(object);
  if (!a || !((a.ndim() == 2 && a.shape(1) == 3) || (a.ndim() == 1 && a.shape(0) == 3)))
    throw InvalidInput(std::string(what) + ": expected an array of shape (N, 3) or (3,)");
  const py::ssize_t n = a.ndim() == 1 ? 1 : a.shape(0);
  std::vector<Eigen::Vector3d> out(static_cast<std::size_t>(n));
  std::memcpy(out.data()->data(), a.data(), static_cast<std::size_t>(n) * 3 * sizeof(double));
  return out;
}

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The domain: tetrahedra given as arrays or a mesh file, the Delaunay tetrahedralisation of
// points, or CGAL Mesh_3 of a closed surface (a mesh file or a mesh dict).
TetrahedralMesh domain_from(const py::object& points, const py::object& tetrahedra, const py::object& surface, double cell_size) {
  const int given = !tetrahedra.is_none() + (!points.is_none() && tetrahedra.is_none()) + !surface.is_none();
  if (given != 1)
    throw InvalidInput("give exactly one domain: points and tetrahedra (arrays), tetrahedra (a mesh file), points alone "
                       "(Delaunay) or surface (a closed triangle mesh)");
  if (!tetrahedra.is_none()) {
    if (py::isinstance<py::str>(tetrahedra) || py::hasattr(tetrahedra, "__fspath__"))
      return read_tetrahedral_mesh(tetrahedra.cast<std::filesystem::path>());
    if (points.is_none()) throw InvalidInput("tetrahedra: an array needs the points it indexes");
    TetrahedralMesh mesh;
    mesh.points = points_from(points, "points");
    const auto t = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(tetrahedra);
    if (!t || t.ndim() != 2 || t.shape(1) != 4) throw InvalidInput("tetrahedra: expected an array of shape (M, 4)");
    for (py::ssize_t i = 0; i < t.shape(0); ++i) {
      std::array<int, 4> corners{};
      for (int c = 0; c < 4; ++c) {
        const long long index = t.at(i, c);
        if (index < 0 || index >= static_cast<long long>(mesh.points.size()))
          throw InvalidInput("tetrahedra[" + std::to_string(i) + "]: point index " + std::to_string(index) + " is not in 0.." +
                             std::to_string(mesh.points.size() - 1));
        corners[static_cast<std::size_t>(c)] = static_cast<int>(index);
      }
      mesh.tetrahedra.push_back(corners);
    }
    return mesh;
  }
  if (!points.is_none()) {
    const std::vector<Eigen::Vector3d> p = points_from(points, "points");
    py::gil_scoped_release release;
    return delaunay_tetrahedralization(p);
  }
  SurfaceTetrahedralizationOptions options;
  options.cell_size = cell_size;
  const TriangleMesh closed = py::isinstance<py::dict>(surface) ? mesh_from(surface) : read_mesh(surface.cast<std::filesystem::path>());
  py::gil_scoped_release release;
  return tetrahedralize_closed_surface(closed, options);
}

VolumeData volume_data_from(const py::object& data) {
  if (py::isinstance<py::dict>(data)) {
    const py::dict d = py::reinterpret_borrow<py::dict>(data);
    if (!d.contains("points") || !d.contains("attributes"))
      throw InvalidInput("data: expected a dict with 'points' (N, 3) and 'attributes' {name: (N,)}");
    VolumeData out;
    out.points = points_from(d["points"], "data['points']");
    const py::dict attributes = d["attributes"].cast<py::dict>();
    out.attributes.resize(static_cast<Eigen::Index>(out.points.size()), static_cast<Eigen::Index>(attributes.size()));
    Eigen::Index column = 0;
    for (const auto& [name, values] : attributes) {
      const std::string key = py::str(name);
      const Doubles v = Doubles::ensure(values);
      if (!v || v.ndim() != 1 || v.shape(0) != static_cast<py::ssize_t>(out.points.size()))
        throw InvalidInput("data['attributes']['" + key + "']: expected an array of shape (" + std::to_string(out.points.size()) + ",)");
      out.attribute_names.push_back(key);
      for (py::ssize_t i = 0; i < v.shape(0); ++i) out.attributes(i, column) = v.at(i);
      ++column;
    }
    validate_volume_data(out, "data");
    return out;
  }
  const std::string name = py::str(data);
  try {
    if (std::optional<VolumeData> generated = generated_volume_data(name)) return std::move(*generated);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("data: ") + e.what());
  }
  return read_volume_data(data.cast<std::filesystem::path>());
}

py::dict values_dict(const DmsSplineVolume& volume, const std::vector<double>& values, py::ssize_t n, bool gradients,
                     const std::vector<double>& gradient_values, const std::vector<int>& inside) {
  const int d = volume.dimension();
  py::dict out;
  auto column = [&](int c) {
    py::array_t<double> a(n);
    for (py::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = values[static_cast<std::size_t>(i * d + c)];
    return a;
  };
  py::array_t<double> geometry({n, py::ssize_t{3}});
  for (py::ssize_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) geometry.mutable_at(i, c) = values[static_cast<std::size_t>(i * d + c)];
  out["geometry"] = geometry;
  py::dict attributes;
  for (int a = 0; a < d - 3; ++a) attributes[py::str(volume.attribute_names()[static_cast<std::size_t>(a)])] = column(3 + a);
  out["attributes"] = attributes;
  py::array_t<bool> in(n);
  for (py::ssize_t i = 0; i < n; ++i) in.mutable_at(i) = inside[static_cast<std::size_t>(i)] != 0;
  out["inside"] = in;
  if (gradients) {
    std::vector<double> copy = gradient_values;
    out["gradients"] = array_over(std::move(copy), {n, d, 3}, {3 * d, 3, 1});
  }
  return out;
}

py::dict evaluate_volume(const DmsSplineVolume& volume, const py::handle& points, bool gradients) {
  const std::vector<Eigen::Vector3d> x = points_from(points, "points");
  const int d = volume.dimension();
  const auto n = static_cast<py::ssize_t>(x.size());
  std::vector<double> values(x.size() * static_cast<std::size_t>(d));
  std::vector<double> gradient_values(gradients ? x.size() * static_cast<std::size_t>(d) * 3 : 0);
  std::vector<int> inside(x.size());
  {
    py::gil_scoped_release release;
    const DmsSplineEvaluator prototype(volume);
    tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, x.size(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
      DmsSplineEvaluator& evaluator = evaluators.local();
      DmsSplinePoint p;
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        evaluator.evaluate(x[i], gradients ? 1 : 0, p);
        inside[i] = p.inside;
        for (int c = 0; c < d; ++c) values[i * static_cast<std::size_t>(d) + static_cast<std::size_t>(c)] = p.inside ? p.value[c] : 0.0;
        if (gradients)
          for (int c = 0; c < d; ++c)
            for (int k = 0; k < 3; ++k)
              gradient_values[(i * static_cast<std::size_t>(d) + static_cast<std::size_t>(c)) * 3 + static_cast<std::size_t>(k)] =
                  p.inside ? p.gradient(c, k) : 0.0;
      }
    });
  }
  return values_dict(volume, values, n, gradients, gradient_values, inside);
}

py::dict fit_statistics(const VolumeFitStatistics& s) {
  py::dict out;
  out["data_points"] = s.data_points;
  out["domain_tetrahedra"] = s.domain_tetrahedra;
  out["control_points"] = s.control_points;
  out["knots"] = s.knots;
  out["primary_knots"] = s.primary_knots;
  out["fitted_points"] = s.errors.fitted_points;
  out["outside_points"] = s.errors.outside_points;
  out["geometric_mean_square"] = s.errors.geometric_mean_square;
  out["normalised_geometric_mean_square"] = s.errors.normalised_geometric_mean_square;
  py::dict attributes;
  for (const AttributeFitError& a : s.errors.attributes) {
    py::dict e;
    e["data_min"] = a.data_min;
    e["data_max"] = a.data_max;
    e["mean_square"] = a.mean_square;
    e["max_abs"] = a.max_abs;
    e["normalised_mean_square"] = a.normalised_mean_square;
    e["normalised_max_abs"] = a.normalised_max_abs;
    attributes[py::str(a.name)] = e;
  }
  out["attributes"] = attributes;
  out["field_normalised_mean_square"] = mean_normalised_field_error(s.errors);
  out["primary_knots_layout"] = s.layout;
  out["fairing"] = s.fairing;
  py::dict placement;
  placement["rounds"] = s.knot_placement.rounds;
  placement["round_kept"] = s.knot_placement.kept;
  placement["normalised_mean_square_before"] = s.knot_placement.before;
  placement["normalised_mean_square_after"] = s.knot_placement.after;
  placement["held_out_normalised_mean_square_before"] = s.knot_placement.held_out_before;
  placement["held_out_normalised_mean_square_after"] = s.knot_placement.held_out_after;
  placement["fairing"] = s.knot_placement.fairing;
  out["knot_placement"] = placement;
  py::dict optimisation;
  optimisation["sweeps"] = s.knot_optimisation.sweeps;
  optimisation["vertices_above_threshold"] = s.knot_optimisation.vertices_tried;
  optimisation["vertices_moved"] = s.knot_optimisation.vertices_moved;
  optimisation["primary_knots_moved"] = s.knot_optimisation.primary_knots_moved;
  optimisation["sweeps_kept"] = s.knot_optimisation.kept_sweeps;
  optimisation["sweeps_undone"] = s.knot_optimisation.undone_sweeps;
  optimisation["normalised_mean_square_before"] = s.knot_optimisation.before;
  optimisation["normalised_mean_square_after"] = s.knot_optimisation.after;
  optimisation["judged_on_held_out"] = s.knot_optimisation.judged_on_held_out;
  optimisation["held_out_normalised_mean_square_before"] = s.knot_optimisation.held_out_before;
  optimisation["held_out_normalised_mean_square_after"] = s.knot_optimisation.held_out_after;
  out["knot_optimisation"] = optimisation;
  return out;
}

}  // namespace

void bind_simplex_splines(py::module_& m) {
  py::class_<DmsSplineVolume>(m, "SimplexSplineVolume",
                              "A trivariate DMS simplex spline volume (Hua-He-Qin eq. 5-7) over a tetrahedral domain: geometry "
                              "s(x) in R^3 and named material attributes in one spline. Outside the domain it is zero. Made by "
                              "volspline.simplex_spline or volspline.fit, or read from a model file.")
      .def_property_readonly("degree", &DmsSplineVolume::degree)
      .def_property_readonly("attribute_names", &DmsSplineVolume::attribute_names)
      .def_property_readonly("dimension", &DmsSplineVolume::dimension, "3 + the number of attributes.")
      .def_property_readonly("shared", [](const DmsSplineVolume& v) { return v.sharing() == DmsControlSharing::Shared; },
                             "One control vector per domain point (True) or per tetrahedron (False).")
      .def_property_readonly(
          "domain_points",
          [](const DmsSplineVolume& v) {
            const auto& p = v.domain().points;
            py::array_t<double> a({static_cast<py::ssize_t>(p.size()), py::ssize_t{3}});
            for (std::size_t i = 0; i < p.size(); ++i)
              for (int c = 0; c < 3; ++c) a.mutable_at(static_cast<py::ssize_t>(i), c) = p[i][c];
            return a;
          },
          "The domain's vertices (the primary knots), (P, 3).")
      .def_property_readonly(
          "tetrahedra",
          [](const DmsSplineVolume& v) {
            const auto& t = v.domain().tetrahedra;
            py::array_t<std::int32_t> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{4}});
            for (std::size_t i = 0; i < t.size(); ++i)
              for (int c = 0; c < 4; ++c) a.mutable_at(static_cast<py::ssize_t>(i), c) = t[i][static_cast<std::size_t>(c)];
            return a;
          },
          "The domain's tetrahedra as point indices, (M, 4).")
      .def_property_readonly(
          "control_vectors",
          [](const DmsSplineVolume& v) {
            const Eigen::MatrixXd& c = v.control_vectors();
            // Eigen stores columns contiguously: rows are control vectors (x, y, z, g_1..g_k).
            return py::array_t<double>({static_cast<py::ssize_t>(c.rows()), static_cast<py::ssize_t>(c.cols())},
                                       {static_cast<py::ssize_t>(sizeof(double)), static_cast<py::ssize_t>(sizeof(double) * c.rows())},
                                       c.data());
          },
          "A copy of the control vectors, one row (x, y, z, g_1, ..., g_k) per control point.")
      .def(
          "set_control_vectors",
          [](DmsSplineVolume& v, const py::handle& values) {
            const Doubles a = Doubles::ensure(values);
            const Eigen::MatrixXd& c = v.control_vectors();
            if (!a || a.ndim() != 2 || a.shape(0) != c.rows() || a.shape(1) != c.cols())
              throw InvalidInput("control_vectors: expected an array of shape (" + std::to_string(c.rows()) + ", " +
                                 std::to_string(c.cols()) + ")");
            Eigen::MatrixXd copy(c.rows(), c.cols());
            for (Eigen::Index i = 0; i < c.rows(); ++i)
              for (Eigen::Index j = 0; j < c.cols(); ++j) {
                const double x = a.at(i, j);
                if (!std::isfinite(x)) throw InvalidInput("control_vectors[" + std::to_string(i) + ", " + std::to_string(j) + "]: expected a finite number");
                copy(i, j) = x;
              }
            v.control_vectors() = std::move(copy);
          },
          py::arg("values"), "Replaces the control vectors (same shape as control_vectors): moves control points, edits attributes.")
      .def(
          "evaluate", [](const DmsSplineVolume& v, const py::handle& points, bool gradients) { return evaluate_volume(v, points, gradients); },
          py::arg("points"), py::arg("gradients") = false,
          "The spline at domain points (N, 3), in parallel with the GIL released: a dict of geometry (N, 3), attributes "
          "{name: (N,)}, inside (N,) bool (outside the domain the spline is zero) and, with gradients=True, gradients "
          "(N, dimension, 3): d(x, y, z, g_1..)/d(domain point) (volspline eval).")
      .def(
          "assign_attribute",
          [](DmsSplineVolume& v, const std::string& name, const py::object& field, const std::string& method) {
            if (method != "least-squares" && method != "control-points")
              throw InvalidInput("method: expected least-squares or control-points, got '" + method + "'");
            const AttributeAssignment how = method == "least-squares" ? AttributeAssignment::LeastSquares : AttributeAssignment::ControlPoints;
            AttributeAssignmentReport report;
            if (py::isinstance<py::str>(field) || py::hasattr(field, "__fspath__")) {
              const SkeletonField skeleton = read_skeleton(field.cast<std::filesystem::path>());
              py::gil_scoped_release release;
              report = assign_attribute(v, name, [&](const Eigen::Vector3d& x) { return skeleton(x); }, how);
            } else {
              if (!PyCallable_Check(field.ptr())) throw InvalidInput("field: expected a skeleton file's path or a callable f(x, y, z)");
              report = assign_attribute(v, name, [&](const Eigen::Vector3d& x) { return field(x[0], x[1], x[2]).cast<double>(); }, how);
            }
            py::dict out;
            out["samples"] = report.samples;
            out["max_error"] = report.max_error;
            out["rms_error"] = report.rms_error;
            return out;
          },
          py::arg("name"), py::arg("field"), py::arg("method") = "least-squares",
          "Sets attribute `name` (added if absent) to approximate a field: a skeleton file's path (docs/skeleton-files.md, "
          "Hua-He-Qin eq. 8-9) or a callable f(x, y, z) -> float; by least squares or the paper's control-point rule. "
          "Returns samples, max_error and rms_error.")
      .def("__repr__", [](const DmsSplineVolume& v) {
        return "<volspline.SimplexSplineVolume degree " + std::to_string(v.degree()) + ", " + std::to_string(v.domain().tetrahedra.size()) +
               " tetrahedra, " + std::to_string(v.control_vector_count()) + " control vectors>";
      });

  m.def(
      "simplex_spline",
      [](int degree, const py::object& points, const py::object& tetrahedra, const py::object& surface, double cell_size,
         const std::string& control, double spread) {
        if (control != "shared" && control != "per_tetrahedron")
          throw InvalidInput("control: expected shared or per_tetrahedron, got '" + control + "'");
        TetrahedralMesh domain = domain_from(points, tetrahedra, surface, cell_size);
        py::gil_scoped_release release;
        KnotCloudOptions options;
        options.spread = spread;
        KnotClouds clouds = generate_knot_clouds(domain, degree, options);
        return DmsSplineVolume(std::move(domain), std::move(clouds),
                               control == "shared" ? DmsControlSharing::Shared : DmsControlSharing::PerTetrahedron);
      },
      py::arg("degree") = 2, py::kw_only(), py::arg("points") = py::none(), py::arg("tetrahedra") = py::none(),
      py::arg("surface") = py::none(), py::arg("cell_size") = 0.0, py::arg("control") = "shared",
      py::arg("spread") = KnotCloudOptions{}.spread,
      R"(A trivariate DMS simplex spline volume of the given degree (0..5) with generated knot clouds and the
identity as geometry, as `volspline make simplex-spline`. The domain is exactly one of: points (N, 3)
and tetrahedra (M, 4) arrays; tetrahedra = a tetrahedral mesh file (.mesh, .node/.ele, .vtu, .vtk);
points alone (their Delaunay tetrahedralisation); surface = a closed triangle mesh (a file or a
mesh dict) meshed by CGAL Mesh_3 with cells of at most cell_size (0: diagonal / 20).)");

  m.def(
      "fit",
      [](const py::object& data, int degree, const std::vector<std::string>& attributes, int primary_knots, const std::string& knots,
         double error, long long max_tetrahedra, std::optional<double> fairing, int knot_sweeps, bool fixed_primary_knots, bool judge_local_step_at_data,
         const py::object& progress) {
        VolumeData samples = select_attributes(volume_data_from(data), attributes);
        if (samples.attribute_names.empty()) throw InvalidInput("data: no attributes to fit (only x, y, z)");
        if (knots != "fixed" && knots != "place" && knots != "optimise")
          throw InvalidInput("knots: expected fixed, place or optimise, got '" + knots + "'");
        if (primary_knots < 0 || !(error >= 0) || max_tetrahedra < 0 || (fairing && (!(*fairing >= 0) || !std::isfinite(*fairing))))
          throw InvalidInput("primary_knots, error, max_tetrahedra and fairing: expected finite numbers >= 0");
        if (knot_sweeps < 1 || knot_sweeps > 50) throw InvalidInput("knot_sweeps: expected 1 to 50, got " + std::to_string(knot_sweeps));
        VolumeFitOptions options;
        options.degree = degree;
        options.domain.primary_knots = primary_knots;
        options.knots.enabled = knots != "fixed";
        options.knots.local = knots == "optimise";
        options.knots.sweeps = knot_sweeps;
        options.knots.move_primary_knots = !fixed_primary_knots;
        options.knots.held_out = !judge_local_step_at_data;
        options.refinement.error = error;
        options.refinement.max_tetrahedra = static_cast<std::size_t>(max_tetrahedra);
        // Given (0 too), the weight is used as it is; None: the default (0.1, unfaired with a jump).
        if (fairing) options.fit.fairing = options.default_fairing = *fairing;
        PythonProgress listener(progress);
        Progress* reports = listener.get();
        VolumeFit result = [&] {
          py::gil_scoped_release release;
          VolumeFit fitted = fit_volume_data(samples, options, [&](const std::string& phase) {
            if (reports) reports->begin_phase(phase);
          });
          if (reports) reports->end_phase();
          return fitted;
        }();
        listener.rethrow();
        py::dict stats = fit_statistics(result.statistics);
        return py::make_tuple(std::move(result.volume), stats);
      },
      py::arg("data"), py::arg("degree") = 2, py::kw_only(), py::arg("attributes") = std::vector<std::string>{},
      py::arg("primary_knots") = 0, py::arg("knots") = "fixed", py::arg("error") = 0.0, py::arg("max_tetrahedra") = 0,
      py::arg("fairing") = py::none(), py::arg("knot_sweeps") = KnotOptimisationOptions{}.sweeps,
      py::arg("fixed_primary_knots") = false, py::arg("judge_local_step_at_data") = false, py::arg("progress") = py::none(),
      R"(Fits scattered volume data with a DMS simplex spline (Hua-He-Qin §5), as `volspline fit`. data: a
file (.csv with a header, .ply, .vtu, .vti, .vtk, .nii, .inr), 'marschner-lobb:N' or 'two-material:N',
or a dict {'points': (N, 3), 'attributes': {name: (N,)}}. attributes: the columns to fit (default
all). knots: 'fixed', 'place' (primary knots placed by error equidistribution, judged on held-out
data) or 'optimise' (place, then §5.3's local step on the knot clouds: knot_sweeps passes; primary
knots move with their sub-knots where the domain stays the same unless fixed_primary_knots; a sweep is
kept if it lowers the error at the held-out eighth of the points, or at the data with
judge_local_step_at_data); error > 0 refines adaptively (§5.4) within max_tetrahedra; fairing: the weight of the term that damps oscillations between data points
(default None: 0.1, unfaired with a jump; 0: none; docs/fitting.md). Returns (SimplexSplineVolume, stats): the paper's Table 1 figures and the errors
per attribute, raw and normalised to the data range.)");

  m.def(
      "xray",
      [](const DmsSplineVolume& volume, const std::string& attribute, std::array<int, 2> size, const Eigen::Vector3d& view,
         const Eigen::Vector3d& up, double fov, double absorption) {
        XrayOptions options;
        options.attribute = attribute;
        options.width = size[0];
        options.height = size[1];
        options.view_direction = view;
        options.up = up;
        options.field_of_view_deg = fov;
        options.absorption = absorption;
        Image image;
        XrayPicture picture;
        {
          py::gil_scoped_release release;
          XrayRenderer renderer(volume, options);
          renderer.render();
          image = renderer.image();
          picture = renderer.picture();
        }
        std::vector<double> integrals = std::move(picture.line_integrals);
        py::dict out;
        out["image"] = image_array(image);
        out["line_integrals"] = array_over(std::move(integrals), {picture.height, picture.width}, {picture.width, 1});
        out["absorption"] = picture.absorption;
        out["seconds"] = picture.seconds;
        return out;
      },
      py::arg("volume"), py::arg("attribute") = "", py::arg("size") = std::array<int, 2>{512, 512},
      py::arg("view") = Eigen::Vector3d(-1.0, -1.3, -0.8), py::arg("up") = Eigen::Vector3d(0.0, 0.0, 1.0), py::arg("fov") = 0.0,
      py::arg("absorption") = std::numeric_limits<double>::quiet_NaN(),
      R"(The X-ray picture I = exp(-k ∫ f) of an attribute (default the first; the chord length without
attributes), every basis function's line integral computed analytically (Hua-He-Qin §6.1), as
`volspline xray`. size (width, height); view: the direction looked in; fov 0: parallel projection;
absorption k (NaN: the largest integral absorbs 86 %). Returns image (height, width, 4) uint8,
line_integrals (height, width), absorption and seconds.)");

  m.def(
      "simplex_isosurface",
      [](const DmsSplineVolume& volume, const std::string& attribute, double value, double edge, int subdivisions) {
        SimplexIsosurfaceOptions options;
        options.attribute = attribute;
        options.value = value;
        options.target_edge = edge;
        options.subdivisions = subdivisions;
        SimplexIsosurface surface;
        {
          py::gil_scoped_release release;
          surface = simplex_isosurface(volume, options);
        }
        return mesh_dict(surface.mesh);
      },
      py::arg("volume"), py::arg("attribute"), py::arg("value"), py::arg("edge") = 0.0, py::arg("subdivisions") = 0,
      "The isosurface attribute = value of a simplex spline volume (Hua-He-Qin §6.2): marching tetrahedra over a local "
      "longest-edge bisection of the domain to `edge` (0: diagonal / 40) or `subdivisions`^3 per tetrahedron, vertices "
      "found on the spline; positions s(x), parameters the domain points x (view --iso-attribute).");

  m.def(
      "simplex_slice",
      [](const DmsSplineVolume& volume, const Eigen::Vector3d& normal, double offset, const std::string& attribute, double edge,
         int subdivisions) {
        SimplexSliceOptions options;
        options.attribute = attribute;
        options.target_edge = edge;
        options.subdivisions = subdivisions;
        SimplexSlice slice;
        {
          py::gil_scoped_release release;
          slice = simplex_plane_slice(volume, Plane{normal, offset}, options);
        }
        py::dict out = mesh_dict(slice.mesh);
        out["values"] = py::array_t<double>(static_cast<py::ssize_t>(slice.values.size()), slice.values.data());
        return out;
      },
      py::arg("volume"), py::arg("normal"), py::arg("offset"), py::arg("attribute") = "", py::arg("edge") = 0.0,
      py::arg("subdivisions") = 0,
      "The slice of a simplex spline volume's domain by the plane normal . x = offset, mapped by the spline, with the "
      "attribute at every vertex in values (view --plane).");

  m.def(
      "simplex_boundary",
      [](const DmsSplineVolume& volume) {
        TriangleMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = simplex_boundary_mesh(volume);
        }
        return mesh_dict(mesh);
      },
      py::arg("volume"), "The image s(∂Ω) of the domain's boundary (part 17), as `volspline boundary` of a simplex spline volume.");
}

}  // namespace volspline::python
