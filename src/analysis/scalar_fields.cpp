#include "volspline/analysis/scalar_fields.h"

#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/core/error.h"
#include "volspline/spline/attribute_spline.h"

namespace volspline {

std::string ScalarField::name() const {
  switch (kind) {
    case ScalarKind::Jacobian:
      return "jacobian";
    case ScalarKind::U:
      return "u";
    case ScalarKind::V:
      return "v";
    case ScalarKind::W:
      return "w";
    case ScalarKind::Attribute:
      break;
  }
  return attribute;
}

ScalarField scalar_field_named(const std::string& name) {
  if (name.empty()) throw InvalidInput("expected a scalar field: jacobian, u, v, w or an attribute name");
  if (name == "jacobian") return {ScalarKind::Jacobian, ""};
  if (name == "u") return {ScalarKind::U, ""};
  if (name == "v") return {ScalarKind::V, ""};
  if (name == "w") return {ScalarKind::W, ""};
  return {ScalarKind::Attribute, name};
}

std::vector<double> evaluate_scalar_field(const BSplineVolume& volume, const ScalarField& field,
                                          const std::vector<Eigen::Vector3d>& parameters,
                                          const std::vector<double>& attribute_values) {
  std::vector<double> values(parameters.size());
  std::vector<BSplineVolume::Parameter> t(parameters.size());
  for (std::size_t i = 0; i < parameters.size(); ++i) t[i] = {parameters[i][0], parameters[i][1], parameters[i][2]};
  switch (field.kind) {
    case ScalarKind::U:
    case ScalarKind::V:
    case ScalarKind::W: {
      const int d = field.kind == ScalarKind::U ? 0 : field.kind == ScalarKind::V ? 1 : 2;
      for (std::size_t i = 0; i < parameters.size(); ++i) {
        volume.check_in_domain(t[i]);
        values[i] = parameters[i][d];
      }
      return values;
    }
    case ScalarKind::Jacobian: {
      if (volume.dimension() != 3)
        throw InvalidInput("the Jacobian needs control points in R^3, got " + std::to_string(volume.dimension()) + " coordinates");
      // Order 1 gives the point and then the three first partials (derivative_multi_indices).
      const std::vector<double> d = volume.evaluate_points(t, 1);
      for (std::size_t i = 0; i < parameters.size(); ++i) values[i] = jacobian_determinant(d.data() + 12 * i);
      return values;
    }
    case ScalarKind::Attribute: {
      const BSplineVolume field_spline = attribute_spline(volume, attribute_values);
      const std::vector<double> a = field_spline.evaluate_points(t, 0);
      for (std::size_t i = 0; i < parameters.size(); ++i) values[i] = a[i];
      return values;
    }
  }
  return values;
}

}  // namespace volspline
