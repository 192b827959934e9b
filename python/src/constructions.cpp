// The constructions of `volspline make` (construct/): exact primitives, revolution, extrusion,
// ruled volumes, lofts and sweeps (docs/constructions.md, docs/python.md).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.h"
#include "volspline/construct/loft.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/construct/revolution.h"
#include "volspline/construct/sweep.h"
#include "volspline/construct/translation.h"
#include "volspline/core/error.h"

namespace volspline::python {

void bind_constructions(py::module_& m) {
  using Eigen::Vector3d;
  const Vector3d origin = Vector3d::Zero();
  m.def("box", &box, py::arg("size"), py::arg("center") = origin,
        "The axis-parallel box center +- size/2, degree (1, 1, 1), u, v, w along x, y, z (make box).");
  m.def("ball", &ball, py::arg("radius"), py::arg("center") = origin,
        "The exact solid ball: a half disk revolved, degree (1, 2, 2); u = 1 is the sphere (make ball).");
  m.def("cylinder", &cylinder, py::arg("radius"), py::arg("height"), py::arg("inner") = 0.0, py::arg("center") = origin,
        "The solid or hollow cylinder about the z axis, degree (1, 1, 2) (make cylinder).");
  m.def("cone", &cone, py::arg("radius1"), py::arg("radius2"), py::arg("height"), py::arg("center") = origin,
        "The cone or frustum about the z axis, degree (1, 1, 2) (make cone).");
  m.def("torus", &torus, py::arg("major"), py::arg("minor"), py::arg("angle") = 360.0, py::arg("center") = origin,
        "The solid torus, or a segment of angle degrees, about the z axis, degree (1, 2, 2) (make torus).");
  m.def("half_torus", &half_torus, py::arg("major") = 2.0, py::arg("minor") = 1.0, py::arg("center") = origin,
        "Lasser Fig. 2: a half torus as one Bézier volume with points at infinity (make half-torus).");
  m.def("half_cylinder_sweep", &half_cylinder_sweep,
        "Joy-Duchaineau Fig. 1: (cos pi u + 3w, sin pi u, v), rational degree (2, 1, 1).");
  m.def("hyperboloid", &hyperboloid_segment, py::arg("throat_radius") = 1.0, py::arg("half_height") = 1.0, py::arg("center") = origin,
        "Lasser Fig. 3: half of a solid hyperboloid of one sheet x^2 + y^2 - z^2 = a^2 (a = throat_radius), |z| <= "
        "half_height, degree (1, 1, 2) with points at infinity (make hyperboloid).");
  m.def("paper_example_patch", &paper_example_patch,
        "The bicubic patch of Joy-Duchaineau's Figs. 10, 11 and 13, from which swept_patch, twisted_loft and "
        "curved_loft are made.");
  m.def("swept_patch", static_cast<BSplineVolume (*)()>(&swept_patch), "Joy-Duchaineau Fig. 10: the bicubic patch swept along a line (make swept-patch).");
  m.def("twisted_loft", &twisted_loft,
        "Joy-Duchaineau Fig. 11: the patch twisted 35 degrees while swept, sampled 4 times and lofted (make twisted-loft).");
  m.def("curved_loft", &curved_loft,
        "Joy-Duchaineau Fig. 13: the patch swept along a curved path, sampled and lofted (make curved-loft).");
  m.def("revolve", &revolve, py::arg("profile"), py::arg("axis_point"), py::arg("axis_direction"), py::arg("angle"),
        "Revolve a profile surface about an axis through angle degrees (Lasser Theorem 2), exactly (make revolve).");
  m.def("extrude", &extrude, py::arg("profile"), py::arg("vector"),
        "Move a profile surface along a vector (Lasser Theorem 1) (make extrude).");
  m.def("translation_volume", &translation_volume, py::arg("profile"), py::arg("path"),
        "Lasser's translation volume F(u, v) + K(w) - K(0), exact for rational paths (make extrude --path).");
  m.def("ruled", &ruled_volume, py::arg("a"), py::arg("b"), "The ruled (linear blending) volume between two surfaces (make ruled).");
  m.def(
      "loft",
      [](const std::vector<BSplineSurface>& sections, int degree, const std::string& parameterization) {
        LoftParameterization p = LoftParameterization::ChordLength;
        if (parameterization == "centripetal")
          p = LoftParameterization::Centripetal;
        else if (parameterization != "chord-length")
          throw InvalidInput("parameterization: expected chord-length or centripetal, got '" + parameterization + "'");
        return loft(sections, degree, p);
      },
      py::arg("sections"), py::arg("degree") = 3, py::arg("parameterization") = "chord-length",
      "A volume interpolating the sections (skinning) (make loft).");
  m.def(
      "sweep",
      [](const BSplineSurface& profile, const BSplineCurve& path, const std::string& frame) {
        SweepFrame f = SweepFrame::RotationMinimizing;
        if (frame == "frenet")
          f = SweepFrame::Frenet;
        else if (frame == "fixed")
          f = SweepFrame::Fixed;
        else if (frame != "rmf")
          throw InvalidInput("frame: expected rmf, frenet or fixed, got '" + frame + "'");
        return sweep(profile, path, f);
      },
      py::arg("profile"), py::arg("path"), py::arg("frame") = "rmf",
      "Sweep a profile surface along a curve with a moving frame, V = c(w) + R(w) F(u, v) (make sweep).");
}

}  // namespace volspline::python
