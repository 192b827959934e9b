#include "volspline/io/model_file.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/coordinate_range.h"
#include "volspline/io/strict_json.h"
#include "volspline/spline/attribute_spline.h"
#include "model_json_support.h"
#include "simplex_spline_json.h"
#include "model_curve.h"

namespace volspline {

namespace {

using nlohmann::json;
using namespace model_json;

// ------------------------------------------------------------------------------------------
// Interpreting the DOM.

struct TypeInfo {
  const char* name;
  int parameters;
  bool bezier;
};

// The first six are the classic types, listed first in messages; the 4-variate ones follow.
constexpr std::array<TypeInfo, 8> kTypes{{
    {"bspline_curve", 1, false},
    {"bspline_surface", 2, false},
    {"bspline_volume", 3, false},
    {"bezier_curve", 1, true},
    {"bezier_surface", 2, true},
    {"bezier_volume", 3, true},
    {"bspline_hypervolume", 4, false},
    {"bezier_hypervolume", 4, true},
}};
constexpr std::size_t kClassicTypes = 6;
constexpr const char* kSweptSolidType = "swept_solid";
// A frenet or rmf frame is fitted while the file is read; the fit may halve every span 12 times,
// so its cost is bounded by bounding the path (a larger one is fitted by `make swept-solid`, which
// stores the fitted curves).
constexpr int kMaxFittedPathSpans = 64;

json metadata(const json& object, const std::string& path) {
  const auto it = object.find("metadata");
  if (it == object.end()) return nullptr;
  if (!it->is_object()) fail("a JSON object", *it, json_key_path(path, "metadata"));
  return *it;
}

/// "4 x 5 x 3", the control-point grid from the degrees and knots.
template <int D>
std::string shape_text(const std::array<std::uint64_t, D>& counts) {
  std::string shape;
  for (int d = 0; d < D; ++d) shape += (d ? " x " : "") + std::to_string(counts[static_cast<std::size_t>(d)]);
  return shape;
}

template <int D>
TensorSpline<D> read_spline(const json& object, const std::string& path, const TypeInfo& type) {
  const std::string type_name = type.name;

  // Degrees: integers >= 1, one per direction.
  const std::string degree_path = json_key_path(path, "degree");
  const json& degree_json =
      required(object, "degree", path, "an array of " + std::to_string(D) + " integers for a " + type_name);
  const std::string degree_what = D == 1 ? "an array of 1 integer (the degree of a " + type_name + ")"
                                         : "an array of " + std::to_string(D) +
                                               " integers (one degree per direction of a " + type_name + ")";
  if (!degree_json.is_array() || degree_json.size() != static_cast<std::size_t>(D)) fail(degree_what, degree_json, degree_path);
  std::array<int, D> degrees{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    const json& value = degree_json[d];
    const std::string at = json_index_path(degree_path, d);
    if (!value.is_number_integer()) fail("an integer degree", value, at);
    // nlohmann stores nonnegative integer literals as unsigned, negative ones as signed.
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() < 1) fail("a degree of at least 1", value, at);
    if (value.get<std::uint64_t>() > static_cast<std::uint64_t>(kMaxModelDegree)) {
      fail("a degree of at most " + std::to_string(kMaxModelDegree) + " (the limit of model files)", value, at);
    }
    degrees[d] = static_cast<int>(value.get<std::uint64_t>());
  }

  // Knot vectors. Bézier knots follow from the degrees and are made only once the control
  // points show that the degrees are real (a degree of 10^9 must not allocate 2 * 10^9 knots).
  std::vector<KnotVector> knots;
  std::array<std::uint64_t, D> counts{};
  const std::string knots_path = json_key_path(path, "knots");
  if (type.bezier) {
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) counts[d] = static_cast<std::uint64_t>(degrees[d]) + 1;
  } else {
    const json& knots_json = required(object, "knots", path, "one knot vector per direction");
    const std::string knots_what = D == 1 ? "an array of 1 knot vector (an array of numbers)"
                                          : "an array of " + std::to_string(D) + " knot vectors (arrays of numbers)";
    if (!knots_json.is_array() || knots_json.size() != static_cast<std::size_t>(D)) fail(knots_what, knots_json, knots_path);
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
      const std::string at = json_index_path(knots_path, d);
      std::vector<double> values = numbers(knots_json[d], at, "a knot vector (an array of numbers)");
      // The count is checked before anything is sized by the degree.
      const std::uint64_t needed = 2 * (static_cast<std::uint64_t>(degrees[d]) + 1);
      if (values.size() < needed) {
        throw InvalidInput("a knot vector of degree " + std::to_string(degrees[d]) + " needs at least " +
                               std::to_string(needed) + " knots, got " + std::to_string(values.size()),
                           at);
      }
      try {
        knots.emplace_back(degrees[d], std::move(values));
      } catch (const InvalidInput& e) {
        throw e.located(at);
      }
      counts[d] = static_cast<std::uint64_t>(knots.back().num_basis());
    }
  }

  // Control points: the count must match the grid; every point has k = size of the first.
  const std::string points_path = json_key_path(path, "control_points");
  const json& points_json = required(object, "control_points", path, "an array of control points, u fastest");
  if (!points_json.is_array()) fail("an array of control points (arrays of numbers)", points_json, points_path);
  const std::optional<std::uint64_t> product = product_exactly<std::uint64_t>(counts);
  const bool overflow = !product || *product > static_cast<std::uint64_t>(INT_MAX);
  const std::uint64_t expected = overflow ? 0 : *product;
  if (overflow || expected != points_json.size()) {
    const std::string from = type.bezier ? " from the degrees" : " from the degrees and knots";
    throw InvalidInput(
        "expected " + (overflow ? shape_text<D>(counts) + " control points (" + from.substr(1) + ")"
                                : std::to_string(expected) + " control points (" + shape_text<D>(counts) + from + ")") +
            ", got " + std::to_string(points_json.size()),
        points_path);
  }
  const std::size_t n = points_json.size();
  const json& first = points_json[0];
  if (!first.is_array() || first.empty()) {
    fail("a control point (an array of at least one number)", first, json_index_path(points_path, 0));
  }
  const std::size_t k = first.size();
  if (k > static_cast<std::size_t>(INT_MAX)) fail("a control point with fewer coordinates", first, json_index_path(points_path, 0));
  // Only control_points[0] has been seen: n x (k + 1) numbers must fit the spline's int sizes
  // before anything is sized by that product.
  try {
    checked_product<std::size_t>({n, k + 1}, "control points x (coordinates + 1)", {}, static_cast<std::size_t>(INT_MAX));
  } catch (const InvalidInput& e) {
    throw InvalidInput(e.message(), points_path);
  }
  std::vector<double> points;
  points.reserve(std::min<std::size_t>(n * k, std::size_t{1} << 20));
  for (std::size_t i = 0; i < n; ++i) {
    const json& point = points_json[i];
    const std::string at = json_index_path(points_path, i);
    if (!point.is_array() || point.size() != k) {
      fail("a control point with " + std::to_string(k) + (k == 1 ? " coordinate" : " coordinates") +
               " (as many as control_points[0])",
           point, at);
    }
    for (std::size_t c = 0; c < k; ++c) points.push_back(number(point[c], json_index_path(at, c)));
  }

  // Weights (optional): one per control point, each >= 0.
  std::vector<double> weights;
  if (const auto it = object.find("weights"); it != object.end()) {
    const std::string weights_path = json_key_path(path, "weights");
    if (!it->is_array() || it->size() != n) {
      fail("an array of " + std::to_string(n) + " weights (one per control point)", *it, weights_path);
    }
    weights = numbers(*it, weights_path, "an array of weights");
    for (std::size_t i = 0; i < n; ++i) {
      if (weights[i] < 0.0) fail("a weight >= 0", (*it)[i], json_index_path(weights_path, i));
    }
  }

  if (type.bezier) {
    for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) knots.push_back(KnotVector::bezier(degrees[d]));
  }
  std::array<KnotVector, D> knot_array = [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<KnotVector, D>{std::move(knots[I])...};
  }(std::make_index_sequence<D>{});

  try {
    return TensorSpline<D>(std::move(knot_array), static_cast<int>(k), std::move(points), std::move(weights));
  } catch (const InvalidInput& e) {
    throw e.located(path);
  }
}

/// "attributes": an object of named arrays, one finite number per control point each.
std::map<std::string, std::vector<double>> read_attributes(const json& value, const std::string& path, int count) {
  if (!value.is_object()) fail("an object of named arrays of numbers (one number per control point)", value, path);
  std::map<std::string, std::vector<double>> attributes;
  for (const auto& item : value.items()) {
    const std::string at = json_key_path(path, item.key());
    if (item.key().empty()) throw InvalidInput("expected a nonempty attribute name, got \"\"", at);
    const std::string what = "an array of " + std::to_string(count) + " numbers (one per control point)";
    if (!item.value().is_array() || item.value().size() != static_cast<std::size_t>(count)) fail(what, item.value(), at);
    attributes.emplace(item.key(), numbers(item.value(), at, what));
  }
  return attributes;
}

// Control points of a spline object; a swept solid has none of its own.
int control_point_count(const SplineObject& spline) {
  return std::visit(
      [](const auto& s) {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, SweptSolid>) return 0;
        else if constexpr (std::is_same_v<std::decay_t<decltype(s)>, DmsSplineVolume>) return s.control_vector_count();
        else return s.num_control_points_total();
      },
      spline);
}

// "one of bspline_curve, ..., bezier_volume" and the other types after them.
std::string type_names(std::size_t count) {
  std::string names;
  for (std::size_t i = 0; i < count; ++i) names += (names.empty() ? "" : ", ") + std::string(kTypes[i].name);
  return names;
}
std::string other_type_names() {
  return type_names(kTypes.size()).substr(type_names(kClassicTypes).size() + 2) + ", " + kSweptSolidType + ", " +
         kSimplexSplineVolumeType;
}

const TypeInfo& spline_type(const json& object, const std::string& path) {
  const json& type_json =
      required(object, "type", path, "one of " + type_names(kTypes.size()) + ", " + kSweptSolidType + ", " + kSimplexSplineVolumeType);
  const std::string type_path = json_key_path(path, "type");
  const std::string others = " (or " + other_type_names() + ")";
  if (!type_json.is_string()) throw InvalidInput("expected a type name (one of " + type_names(kClassicTypes) + others + "), got " +
                                                     describe_json_value(type_json), type_path);
  const std::string& type_name = type_json.get_ref<const std::string&>();
  const auto type = std::find_if(kTypes.begin(), kTypes.end(), [&](const TypeInfo& t) { return type_name == t.name; });
  if (type == kTypes.end())
    throw InvalidInput("expected one of " + type_names(kClassicTypes) + ", got " + describe_json_value(type_json) + others, type_path);
  return *type;
}

SplineObject read_spline_of(const json& object, const std::string& path, const TypeInfo& type) {
  switch (type.parameters) {
    case 1:
      return read_spline<1>(object, path, type);
    case 2:
      return read_spline<2>(object, path, type);
    case 3:
      return read_spline<3>(object, path, type);
    default:
      return read_spline<4>(object, path, type);
  }
}

void reject_bezier_knots(const json& object, const std::string& path, const TypeInfo& type) {
  if (type.bezier && object.contains("knots")) {
    const std::string shape = type.name + 7;
    throw InvalidInput(std::string("a ") + type.name + " has no \"knots\": its domain is [0, 1] in every direction "
                           "(use type \"bspline_" + shape + "\" to give knots)",
                       json_key_path(path, "knots"));
  }
}

// A curve or volume inside a swept solid: only the geometry keys (name, attributes and metadata
// belong to the swept solid).
template <int D>
TensorSpline<D> read_part(const json& object, const std::string& path, const char* what) {
  if (!object.is_object()) fail(std::string("an object (") + what + ")", object, path);
  check_keys(object, path, {"type", "degree", "knots", "control_points", "weights"});
  const TypeInfo& type = spline_type(object, path);
  if (type.parameters != D) {
    throw InvalidInput(std::string("expected ") + what + " (bspline_" + (D == 1 ? "curve" : "volume") + " or bezier_" +
                           (D == 1 ? "curve" : "volume") + "), got a " + type.name,
                       json_key_path(path, "type"));
  }
  reject_bezier_knots(object, path, type);
  return read_spline<D>(object, path, type);
}

SweptSolidFrame read_frame(const json& value, const std::string& path) {
  const std::string expected =
      "a frame: \"fixed\", \"frenet\", \"rmf\", {\"rotate\": {\"axis\": [x, y, z], \"degrees\": d}} or {\"curves\": [b, n, t]}";
  SweptSolidFrame frame;
  if (value.is_string()) {
    const std::string& name = value.get_ref<const std::string&>();
    if (name == "fixed") frame.kind = SweptSolidFrame::Kind::Fixed;
    else if (name == "frenet") frame.kind = SweptSolidFrame::Kind::Frenet;
    else if (name == "rmf") frame.kind = SweptSolidFrame::Kind::RotationMinimizing;
    else fail(expected, value, path);
    return frame;
  }
  if (!value.is_object() || value.size() != 1) fail(expected, value, path);
  if (const auto it = value.find("rotate"); it != value.end()) {
    const std::string at = json_key_path(path, "rotate");
    if (!it->is_object()) fail("an object with the keys \"axis\" and \"degrees\"", *it, at);
    check_keys(*it, at, {"axis", "degrees"});
    const json& axis = required(*it, "axis", at, "the rotation axis [x, y, z]");
    if (!axis.is_array() || axis.size() != 3) fail("an array of 3 numbers (the rotation axis)", axis, json_key_path(at, "axis"));
    const std::vector<double> a = numbers(axis, json_key_path(at, "axis"), "an array of 3 numbers");
    frame.kind = SweptSolidFrame::Kind::Rotation;
    frame.axis = Eigen::Vector3d(a[0], a[1], a[2]);
    if (frame.axis.isZero(0.0)) fail("a nonzero rotation axis", axis, json_key_path(at, "axis"));
    frame.degrees = number(required(*it, "degrees", at, "the angle in degrees at the end of the path"), json_key_path(at, "degrees"));
    return frame;
  }
  if (const auto it = value.find("curves"); it != value.end()) {
    const std::string at = json_key_path(path, "curves");
    if (!it->is_array() || it->size() != 3) fail("an array of 3 curves (b, n, t: the columns of R(t))", *it, at);
    frame.kind = SweptSolidFrame::Kind::Curves;
    for (std::size_t k = 0; k < 3; ++k) frame.curves.push_back(read_part<1>((*it)[k], json_index_path(at, k), "a frame curve"));
    return frame;
  }
  fail(expected, value, path);
}

SweptSolid read_swept_solid(const json& object, const std::string& path) {
  check_keys(object, path, {"name", "type", "generator", "path", "frame", "frame_name", "frame_fit_error", "metadata"});
  const std::string generator_path = json_key_path(path, "generator");
  const json& generator_json = required(object, "generator", path, "an array of volume objects (the generator patches)");
  if (!generator_json.is_array() || generator_json.empty())
    fail("a nonempty array of volume objects (the generator patches)", generator_json, generator_path);
  std::vector<BSplineVolume> generator;
  for (std::size_t i = 0; i < generator_json.size(); ++i)
    generator.push_back(read_part<3>(generator_json[i], json_index_path(generator_path, i), "a volume"));
  BSplineCurve path_curve = read_part<1>(required(object, "path", path, "a curve object (the trajectory c(t))"),
                                         json_key_path(path, "path"), "a curve");
  const auto frame_it = object.find("frame");
  const SweptSolidFrame frame = frame_it == object.end() ? SweptSolidFrame{} : read_frame(*frame_it, json_key_path(path, "frame"));
  if ((frame.kind == SweptSolidFrame::Kind::Frenet || frame.kind == SweptSolidFrame::Kind::RotationMinimizing) &&
      path_curve.knot_vector(0).num_spans() > kMaxFittedPathSpans) {
    throw InvalidInput("a frenet or rmf frame is fitted when the file is read, for paths of at most " +
                           std::to_string(kMaxFittedPathSpans) + " knot spans (this one has " +
                           std::to_string(path_curve.knot_vector(0).num_spans()) +
                           "); give the fitted frame as \"curves\" (volspline make swept-solid writes it)",
                       json_key_path(path, "frame"));
  }
  // frame_name and frame_fit_error say where given frame curves came from (written with them).
  const auto name_it = object.find("frame_name"), error_it = object.find("frame_fit_error");
  if ((name_it != object.end() || error_it != object.end()) && frame.kind != SweptSolidFrame::Kind::Curves) {
    throw InvalidInput("\"frame_name\" and \"frame_fit_error\" go only with a frame given by \"curves\"",
                       json_key_path(path, name_it != object.end() ? "frame_name" : "frame_fit_error"));
  }
  std::string frame_name;
  if (name_it != object.end()) {
    if (!name_it->is_string()) fail("a string", *name_it, json_key_path(path, "frame_name"));
    frame_name = name_it->get<std::string>();
  }
  double fit_error = 0.0;
  if (error_it != object.end()) {
    fit_error = number(*error_it, json_key_path(path, "frame_fit_error"));
    if (fit_error < 0.0) fail("a number >= 0", *error_it, json_key_path(path, "frame_fit_error"));
  }
  try {
    SweptSolid solid = make_swept_solid(std::move(generator), std::move(path_curve), frame);
    if (name_it != object.end()) solid.frame_name = std::move(frame_name);
    if (error_it != object.end()) solid.frame_fit_error = fit_error;
    return solid;
  } catch (const InvalidInput& e) {
    throw e.located(path);
  }
}

ModelObject read_object(const json& object, const std::string& path) {
  if (!object.is_object()) fail("an object (a curve, surface, volume, hypervolume or swept solid)", object, path);
  const auto type_it = object.find("type");
  const bool swept = type_it != object.end() && type_it->is_string() && type_it->get_ref<const std::string&>() == kSweptSolidType;
  const bool simplex =
      type_it != object.end() && type_it->is_string() && type_it->get_ref<const std::string&>() == kSimplexSplineVolumeType;
  if (simplex) {
    std::string name;
    if (const auto it = object.find("name"); it != object.end()) {
      if (!it->is_string()) fail("a string", *it, json_key_path(path, "name"));
      name = it->get<std::string>();
    }
    json object_metadata = metadata(object, path);
    return ModelObject{std::move(name), false, read_simplex_spline_volume(object, path), std::move(object_metadata)};
  }
  if (!swept) check_keys(object, path, {"name", "type", "degree", "knots", "control_points", "weights", "attributes", "metadata"});

  const TypeInfo* type = swept ? nullptr : &spline_type(object, path);
  if (type != nullptr) reject_bezier_knots(object, path, *type);

  std::string name;
  if (const auto it = object.find("name"); it != object.end()) {
    if (!it->is_string()) fail("a string", *it, json_key_path(path, "name"));
    name = it->get<std::string>();
  }
  json object_metadata = metadata(object, path);
  if (swept) return ModelObject{std::move(name), false, read_swept_solid(object, path), std::move(object_metadata)};
  ModelObject result{std::move(name), type->bezier, read_spline_of(object, path, *type), std::move(object_metadata)};
  if (const auto it = object.find("attributes"); it != object.end()) {
    result.attributes = read_attributes(*it, json_key_path(path, "attributes"), control_point_count(result.spline));
  }
  return result;
}

Model read_document(const json& root) {
  if (!root.is_object()) fail("a JSON object with the keys \"volspline\" and \"objects\"", root, "");
  check_keys(root, "", {"volspline", "objects", "metadata"});

  const json& version = required(root, "volspline", "", "the format version: 1");
  const std::string supported = "this reader supports version " + std::to_string(kModelFormatVersion);
  if (!version.is_number_integer()) fail("the format version as an integer (" + supported + ")", version, "volspline");
  if (version.is_number_unsigned() ? version.get<std::uint64_t>() != static_cast<std::uint64_t>(kModelFormatVersion)
                                   : version.get<std::int64_t>() != kModelFormatVersion) {
    throw InvalidInput("unsupported format version " + version.dump() + ": " + supported, "volspline");
  }

  const json& objects = required(root, "objects", "", "a nonempty array of curves, surfaces, volumes and swept solids");
  if (!objects.is_array() || objects.empty()) {
    fail("a nonempty array of objects (curves, surfaces and volumes)", objects, "objects");
  }
  Model model;
  model.metadata = metadata(root, "");
  model.objects.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) model.objects.push_back(read_object(objects[i], json_index_path("objects", i)));
  return model;
}

// ------------------------------------------------------------------------------------------
// Writing.

void write_metadata(std::ostringstream& out, const json& metadata, const std::string& path, const std::string& indent) {
  if (!metadata.is_object()) fail("a JSON object or null", metadata, path);
  out << ",\n" << indent << "\"metadata\": " << json_text(metadata, path, indent, true);
}

bool is_unit_bezier(const KnotVector& kv) {
  const double a = kv.knots().front();
  return kv.is_bezier() && a == 0.0 && !std::signbit(a) && kv.knots().back() == 1.0;
}

template <int D>
void write_spline(std::ostringstream& out, const TensorSpline<D>& spline, bool bezier, const std::string& indent,
                  const std::string& path) {
  for (int d = 0; d < D; ++d) {
    if (spline.knot_vector(d).degree() > kMaxModelDegree) {
      throw InvalidInput("expected a degree of at most " + std::to_string(kMaxModelDegree) +
                             " (the limit of model files), got " + std::to_string(spline.knot_vector(d).degree()),
                         json_index_path(json_key_path(path, "degree"), static_cast<std::size_t>(d)));
    }
  }
  out << indent << "\"degree\": [";
  for (int d = 0; d < D; ++d) out << (d ? ", " : "") << spline.knot_vector(d).degree();
  out << "]";
  if (!bezier) {
    out << ",\n" << indent << "\"knots\": [\n";
    for (int d = 0; d < D; ++d) {
      const std::vector<double>& knots = spline.knot_vector(d).knots();
      out << indent << "  ";
      write_numbers(out, knots.data(), knots.size(), indent + "  ");
      out << (d + 1 < D ? ",\n" : "\n");
    }
    out << indent << "]";
  }
  const std::size_t n = static_cast<std::size_t>(spline.num_control_points_total());
  const std::size_t k = static_cast<std::size_t>(spline.dimension());
  out << ",\n" << indent << "\"control_points\": [\n";
  for (std::size_t i = 0; i < n; ++i) {
    out << indent << "  [";
    for (std::size_t c = 0; c < k; ++c) out << (c ? ", " : "") << number_text(spline.points()[i * k + c]);
    out << (i + 1 < n ? "],\n" : "]\n");
  }
  out << indent << "]";
  if (spline.is_rational()) {
    out << ",\n" << indent << "\"weights\": ";
    write_numbers(out, spline.weights().data(), spline.weights().size(), indent);
  }
}

// One curve or volume of a swept solid: "{", its type and geometry, "}".
template <int D>
void write_part(std::ostringstream& out, const TensorSpline<D>& spline, const std::string& indent, const std::string& path,
                bool indent_first = true) {
  static const char* const kShapes[] = {"curve", "surface", "volume", "hypervolume"};
  out << (indent_first ? indent : "") << "{\n" << indent << "  \"type\": \"bspline_" << kShapes[D - 1] << "\",\n";
  write_spline(out, spline, false, indent + "  ", path);
  out << "\n" << indent << "}";
}

void write_swept_solid(std::ostringstream& out, const SweptSolid& solid, const std::string& indent, const std::string& path) {
  out << indent << "\"generator\": [\n";
  for (std::size_t i = 0; i < solid.generator.size(); ++i) {
    write_part(out, solid.generator[i], indent + "  ", json_index_path(json_key_path(path, "generator"), i));
    out << (i + 1 < solid.generator.size() ? ",\n" : "\n");
  }
  out << indent << "],\n" << indent << "\"path\": ";
  write_part(out, solid.path, indent, json_key_path(path, "path"), false);
  out << ",\n" << indent << "\"frame\": {\"curves\": [\n";
  for (std::size_t k = 0; k < 3; ++k) {
    write_part(out, solid.frame[k], indent + "  ", json_index_path(json_key_path(json_key_path(path, "frame"), "curves"), k));
    out << (k + 1 < 3 ? ",\n" : "\n");
  }
  out << indent << "]},\n" << indent << "\"frame_name\": " << json_text(json(solid.frame_name), json_key_path(path, "frame_name"), indent, false)
      << ",\n" << indent << "\"frame_fit_error\": " << number_text(solid.frame_fit_error);
}

void write_attributes(std::ostringstream& out, const ModelObject& object, const std::string& path,
                      const std::string& indent) {
  try {
    validate_attributes(object);
  } catch (const InvalidInput& e) {
    throw e.located(path);
  }
  out << ",\n" << indent << "\"attributes\": {\n";
  std::size_t i = 0;
  for (const auto& [name, values] : object.attributes) {
    const std::string at = json_key_path(json_key_path(path, "attributes"), name);
    out << indent << "  " << json_text(json(name), at, indent, false) << ": ";
    write_numbers(out, values.data(), values.size(), indent + "  ");
    out << (++i < object.attributes.size() ? ",\n" : "\n");
  }
  out << indent << "}";
}

}  // namespace

BSplineCurve read_model_curve(const json& object, const std::string& path) { return read_part<1>(object, path, "a curve"); }

std::string model_curve_json(const BSplineCurve& curve, const std::string& indent, const std::string& path) {
  std::ostringstream out;
  write_part(out, curve, indent, path, false);
  return out.str();
}

Model parse_model(std::string_view text, const std::string& source_name) {
  try {
    Model model = read_document(parse_json_document(text));
    check_coordinate_range(model);
    return model;
  } catch (const InvalidInput& e) {
    throw located_in_source(e, source_name);
  }
}

Model read_model(const std::filesystem::path& path) { return parse_model(read_file(path), path.string()); }

std::string object_type_name(const ModelObject& object) {
  return std::visit(
      [&](const auto& spline) {
        if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, SweptSolid>) {
          return std::string(kSweptSolidType);
        } else if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, DmsSplineVolume>) {
          return std::string(kSimplexSplineVolumeType);
        } else {
          bool bezier = object.bezier;
          for (const KnotVector& kv : spline.knot_vectors()) bezier = bezier && is_unit_bezier(kv);
          const std::size_t parameters = spline.knot_vectors().size();
          static const char* const kShapes[] = {"curve", "surface", "volume", "hypervolume"};
          return std::string(bezier ? "bezier_" : "bspline_") + kShapes[parameters - 1];
        }
      },
      object.spline);
}

void validate_attributes(const ModelObject& object) {
  if (is_simplex_spline_volume(object) && !object.attributes.empty())
    throw InvalidInput("a simplex_spline_volume keeps its attributes in its control vectors (DmsSplineVolume::add_attribute)", "attributes");
  const int count = control_point_count(object.spline);
  for (const auto& [name, values] : object.attributes) {
    const std::string at = json_key_path("attributes", name);
    if (name.empty()) throw InvalidInput("expected a nonempty attribute name, got \"\"", at);
    if (values.size() != static_cast<std::size_t>(count)) {
      throw InvalidInput("expected " + std::to_string(count) + " values (one per control point), got " +
                             std::to_string(values.size()),
                         at);
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!std::isfinite(values[i])) {
        throw InvalidInput("expected a finite number, got " + format_double(values[i]), json_index_path(at, i));
      }
    }
  }
}

double evaluate_attribute(const ModelObject& object, const std::string& name, const std::vector<double>& t) {
  const auto it = object.attributes.find(name);
  if (it == object.attributes.end()) {
    std::string names;
    for (const auto& item : object.attributes) names += (names.empty() ? "" : ", ") + item.first;
    throw InvalidInput("no attribute " + json_quoted(name) + " (the object has " +
                       (names.empty() ? std::string("none") : names) + ")");
  }
  if (is_swept_solid(object)) throw InvalidInput("a swept solid has no attributes");
  if (is_simplex_spline_volume(object))
    throw InvalidInput("a simplex_spline_volume is evaluated at points of its domain (DmsSplineEvaluator), not at parameters");
  return std::visit(
      [&](const auto& spline) -> double {
        using Spline = std::decay_t<decltype(spline)>;
        if constexpr (std::is_same_v<Spline, SweptSolid> || std::is_same_v<Spline, DmsSplineVolume>) {
          return 0.0;  // refused above
        } else {
        constexpr int D = Spline::num_parameters;
        if (t.size() != static_cast<std::size_t>(D)) {
          throw InvalidInput("expected " + std::to_string(D) + " parameter values for a " + object_type_name(object) +
                             ", got " + std::to_string(t.size()));
        }
        typename Spline::Parameter parameter{};
        std::copy(t.begin(), t.end(), parameter.begin());
        spline.check_in_domain(parameter);
        std::optional<Spline> field;
        try {
          field.emplace(attribute_spline(spline, it->second));
        } catch (const InvalidInput& e) {
          throw e.located(json_key_path("attributes", name));
        }
        double value = 0.0;
        field->evaluate(parameter, &value);
        return value;
        }
      },
      object.spline);
}

std::string model_to_json(const Model& model) {
  if (model.objects.empty()) throw InvalidInput("expected at least one object, got none", "objects");
  check_coordinate_range(model);  // what no reader would accept is not written
  std::ostringstream out;
  out << "{\n  \"volspline\": " << kModelFormatVersion << ",\n  \"objects\": [\n";
  const std::string indent = "      ";
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const ModelObject& object = model.objects[i];
    const std::string path = json_index_path("objects", i);
    out << "    {\n";
    if (!object.name.empty()) {
      out << indent << "\"name\": " << json_text(json(object.name), json_key_path(path, "name"), indent, false) << ",\n";
    }
    const std::string type = object_type_name(object);
    out << indent << "\"type\": \"" << type << "\",\n";
    const bool bezier = type.rfind("bezier_", 0) == 0;
    std::visit(
        [&](const auto& spline) {
          if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, SweptSolid>) write_swept_solid(out, spline, indent, path);
          else if constexpr (std::is_same_v<std::decay_t<decltype(spline)>, DmsSplineVolume>)
            write_simplex_spline_volume(out, spline, indent, path);
          else write_spline(out, spline, bezier, indent, path);
        },
        object.spline);
    if (!object.attributes.empty()) write_attributes(out, object, path, indent);
    if (!object.metadata.is_null()) write_metadata(out, object.metadata, json_key_path(path, "metadata"), indent);
    out << "\n    }" << (i + 1 < model.objects.size() ? ",\n" : "\n");
  }
  out << "  ]";
  if (!model.metadata.is_null()) write_metadata(out, model.metadata, "metadata", "  ");
  out << "\n}\n";
  return out.str();
}

void write_model(const Model& model, const std::filesystem::path& path) {
  std::string text;
  try {
    text = model_to_json(model);
  } catch (const InvalidInput& e) {
    throw located_in_source(e, path.string());  // "out.json: objects[0]...": which output, which number
  }
  write_file_atomically(path, text);
}


}  // namespace volspline
