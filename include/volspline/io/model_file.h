#pragma once
// Model files, format version 1: a JSON document holding B-spline and Bézier curves, surfaces,
// volumes and 4-variate hypervolumes, swept solids (construct/swept_solid.h) and trivariate
// simplex spline volumes (simplex/dms_spline_volume.h). The format, every key and the error messages are described in
// docs/model-format.md; storage order and domain conventions: core/conventions.h.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>


#include "volspline/construct/swept_solid.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/core/error.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// A curve (D=1), surface (D=2), volume (D=3) or hypervolume (D=4); a swept solid: a
/// generator, a path and a frame, which is no single spline (its patches are hypervolumes,
/// swept_patches); or a DMS simplex spline volume over a tetrahedral domain, which holds its
/// attributes itself. Code that works on tensor-product splines visits the first four and
/// refuses or skips the others (is_swept_solid, is_simplex_spline_volume).
using SplineObject = std::variant<TensorSpline<1>, TensorSpline<2>, TensorSpline<3>, TensorSpline<4>, SweptSolid, DmsSplineVolume>;

/// One entry of a model's "objects" array.
struct ModelObject {
  /// The optional "name"; empty if absent (an empty name is not written).
  std::string name;
  /// Read from a bezier_* type (never for a swept solid). Written as bezier_* when true and every knot vector is a single
  /// clamped span on [0, 1]; otherwise written as bspline_*.
  bool bezier = false;
  SplineObject spline;
  /// The object's "metadata": a JSON object, or null if absent.
  nlohmann::json metadata;
  /// The object's "attributes": named scalars, one value per control point (u fastest), that
  /// vary over the object with the same basis as its geometry (evaluate_attribute). Empty if
  /// absent; always empty for a swept solid.
  std::map<std::string, std::vector<double>> attributes{};
};

/// Whether `object` is a swept solid rather than a spline.
inline bool is_swept_solid(const ModelObject& object) { return std::holds_alternative<SweptSolid>(object.spline); }
/// Whether `object` is a simplex spline volume (its attributes are columns of its control vectors).
inline bool is_simplex_spline_volume(const ModelObject& object) { return std::holds_alternative<DmsSplineVolume>(object.spline); }

/// Calls f(spline) with the curve, surface or volume of `object` and returns what f returns: for
/// code that handles only those (exchange formats, Bézier cells, solids).
/// \throw InvalidInput located at `where` ("FORMAT holds curves, surfaces and volumes, not a
/// swept_solid") if the object is a hypervolume or a swept solid; whatever f throws.
template <class F>
decltype(auto) visit_classic_spline(const ModelObject& object, const std::string& format, const std::string& where, F&& f);

/// Calls f(spline) with the spline (D = 1..4) of `object` and returns what f returns.
/// \throw InvalidInput located at `where` ("ACTION works on splines, not on a swept solid (its
/// patches are hypervolumes)") if the object is a swept solid or a simplex spline volume;
/// whatever f throws.
template <class F>
decltype(auto) visit_spline(const ModelObject& object, const std::string& action, const std::string& where, F&& f);

/// A whole model file.
struct Model {
  std::vector<ModelObject> objects;
  /// The top-level "metadata": a JSON object, or null if absent.
  nlohmann::json metadata;
};

/// The format version this library reads and writes.
inline constexpr int kModelFormatVersion = 1;

/// The highest degree a model file may give in any direction. Checking a rational spline costs
/// O(p^2) per knot span, so unbounded degrees would let a small file keep the reader busy for
/// minutes; CAD systems stay far below (OpenCASCADE's limit is 25).
inline constexpr int kMaxModelDegree = 64;

/// Parses the text of a model file. `source_name` (usually the file name) starts every error
/// message. \throw InvalidInput whose what() reads "SOURCE: JSON.PATH: what was expected, got
/// what" (for example "model.json: objects[0].knots[1][3]: knots must not decrease: 0.2 follows
/// 0.5"), or "SOURCE: line L, column C: invalid JSON: ..." for text that is not JSON.
Model parse_model(std::string_view text, const std::string& source_name);

/// Reads and parses a model file; errors name the file as given.
/// \throw IoError if the file cannot be read, InvalidInput if it is not a valid model.
Model read_model(const std::filesystem::path& path);

/// The JSON text of a model (version 1): one control point per line, every number with 17
/// significant digits, so that parse_model(model_to_json(m)) reproduces every double bit for bit.
/// \throw InvalidInput if the model cannot be written as a valid file (no objects, metadata
/// that is not a JSON object, a name that is not UTF-8).
std::string model_to_json(const Model& model);

/// Writes model_to_json(model) to `path` atomically (whole or not at all).
/// \throw IoError if the file cannot be written, InvalidInput as model_to_json.
void write_model(const Model& model, const std::filesystem::path& path);

/// The "type" the object is written with: "bezier_curve", "bspline_volume",
/// "bspline_hypervolume", ..., "swept_solid".
std::string object_type_name(const ModelObject& object);

/// The value of the attribute `name` of `object` at the parameter `t` (one number per parameter
/// direction of the object). The attribute is interpolated like a coordinate of the control
/// points: with the same B-spline basis and, for a rational object, the same weights, so
/// a(t) = sum_i N_i(t) w_i a_i / sum_i N_i(t) w_i (see attribute_spline).
/// \throw InvalidInput if the object is a swept solid or has no such attribute, t has the wrong number of values or
/// lies outside the domain, or the attribute has the wrong number of values.
double evaluate_attribute(const ModelObject& object, const std::string& name, const std::vector<double>& t);

/// Checks every attribute of `object`: one finite value per control point and a nonempty name.
/// \throw InvalidInput located at "attributes.NAME" (or "attributes.NAME[i]") otherwise.
void validate_attributes(const ModelObject& object);

template <class F>
decltype(auto) visit_spline(const ModelObject& object, const std::string& action, const std::string& where, F&& f) {
  using Result = decltype(f(std::declval<const BSplineCurve&>()));
  return std::visit(
      [&](const auto& spline) -> Result {
        if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, SweptSolid>) {
          throw InvalidInput(action + " works on splines, not on a swept solid (its patches are hypervolumes)", where);
        } else if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, DmsSplineVolume>) {
          throw InvalidInput(action + " works on tensor-product splines, not on a simplex_spline_volume", where);
        } else {
          return f(spline);
        }
      },
      object.spline);
}

template <class F>
decltype(auto) visit_classic_spline(const ModelObject& object, const std::string& format, const std::string& where, F&& f) {
  using Result = decltype(f(std::declval<const BSplineCurve&>()));
  return std::visit(
      [&](const auto& spline) -> Result {
        using Spline = std::decay_t<decltype(spline)>;
        if constexpr (std::is_same_v<Spline, SweptSolid> || std::is_same_v<Spline, BSplineHypervolume> ||
                      std::is_same_v<Spline, DmsSplineVolume>) {
          throw InvalidInput(format + " holds curves, surfaces and volumes, not a " + object_type_name(object), where);
        } else {
          return f(spline);
        }
      },
      object.spline);
}

}  // namespace volspline
