#include "volspline/io/model_refinement.h"

#include <algorithm>
#include <string>

#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"
#include "volspline/io/model_file.h"
#include "volspline/spline/attribute_spline.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"
#include "volspline/spline/reparameterization.h"

namespace volspline {
namespace {

// The object's geometry with its attributes appended as coordinates, and the way back.
template <int D>
class AugmentedObject {
 public:
  explicit AugmentedObject(const ModelObject& object)
      : dimension_(std::get<TensorSpline<D>>(object.spline).dimension()), spline_(augmented(object, names_)) {}

  void refine(const std::vector<RefinementStep>& steps, const ModelObject& object) {
    for (const RefinementStep& step : steps) {
      if (step.direction < 0 || step.direction >= D)
        throw InvalidInput("direction " + std::to_string(step.direction) + " does not exist for a " + object_type_name(object));
      if (step.elevation > 0) check_elevation(step);
      spline_ = step.elevation > 0 ? elevate_degree(spline_, step.direction, step.elevation)
                                   : refine_knots(spline_, step.direction, step.knots);
    }
  }

  const TensorSpline<D>& spline() const { return spline_; }

  // A degree above kMaxModelDegree could not be read back; below it the new control net is
  // counted (each span gains `elevation` control points per row) against the memory limit.
  void check_elevation(const RefinementStep& step) const {
    const KnotVector& kv = spline_.knot_vector(step.direction);
    const long long degree = static_cast<long long>(kv.degree()) + step.elevation;
    if (degree > kMaxModelDegree)
      throw InvalidInput("elevating the degree " + std::to_string(kv.degree()) + " by " + std::to_string(step.elevation) + " gives " +
                         std::to_string(degree) + ", more than the model format allows (" + std::to_string(kMaxModelDegree) + ")");
    std::uint64_t points = static_cast<std::uint64_t>(spline_.dimension() + 1) * sizeof(double);
    for (int d = 0; d < D; ++d) {
      const std::uint64_t n = static_cast<std::uint64_t>(spline_.num_control_points()[d]);
      points = saturating_product({points, d == step.direction ? saturating_sum({n, saturating_product({static_cast<std::uint64_t>(step.elevation),
                                                                                                         static_cast<std::uint64_t>(spline_.knot_vector(d).num_spans())})})
                                                             : n});
    }
    require_memory(saturating_product({points, 3}), "elevating the degree in direction " + std::to_string(step.direction) + " by " +
                                                        std::to_string(step.elevation));
  }

  // Stores `augmented` (this spline or a piece of it) as the geometry and attributes of `target`.
  void store(ModelObject& target, const TensorSpline<D>& augmented) const {
    if (names_.empty()) {
      target.spline = augmented;
      return;
    }
    auto [spline, values] = split_coordinates(augmented, dimension_);
    target.spline = std::move(spline);
    target.attributes.clear();
    for (std::size_t f = 0; f < names_.size(); ++f) target.attributes[names_[f]] = std::move(values[f]);
  }

 private:
  // The geometry of `object` with its attributes appended, their names in `names`.
  static TensorSpline<D> augmented(const ModelObject& object, std::vector<std::string>& names) {
    validate_attributes(object);
    std::vector<std::vector<double>> fields;
    for (const auto& [name, values] : object.attributes) {
      names.push_back(name);
      fields.push_back(values);
    }
    const auto& geometry = std::get<TensorSpline<D>>(object.spline);
    return fields.empty() ? geometry : append_coordinates(geometry, fields);
  }

  int dimension_;
  std::vector<std::string> names_;
  TensorSpline<D> spline_;
};

template <int D>
ModelObject refine_as(const ModelObject& object, const std::vector<RefinementStep>& steps) {
  AugmentedObject<D> augmented(object);
  augmented.refine(steps, object);
  ModelObject result = object;
  const auto& kvs = augmented.spline().knot_vectors();
  result.bezier = object.bezier && std::all_of(kvs.begin(), kvs.end(), [](const KnotVector& kv) { return kv.is_bezier(); });
  augmented.store(result, augmented.spline());
  return result;
}

template <int D>
std::vector<ModelObject> bezier_objects_as(const ModelObject& object, const std::vector<RefinementStep>& steps) {
  AugmentedObject<D> augmented(object);
  augmented.refine(steps, object);
  const auto pieces = bezier_pieces(augmented.spline());
  std::vector<ModelObject> result;
  for (std::size_t c = 0; c < pieces.size(); ++c) {
    ModelObject piece{object.name.empty() ? "" : object.name + " cell " + std::to_string(c), true, object.spline, object.metadata};
    augmented.store(piece, reparameterize_to_unit_box(pieces[c]));
    result.push_back(std::move(piece));
  }
  return result;
}

}  // namespace

ModelObject refine_object(const ModelObject& object, const std::vector<RefinementStep>& steps) {
  // Nothing to refine: every object, swept solids and simplex spline volumes too, passes as it is
  // (a plain change of format).
  if (steps.empty()) return object;
  return visit_spline(object, "conversion", "type",
                      [&](const auto& s) { return refine_as<std::decay_t<decltype(s)>::num_parameters>(object, steps); });
}

std::vector<ModelObject> bezier_objects(const ModelObject& object, const std::vector<RefinementStep>& steps) {
  return visit_spline(object, "Bézier extraction", "type",
                      [&](const auto& s) { return bezier_objects_as<std::decay_t<decltype(s)>::num_parameters>(object, steps); });
}

}  // namespace volspline
