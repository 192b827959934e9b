#pragma once
// Refining a model object — knot insertion, degree elevation, splitting into Bézier pieces —
// with its attributes (model_file.h) carried along exactly: the attributes ride as extra
// coordinates of the control points (spline/attribute_spline.h), so every step transforms them
// as it transforms the geometry, and for a rational object with the same weights. An attribute
// that equals a coordinate of the control points therefore still equals it afterwards.
#include <vector>

#include "volspline/io/model_file.h"

namespace volspline {

/// One refinement of an object: knots inserted in `direction`, or, when `elevation` > 0, the
/// degree in `direction` raised by `elevation`. Neither changes the geometry.
struct RefinementStep {
  int direction = 0;
  /// Knots to insert (any order, repeats allowed); ignored when elevation > 0.
  std::vector<double> knots;
  /// How much to raise the degree; 0 for an insertion.
  int elevation = 0;

  static RefinementStep insertion(int direction, std::vector<double> knots) { return {direction, std::move(knots), 0}; }
  static RefinementStep degree_elevation(int direction, int times) { return {direction, {}, times}; }
};

/// `object` after `steps`, in order, with its attributes refined alike; name and metadata kept.
/// It stays a Bézier object only if it was one and every knot vector is still a single span.
/// \throw InvalidInput for a direction the object does not have ("direction 2 does not exist for
/// a bspline_surface"), invalid attributes (located at "attributes.NAME", as
/// validate_attributes), or as refine_knots / elevate_degree (knots outside the domain,
/// multiplicity above degree + 1, times < 1).
ModelObject refine_object(const ModelObject& object, const std::vector<RefinementStep>& steps = {});

/// `object` after `steps`, split into one Bézier object per nonempty knot cell (cells in order,
/// the first direction fastest), each reparameterised to [0, 1]^D and named "NAME cell C"
/// (unnamed if the object is), with the object's metadata and its attributes restricted alike.
/// \throw InvalidInput as refine_object.
std::vector<ModelObject> bezier_objects(const ModelObject& object, const std::vector<RefinementStep>& steps = {});

}  // namespace volspline
