#pragma once
// Scalars to colour a solid's surfaces, slices and isoparametric surfaces by (Lasser 1994 §IV;
// Hua-He-Qin model material attributes the same way): the Jacobian determinant of the map, a
// parameter, or a material attribute carried by the control points.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

enum class ScalarKind { Jacobian, U, V, W, Attribute };

struct ScalarField {
  ScalarKind kind = ScalarKind::Jacobian;
  /// The attribute's name for ScalarKind::Attribute.
  std::string attribute;
  /// "jacobian", "u", "v", "w" or the attribute's name.
  std::string name() const;
};

/// "jacobian", "u", "v", "w", or else the name of an attribute.
/// \throw InvalidInput for an empty name.
ScalarField scalar_field_named(const std::string& name);

/// The field at each parameter point (u, v, w) of `volume`. For ScalarKind::Attribute,
/// `attribute_values` holds one value per control point, interpolated with the volume's basis and
/// weights (spline/attribute_spline.h). The Jacobian is det[V_u V_v V_w] (negative where the map
/// is left-handed or folded).
/// \throw InvalidInput if a point lies outside the domain, the volume is not in R^3 (Jacobian), or
/// the attribute values do not match the control points.
std::vector<double> evaluate_scalar_field(const BSplineVolume& volume, const ScalarField& field,
                                          const std::vector<Eigen::Vector3d>& parameters,
                                          const std::vector<double>& attribute_values = {});

}  // namespace volspline
