#pragma once
// The curve object of model files (docs/model-format.md) for formats that embed one, read and
// written by model_file.cpp's own code: skeleton files (io/skeleton_file.h).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// A bspline_curve or bezier_curve object (the keys type, degree, knots, control_points,
/// weights) at `path`. \throw InvalidInput located at `path` (for example
/// "elements[3].curve.knots[0][2]").
BSplineCurve read_model_curve(const nlohmann::json& object, const std::string& path);

/// The JSON text of `curve` as that object, as model files write it; lines after the first are
/// indented by `indent`. \throw InvalidInput located at `path` for a degree model files cannot hold.
std::string model_curve_json(const BSplineCurve& curve, const std::string& indent, const std::string& path);

}  // namespace volspline
