// Swept trivariate solids and their envelopes (Conkey–Joy 2000) from Python: volspline.SweptSolid,
// volspline.swept_solid (as `volspline make swept-solid`) and volspline.sweep_envelope (as
// `volspline sweep-envelope`); construct/swept_solid.h, extract/swept_envelope.h,
// docs/sweeps.md, docs/envelopes.md.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "bindings.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/core/error.h"
#include "volspline/extract/swept_envelope.h"

namespace volspline::python {
namespace {

// "fixed", "frenet", "rmf", ("rotate", axis, degrees) or [b, n, t] curves.
SweptSolidFrame frame_from(const py::handle& frame, double tolerance) {
  SweptSolidFrame out;
  if (py::isinstance<py::str>(frame)) {
    const std::string name = frame.cast<std::string>();
    if (name == "fixed")
      out = SweptSolidFrame::of_kind(SweptSolidFrame::Kind::Fixed);
    else if (name == "frenet")
      out = SweptSolidFrame::of_kind(SweptSolidFrame::Kind::Frenet);
    else if (name == "rmf")
      out = SweptSolidFrame::of_kind(SweptSolidFrame::Kind::RotationMinimizing);
    else
      throw InvalidInput("frame: expected 'fixed', 'frenet', 'rmf', ('rotate', axis, degrees) or three curves [b, n, t], got '" +
                         name + "'");
  } else {
    const py::sequence items = py::reinterpret_borrow<py::sequence>(frame);
    if (py::len(items) == 3 && py::isinstance<py::str>(items[0]) && items[0].cast<std::string>() == "rotate")
      out = SweptSolidFrame::rotation(items[1].cast<Eigen::Vector3d>(), items[2].cast<double>());
    else if (py::len(items) == 3 && py::isinstance<BSplineCurve>(items[0]))
      out = SweptSolidFrame::of_curves(items.cast<std::vector<BSplineCurve>>());
    else
      throw InvalidInput("frame: expected 'fixed', 'frenet', 'rmf', ('rotate', axis, degrees) or three curves [b, n, t]");
  }
  out.tolerance = tolerance;
  return out;
}

std::vector<BSplineHypervolume> patches_from(const py::handle& solid) {
  if (py::isinstance<SweptSolid>(solid)) return swept_patches(solid.cast<const SweptSolid&>());
  if (py::isinstance<BSplineHypervolume>(solid)) return {solid.cast<BSplineHypervolume>()};
  if (py::isinstance<py::list>(solid) || py::isinstance<py::tuple>(solid)) return solid.cast<std::vector<BSplineHypervolume>>();
  throw InvalidInput("solid: expected a SweptSolid, a Hypervolume or a list of Hypervolumes");
}

EnvelopeTrimming trimming_named(const std::string& name) {
  if (name == "auto") return EnvelopeTrimming::Automatic;
  if (name == "arrangement") return EnvelopeTrimming::Arrangement;
  if (name == "contouring") return EnvelopeTrimming::Contouring;
  throw InvalidInput("trimming: expected auto, arrangement or contouring, got '" + name + "'");
}

}  // namespace

void bind_swept_solids(py::module_& m) {
  py::class_<SweptSolid>(m, "SweptSolid",
                         "A generator solid moved along a path while a frame turns it: s(u, v, w, t) = c(t) + R(t) g(u, v, w) "
                         "(Conkey-Joy 2000, eq. 1). Made by volspline.swept_solid or read from a model file.")
      .def_readonly("generator", &SweptSolid::generator, "The generator's volume patches g, in the moving frame's coordinates.")
      .def_readonly("path", &SweptSolid::path, "The path c(t), t in [0, 1].")
      .def_property_readonly(
          "frame", [](const SweptSolid& s) { return std::vector<BSplineCurve>(s.frame.begin(), s.frame.end()); },
          "The frame curves [b, n, t], the columns of R(t), t in [0, 1].")
      .def_readonly("frame_name", &SweptSolid::frame_name, "'fixed', 'frenet', 'rmf', 'rotate' or 'curves'.")
      .def_readonly("frame_fit_error", &SweptSolid::frame_fit_error,
                    "max |R^T R - I| of a fitted frame (frenet, rmf); 0 for exact frames.")
      .def("patches", &swept_patches, "The exact 4-variate spline (Hypervolume, parameters u, v, w, t) of every generator patch.")
      .def("frame_at", &swept_frame_at, py::arg("t"), "R(t) as a 3 x 3 matrix (columns b, n, t).")
      .def("__repr__", [](const SweptSolid& s) {
        return "<volspline.SweptSolid " + std::to_string(s.generator.size()) + " patch(es), frame " + s.frame_name + ">";
      });

  m.def(
      "swept_solid",
      [](const py::object& generator, const BSplineCurve& path, const py::object& frame, double tolerance) {
        std::vector<BSplineVolume> patches;
        if (py::isinstance<BSplineVolume>(generator))
          patches.push_back(generator.cast<BSplineVolume>());
        else
          patches = generator.cast<std::vector<BSplineVolume>>();
        const SweptSolidFrame f = frame_from(frame, tolerance);
        py::gil_scoped_release release;
        return make_swept_solid(std::move(patches), path, f);
      },
      py::arg("generator"), py::arg("path"), py::arg("frame") = "fixed", py::arg("tolerance") = kSweepFrameTolerance,
      R"(The swept solid of a generator (a Volume or a list of Volumes) along a path (a 3-D Curve), as
`volspline make swept-solid`. frame: 'fixed' (R = I), 'frenet' or 'rmf' (fitted to `tolerance`,
the error in frame_fit_error), ('rotate', (ax, ay, az), degrees) (exact rational: the generator
turns about the axis through its local origin by degrees * t), or three Curves [b, n, t]. Raises
InvalidInput for a frame whose determinant vanishes on [0, 1].)");

  m.def(
      "sweep_envelope",
      [](const py::object& solid, double tolerance, const std::string& bounds, bool superset, std::int64_t max_cells,
         const std::string& trimming, double coarse_cells, std::optional<int> adaptive_cells, double refine, const py::object& progress) {
        std::vector<BSplineHypervolume> patches = patches_from(solid);
        SweptEnvelopeOptions options;
        options.tolerance = tolerance;
        if (bounds == "cone")
          options.bounds = JacobianBoundMethod::Cone;
        else if (bounds != "bezier")
          throw InvalidInput("bounds: expected bezier or cone, got '" + bounds + "'");
        options.trim = !superset;
        options.max_cells = max_cells;
        options.trimming_method = trimming_named(trimming);
        if (!(coarse_cells >= 0 && coarse_cells * tolerance < 0.5))
          throw InvalidInput("coarse_cells: expected 0 (off) or a positive multiple of the tolerance below 0.5 / tolerance");
        if (!(refine > 0 && refine <= 1)) throw InvalidInput("refine: expected a multiple of the tolerance in (0, 1]");
        if (adaptive_cells && *adaptive_cells != 0 && (*adaptive_cells < 2 || *adaptive_cells > 64 || *adaptive_cells % 2 != 0))
          throw InvalidInput("adaptive_cells: expected None (chosen from the tolerance), 0 (the uniform fine grid) or an even number from 2 to 64");
        if (adaptive_cells && coarse_cells > 0) throw InvalidInput("give coarse_cells or adaptive_cells, not both");
        if (adaptive_cells && *adaptive_cells * 3 * tolerance >= 0.25)
          throw InvalidInput("adaptive_cells: expected adaptive_cells x 3 x tolerance below 0.25");
        options.coarse_cell_factor = coarse_cells;
        options.adaptive_ratio = coarse_cells > 0 ? 0 : adaptive_cells ? *adaptive_cells : SweptEnvelopeOptions::kAutomaticRatio;
        options.refinement_factor = refine;
        PythonProgress listener(progress);
        options.progress = listener.get();
        SweptEnvelope e;
        {
          py::gil_scoped_release release;
          e = swept_envelope(patches, options);
        }
        listener.rethrow();
        const SweptEnvelopeStats& s = e.stats;
        py::dict stats;
        stats["cap_face_triangles"] = s.cap_face_triangles;
        stats["edge_sweep_triangles"] = s.edge_sweep_triangles;
        stats["cap_fold_triangles"] = s.cap_fold_triangles;
        stats["face_sweep_fold_triangles"] = s.face_sweep_fold_triangles;
        stats["rank_deficient_triangles"] = s.rank_deficient_triangles;
        stats["cells_examined"] = s.cells_examined;
        stats["rank_cells_examined"] = s.rank_cells_examined;
        stats["rank_cells_kept"] = s.rank_cells_kept;
        stats["rank_part_cells_examined"] = s.rank_part_cells_examined;
        stats["rank_minors_divided_by_faces"] = s.rank_minors_divided_by_faces;
        stats["rank_lattice_face_triangles"] = s.rank_lattice_face_triangles;
        stats["budget_reached"] = s.budget_reached;
        stats["seconds"] = s.seconds_total;
        if (!superset) {
          const SupersetTrimmingStats& t = s.trimming;
          stats["trimmed_by"] = s.trimmed_by == EnvelopeTrimming::Arrangement ? "arrangement" : "contouring";
          stats["closed"] = t.closed;
          stats["oriented"] = t.oriented;
          stats["self_intersection_free"] = t.self_intersection_free;
          stats["components"] = t.components;
          stats["volume"] = t.volume;
          stats["boundary_edges"] = t.boundary_edges;
          stats["open_at"] = t.open_at;
          stats["grid_passes"] = t.grid_passes;
          stats["refinement_split_edges"] = t.refinement_splits;
          stats["refinement_unresolved_edges"] = t.refinement_unresolved_edges;
          stats["refinement_edges_beyond_tolerance"] = t.refinement_edges_beyond_tolerance;
          stats["grid_adaptations"] = t.grid_adaptations;
          stats["grid_adaptation_refused"] = t.grid_adaptation_refused;
          stats["tags_corrected"] = t.tags_corrected;
          stats["tags_beyond_tolerance"] = t.tags_beyond_tolerance;
          stats["largest_tag_distance"] = t.largest_tag_distance;
        }
        py::dict out = mesh_dict(e.mesh);
        out["times"] = py::array_t<double>(static_cast<py::ssize_t>(e.times.size()), e.times.data());
        out["patches"] = py::array_t<int>(static_cast<py::ssize_t>(e.patches.size()), e.patches.data());
        out["stats"] = stats;
        return out;
      },
      py::arg("solid"), py::arg("tolerance") = 1e-3, py::arg("bounds") = "bezier", py::arg("superset") = false,
      py::arg("max_cells") = 2000000, py::arg("trimming") = "auto", py::arg("coarse_cells") = 0.0, py::arg("adaptive_cells") = py::none(),
      py::arg("refine") = 0.25,
      py::arg("progress") = py::none(),
      R"(The boundary of the volume a swept solid sweeps, as `volspline sweep-envelope`. solid: a SweptSolid,
a Hypervolume or a list of them. superset=True gives the paper's untrimmed superset (caps part 13,
face and edge sweeps 14, the rank-deficient set 15); otherwise it is trimmed to the true boundary
by a certified point-in-image test (trimming: 'auto', 'arrangement' or 'contouring'; coarse_cells=16
contours a grid of 16 tolerances and refines it toward the sheets' equations to refine x tolerance,
as --coarse-cells: much faster on smooth sweeps, creases not resolved yet; otherwise adaptive_cells=M
contours on cells M x the fine grid split into fine cells at creases, as --adaptive-cells: None,
the default, chooses 4 at tolerances of 1e-3 and above and 32 at 1e-4; adaptive_cells=0 contours on
the uniform fine grid). Returns a
mesh dict whose parameters are each vertex's (u, v, w), plus times (t per vertex), patches (the
generator patch per vertex) and stats (triangles per source, cells, closed, oriented,
self_intersection_free, components, volume, seconds).)");
}

}  // namespace volspline::python
