#pragma once
// What `volspline info --json` says of every object of a model, as JSON: degrees, control-point
// counts, knot spans, domains, rational or not, points at infinity, bounding boxes; a swept
// solid's generator, path and frame; a simplex spline volume's domain, knots, control vectors and
// attribute ranges. The interactive pages (web/interactive_page.h) show it beside the model.
#include <nlohmann/json.hpp>

#include "volspline/io/model_file.h"

namespace volspline {

/// One entry per object, in order: {"index", "type", "name" (if any), ...its description}.
/// Bounding boxes come from control points refined twice (spline/affine_map.h bounding_box).
nlohmann::json model_object_summaries(const Model& model);

}  // namespace volspline
