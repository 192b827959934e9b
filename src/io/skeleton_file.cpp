#include "volspline/io/skeleton_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "model_curve.h"
#include "model_json_support.h"
#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/strict_json.h"

namespace volspline {

namespace {

using nlohmann::json;
using Kind = SkeletonElement::Kind;

constexpr const char* kVersionKey = "volspline_skeleton";

struct KindName {
  Kind kind;
  const char* name;
};
constexpr std::array<KindName, 5> kKinds{{
    {Kind::Point, "point"},
    {Kind::Segment, "segment"},
    {Kind::Polyline, "polyline"},
    {Kind::Curve, "curve"},
    {Kind::Ellipsoid, "ellipsoid"},
}};

const char* kind_name(Kind kind) {
  return std::find_if(kKinds.begin(), kKinds.end(), [&](const KindName& k) { return k.kind == kind; })->name;
}

[[noreturn]] void fail(const std::string& expected, const json& got, const std::string& path) {
  throw InvalidInput("expected " + expected + ", got " + describe_json_value(got), path);
}

// Unknown keys are errors: a misspelt optional key would otherwise be silently ignored.
void allow_keys(const json& object, const std::string& path, const std::vector<std::string>& allowed) {
  for (const auto& item : object.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string list;
    for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
    throw InvalidInput("unknown key " + json_quoted(item.key()) + ": expected one of " + list, json_key_path(path, item.key()));
  }
}

const json& member(const json& object, const char* key, const std::string& path, const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) throw InvalidInput("missing key \"" + std::string(key) + "\" (" + what + ")", path);
  return *it;
}

double number(const json& value, const std::string& path) {
  if (!value.is_number()) fail("a number", value, path);
  return value.get<double>();  // strict JSON refuses literals beyond a double's range
}

std::vector<double> numbers(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array()) fail(what, value, path);
  std::vector<double> out;
  for (std::size_t i = 0; i < value.size(); ++i) out.push_back(number(value[i], json_index_path(path, i)));
  return out;
}

Eigen::Vector3d vector3(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array() || value.size() != 3) fail("an array of 3 numbers (" + what + ")", value, path);
  return {number(value[0], json_index_path(path, 0)), number(value[1], json_index_path(path, 1)),
          number(value[2], json_index_path(path, 2))};
}

// A 3 x 3 matrix by rows, or {"axis": [x, y, z], "degrees": d} (right-handed).
Eigen::Matrix3d read_rotation(const json& value, const std::string& path) {
  const std::string expected =
      "a rotation: an array of 3 rows of 3 numbers, or {\"axis\": [x, y, z], \"degrees\": d}";
  if (value.is_array()) {
    if (value.size() != 3) fail(expected, value, path);
    Eigen::Matrix3d r;
    for (std::size_t i = 0; i < 3; ++i) r.row(static_cast<int>(i)) = vector3(value[i], json_index_path(path, i), "a row of the rotation").transpose();
    return r;
  }
  if (!value.is_object()) fail(expected, value, path);
  allow_keys(value, path, {"axis", "degrees"});
  const std::string axis_path = json_key_path(path, "axis");
  const json& axis_json = member(value, "axis", path, "the rotation axis [x, y, z]");
  const Eigen::Vector3d axis = vector3(axis_json, axis_path, "the rotation axis");
  if (!(axis.norm() > 0.0) || !std::isfinite(axis.norm())) fail("a nonzero rotation axis", axis_json, axis_path);
  const double degrees = number(member(value, "degrees", path, "the angle in degrees"), json_key_path(path, "degrees"));
  return Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()).toRotationMatrix();
}

SkeletonFalloff read_falloff(const json& value, const std::string& path) {
  const std::string expected =
      "a falloff: {\"kind\": \"inverse_square\", \"scale\": s} or {\"kind\": \"polynomial\", \"coefficients\": [a_0, a_1, ...], "
      "\"radius\": r}";
  if (!value.is_object()) fail(expected, value, path);
  const json& kind = member(value, "kind", path, "\"inverse_square\" or \"polynomial\"");
  const std::string kind_path = json_key_path(path, "kind");
  SkeletonFalloff falloff;
  if (kind == "inverse_square") {
    allow_keys(value, path, {"kind", "scale"});
    falloff.kind = SkeletonFalloff::Kind::InverseSquare;
    if (value.contains("scale")) {
      falloff.scale = number(value["scale"], json_key_path(path, "scale"));
      check_length_range(falloff.scale, json_key_path(path, "scale"), "a scale", "docs/formats.md");
    }
  } else if (kind == "polynomial") {
    allow_keys(value, path, {"kind", "coefficients", "radius"});
    falloff.kind = SkeletonFalloff::Kind::Polynomial;
    const std::string at = json_key_path(path, "coefficients");
    falloff.coefficients = numbers(member(value, "coefficients", path, "a_0, a_1, ... of G(d) = Σ a_k d^k"), at,
                                   "an array of numbers (a_0, a_1, ...)");
    falloff.radius = number(member(value, "radius", path, "the distance beyond which G is 0"), json_key_path(path, "radius"));
    check_length_range(falloff.radius, json_key_path(path, "radius"), "a radius", "docs/formats.md");
  } else {
    fail("\"inverse_square\" or \"polynomial\"", kind, kind_path);
  }
  return falloff;
}

SkeletonElement read_element(const json& value, const std::string& path) {
  std::string kinds;
  for (const KindName& k : kKinds) kinds += (kinds.empty() ? "" : ", ") + std::string(k.name);
  if (!value.is_object()) fail("an element (an object whose \"kind\" is one of " + kinds + ")", value, path);
  const json& kind_json = member(value, "kind", path, "one of " + kinds);
  const auto kind = std::find_if(kKinds.begin(), kKinds.end(), [&](const KindName& k) { return kind_json == k.name; });
  if (kind == kKinds.end()) fail("one of " + kinds, kind_json, json_key_path(path, "kind"));

  SkeletonElement element;
  element.kind = kind->kind;
  std::vector<std::string> keys{"name", "kind", "weight", "falloff"};
  switch (element.kind) {
    case Kind::Point:
    case Kind::Segment:
    case Kind::Polyline: {
      keys.push_back("points");
      allow_keys(value, path, keys);
      const std::string at = json_key_path(path, "points");
      const json& points = member(value, "points", path, "an array of points [x, y, z]");
      if (!points.is_array()) fail("an array of points [x, y, z]", points, at);
      for (std::size_t i = 0; i < points.size(); ++i) element.points.push_back(vector3(points[i], json_index_path(at, i), "a point"));
      if (!element.points.empty())
        check_point_coordinate_range(
            element.points.front().data(), element.points.size(), 3, 3,
            [&](std::size_t i, std::size_t c) { return json_index_path(json_index_path(at, i), c); }, at, "points",
            "docs/formats.md");
      break;
    }
    case Kind::Curve:
      keys.push_back("curve");
      allow_keys(value, path, keys);
      element.curve = read_model_curve(member(value, "curve", path, "a curve object as in model files"), json_key_path(path, "curve"));
      {
        const std::string at = json_key_path(json_key_path(path, "curve"), "control_points");
        const std::vector<double>& w = element.curve->weights();
        check_point_coordinate_range(
            element.curve->points().data(), static_cast<std::size_t>(element.curve->num_control_points_total()),
            static_cast<std::size_t>(element.curve->dimension()), static_cast<std::size_t>(element.curve->dimension()),
            [&](std::size_t i, std::size_t c) { return json_index_path(json_index_path(at, i), c); }, at, "control points",
            "docs/formats.md", [&](std::size_t i) { return !w.empty() && w[i] == 0.0; });
      }
      break;
    case Kind::Ellipsoid:
      keys.insert(keys.end(), {"centre", "semi_axes", "rotation"});
      allow_keys(value, path, keys);
      element.centre = vector3(member(value, "centre", path, "the centre [x, y, z]"), json_key_path(path, "centre"), "the centre");
      element.semi_axes = vector3(member(value, "semi_axes", path, "the three semi-axes"), json_key_path(path, "semi_axes"),
                                  "the semi-axes along the rotation's columns");
      check_point_coordinate_range(
          element.centre.data(), 1, 3, 3,
          [&](std::size_t, std::size_t c) { return json_index_path(json_key_path(path, "centre"), c); }, json_key_path(path, "centre"),
          "points", "docs/formats.md");
      for (int k = 0; k < 3; ++k)
        check_length_range(element.semi_axes[k], json_index_path(json_key_path(path, "semi_axes"), static_cast<std::size_t>(k)),
                           "a semi-axis", "docs/formats.md");
      if (value.contains("rotation")) element.rotation = read_rotation(value["rotation"], json_key_path(path, "rotation"));
      break;
  }
  if (const auto it = value.find("name"); it != value.end()) {
    if (!it->is_string()) fail("a string", *it, json_key_path(path, "name"));
    element.name = it->get<std::string>();
  }
  if (value.contains("weight")) element.weight = number(value["weight"], json_key_path(path, "weight"));
  if (value.contains("falloff")) element.falloff = read_falloff(value["falloff"], json_key_path(path, "falloff"));
  return element;
}

SkeletonField read_document(const json& root) {
  if (!root.is_object()) fail("a JSON object with the keys \"volspline_skeleton\" and \"elements\"", root, "");
  allow_keys(root, "", {kVersionKey, "elements"});
  const json& version = member(root, kVersionKey, "", "the format version: 1");
  const std::string supported = "this reader supports version " + std::to_string(kSkeletonFormatVersion);
  if (!version.is_number_unsigned() || version.get<std::uint64_t>() != static_cast<std::uint64_t>(kSkeletonFormatVersion))
    fail("the format version " + std::to_string(kSkeletonFormatVersion) + " (" + supported + ")", version, kVersionKey);
  const json& elements = member(root, "elements", "", "a nonempty array of skeleton elements");
  if (!elements.is_array() || elements.empty()) fail("a nonempty array of skeleton elements", elements, "elements");
  std::vector<SkeletonElement> read;
  for (std::size_t i = 0; i < elements.size(); ++i) read.push_back(read_element(elements[i], json_index_path("elements", i)));
  return SkeletonField(std::move(read));
}

// Numbers as model files write them (io/model_json_support.h).
std::string numbers_json(const std::vector<double>& values, const std::string& indent) {
  std::ostringstream out;
  model_json::write_numbers(out, values.data(), values.size(), indent);
  return out.str();
}

std::string point_text(const Eigen::Vector3d& p) { return numbers_json({p[0], p[1], p[2]}, ""); }

std::string json_string(const std::string& text, const std::string& path) {
  try {
    return json(text).dump(-1, ' ', false, json::error_handler_t::strict);
  } catch (const json::exception&) {
    throw InvalidInput("expected text in UTF-8, got invalid UTF-8", path);
  }
}

void write_element(std::ostringstream& out, const SkeletonElement& element, const std::string& path) {
  const std::string indent = "      ";
  out << "    {\n";
  if (!element.name.empty()) out << indent << "\"name\": " << json_string(element.name, json_key_path(path, "name")) << ",\n";
  out << indent << "\"kind\": \"" << kind_name(element.kind) << "\",\n";
  switch (element.kind) {
    case Kind::Point:
    case Kind::Segment:
    case Kind::Polyline:
      out << indent << "\"points\": [";
      for (std::size_t i = 0; i < element.points.size(); ++i) out << (i ? ", " : "") << point_text(element.points[i]);
      out << "],\n";
      break;
    case Kind::Curve:
      out << indent << "\"curve\": " << model_curve_json(*element.curve, indent, json_key_path(path, "curve")) << ",\n";
      break;
    case Kind::Ellipsoid:
      out << indent << "\"centre\": " << point_text(element.centre) << ",\n";
      out << indent << "\"semi_axes\": " << point_text(element.semi_axes) << ",\n";
      if (element.rotation != Eigen::Matrix3d::Identity()) {
        out << indent << "\"rotation\": [";
        for (int i = 0; i < 3; ++i) out << (i ? ", " : "") << point_text(element.rotation.row(i).transpose());
        out << "],\n";
      }
      break;
  }
  out << indent << "\"weight\": " << model_json::number_text(element.weight) << ",\n";
  const SkeletonFalloff& falloff = element.falloff;
  if (falloff.kind == SkeletonFalloff::Kind::InverseSquare) {
    out << indent << "\"falloff\": {\"kind\": \"inverse_square\", \"scale\": " << model_json::number_text(falloff.scale) << "}\n";
  } else {
    out << indent << "\"falloff\": {\"kind\": \"polynomial\", \"coefficients\": " << numbers_json(falloff.coefficients, indent)
        << ", \"radius\": " << model_json::number_text(falloff.radius) << "}\n";
  }
  out << "    }";
}

}  // namespace

SkeletonField parse_skeleton(std::string_view text, const std::string& source_name) {
  try {
    return read_document(parse_json_document(text));
  } catch (const InvalidInput& e) {
    throw located_in_source(e, source_name);
  }
}

SkeletonField read_skeleton(const std::filesystem::path& path) { return parse_skeleton(read_file(path), path.string()); }

std::string skeleton_to_json(const SkeletonField& field) {
  if (field.elements().empty()) throw InvalidInput("expected at least one element, got none", "elements");
  std::ostringstream out;
  out << "{\n  \"" << kVersionKey << "\": " << kSkeletonFormatVersion << ",\n  \"elements\": [\n";
  const std::vector<SkeletonElement>& elements = field.elements();
  for (std::size_t i = 0; i < elements.size(); ++i) {
    write_element(out, elements[i], json_index_path("elements", i));
    out << (i + 1 < elements.size() ? ",\n" : "\n");
  }
  out << "  ]\n}\n";
  return out.str();
}

void write_skeleton(const SkeletonField& field, const std::filesystem::path& path) {
  write_file_atomically(path, skeleton_to_json(field));
}

}  // namespace volspline
