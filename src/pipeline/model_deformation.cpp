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
      else throw InvalidInput("expected a curve or a surface; deform volumes by composing their control points with `make`", "type");
    } catch (const InvalidInput& e) {
      throw e.located(object_location(source_name, i));
    }
    object.bezier = false;
  }
  return model;
}

}  // namespace volspline
