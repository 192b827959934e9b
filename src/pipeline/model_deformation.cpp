#include "volspline/pipeline/model_deformation.h"

#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"
#include "volspline/io/model_volumes.h"

namespace volspline {

Model deform_model(const Lattice& lattice, Model model, const std::string& source_name) {
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    ModelObject& object = model.objects[i];
    try {
      if (auto* c = std::get_if<BSplineCurve>(&object.spline)) object.spline = deform_curve(lattice, *c);
      else if (auto* f = std::get_if<BSplineSurface>(&object.spline)) object.spline = deform_surface(lattice, *f);
      else if (auto* v = std::get_if<DmsSplineVolume>(&object.spline)) {
        // Hua–He–Qin §4.2: a simplex spline volume is deformed by moving its control points
        // through the lattice (not composed exactly: the composition's degree would multiply).
        Eigen::MatrixXd& control = v->control_vectors();
        std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(control.rows()));
        for (Eigen::Index r = 0; r < control.rows(); ++r) points[static_cast<std::size_t>(r)] = control.row(r).head<3>().transpose();
        const std::vector<Eigen::Vector3d> moved = deform_points(lattice, points);
        for (Eigen::Index r = 0; r < control.rows(); ++r) control.row(r).head<3>() = moved[static_cast<std::size_t>(r)].transpose();
      } else throw InvalidInput("expected a curve, a surface or a simplex_spline_volume; deform tensor-product volumes by composing their control points with `make`", "type");
    } catch (const InvalidInput& e) {
      throw e.located(object_location(source_name, i));
    }
    object.bezier = false;
  }
  return model;
}

}  // namespace volspline
