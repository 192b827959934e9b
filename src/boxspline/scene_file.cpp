#include "volspline/boxspline/scene_file.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/strict_json.h"

namespace volspline {

namespace {

using nlohmann::json;

std::string key_path(const std::string& parent, const std::string& key) { return parent.empty() ? key : parent + "." + key; }
std::string index_path(const std::string& parent, std::size_t i) { return parent + "[" + std::to_string(i) + "]"; }

[[noreturn]] void fail(const std::string& expected, const json& got, const std::string& path) {
  throw InvalidInput("expected " + expected + ", got " + describe_json_value(got), path);
}

void check_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return item.key() == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InvalidInput("unknown key \"" + item.key() + "\": expected one of " + list, key_path(path, item.key()));
    }
  }
}

const json& required(const json& object, const char* key, const std::string& path, const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) throw InvalidInput("missing key \"" + std::string(key) + "\" (" + what + ")", path);
  return *it;
}

double number(const json& value, const std::string& path, const std::string& what = "a number") {
  if (!value.is_number()) fail(what, value, path);
  const double x = value.get<double>();
  if (!std::isfinite(x)) fail("a finite number", value, path);
  return x;
}

// The range of coordinates of models (io/coordinate_range.h, docs/model-format.md "Range of
// coordinates"; that layer is below this one): positions and lengths of magnitude at most 2^200,
// lengths at least 2^-200. A primitive's value is a polynomial of degree up to 4 in them (the
// torus), which stays a normal double there; beyond, a blend of spheres of radius 1e300 or 1e-200
// meshed to nothing with exit 0.
constexpr double kMaxSceneCoordinate = kMaxCoordinate, kMinSceneLength = kMinExtent;  // core/coordinate_range.h

double positive(const json& object, const char* key, const std::string& path, const std::string& what) {
  const std::string at = key_path(path, key);
  const double x = number(required(object, key, path, what), at, what);
  if (!(x > 0.0)) fail(what, object.at(key), at);
  if (x > kMaxSceneCoordinate || x < kMinSceneLength)
    fail(what + " between 2^-200 and 2^200 (about 6.2e-61 and 1.6e60; docs/scene-format.md)", object.at(key), at);
  return x;
}

Eigen::Vector3d point(const json& object, const char* key, const std::string& path, const std::string& what) {
  const json& value = required(object, key, path, what);
  const std::string at = key_path(path, key);
  if (!value.is_array() || value.size() != 3) fail(what + " (an array of 3 numbers)", value, at);
  Eigen::Vector3d p;
  for (std::size_t i = 0; i < 3; ++i) {
    p[static_cast<int>(i)] = number(value[i], index_path(at, i));
    if (std::abs(p[static_cast<int>(i)]) > kMaxSceneCoordinate)
      fail("a coordinate of magnitude at most 2^200 (about 1.6e60; docs/scene-format.md)", value[i], index_path(at, i));
  }
  return p;
}

Eigen::Vector3d direction(const json& object, const char* key, const std::string& path, const std::string& what) {
  const Eigen::Vector3d d = point(object, key, path, what);
  if (!(d.norm() > 0.0) || !std::isfinite(d.norm())) fail("a nonzero " + what, object.at(key), key_path(path, key));
  return d.normalized();
}

/// Applies a rigid motion x ↦ R x + t to every primitive of a node.
void place(SceneNode& node, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  if (node.operation == SceneOperation::Primitive) {
    node.primitive.origin = rotation * node.primitive.origin + translation;
    node.primitive.rotation = rotation * node.primitive.rotation;
    return;
  }
  for (SceneNode& child : node.children) place(child, rotation, translation);
}

Eigen::Matrix3d rotation(const json& object, const std::string& path) {
  if (!object.is_object()) fail("a rotation {\"axis\": [x, y, z], \"angle_deg\": a}", object, path);
  check_keys(object, path, {"axis", "angle_deg"});
  const Eigen::Vector3d axis = direction(object, "axis", path, "rotation axis");
  const double angle = number(required(object, "angle_deg", path, "the rotation angle in degrees"), key_path(path, "angle_deg"));
  return Eigen::AngleAxisd(angle * std::numbers::pi / 180.0, axis).toRotationMatrix();
}

constexpr const char* kNodeKinds =
    "sphere, ellipsoid, cylinder, cone, torus, plane, union, intersection, difference, blend or place";

SceneNode read_node(const json& value, const std::string& path);

std::vector<SceneNode> read_children(const json& value, const std::string& path, std::size_t minimum, std::size_t maximum) {
  const std::string count = minimum == maximum ? "exactly " + std::to_string(minimum) : "at least " + std::to_string(minimum);
  if (!value.is_array() || value.size() < minimum || value.size() > maximum)
    fail("an array of " + count + " nodes", value, path);
  std::vector<SceneNode> children;
  for (std::size_t i = 0; i < value.size(); ++i) children.push_back(read_node(value[i], index_path(path, i)));
  return children;
}

SceneNode read_primitive(const std::string& kind, const json& p, const std::string& at) {
  SceneNode node;
  ImplicitPrimitive& q = node.primitive;
  if (!p.is_object()) fail("the parameters of a " + kind + " (an object)", p, at);
  if (kind == "sphere") {
    check_keys(p, at, {"center", "radius"});
    q.kind = PrimitiveKind::Sphere;
    q.origin = point(p, "center", at, "the centre");
    q.radius = positive(p, "radius", at, "a positive radius");
  } else if (kind == "ellipsoid") {
    check_keys(p, at, {"center", "radii", "rotation"});
    q.kind = PrimitiveKind::Ellipsoid;
    q.origin = point(p, "center", at, "the centre");
    q.radii = point(p, "radii", at, "the semi-axes along x, y, z");
    for (int i = 0; i < 3; ++i)
      if (!(q.radii[i] >= kMinSceneLength))
        fail(q.radii[i] > 0.0 ? "a semi-axis of at least 2^-200 (about 6.2e-61; docs/scene-format.md)" : "a positive semi-axis",
             p["radii"][static_cast<std::size_t>(i)], index_path(key_path(at, "radii"), static_cast<std::size_t>(i)));
    if (p.contains("rotation")) q.rotation = rotation(p["rotation"], key_path(at, "rotation"));
  } else if (kind == "cylinder") {
    check_keys(p, at, {"point", "axis", "radius"});
    q.kind = PrimitiveKind::Cylinder;
    q.origin = point(p, "point", at, "a point on the axis");
    q.rotation = frame_with_z_axis(direction(p, "axis", at, "axis direction"));
    q.radius = positive(p, "radius", at, "a positive radius");
  } else if (kind == "cone") {
    check_keys(p, at, {"apex", "axis", "half_angle_deg"});
    q.kind = PrimitiveKind::Cone;
    q.origin = point(p, "apex", at, "the apex");
    q.rotation = frame_with_z_axis(direction(p, "axis", at, "axis direction"));
    const std::string a = key_path(at, "half_angle_deg");
    const double angle = number(required(p, "half_angle_deg", at, "the half angle in degrees"), a);
    if (!(angle > 0.0 && angle < 90.0)) fail("a half angle strictly between 0 and 90 degrees", p["half_angle_deg"], a);
    q.half_angle = angle * std::numbers::pi / 180.0;
  } else if (kind == "torus") {
    check_keys(p, at, {"center", "axis", "major", "minor"});
    q.kind = PrimitiveKind::Torus;
    q.origin = point(p, "center", at, "the centre");
    q.rotation = frame_with_z_axis(direction(p, "axis", at, "axis direction"));
    q.radius = positive(p, "major", at, "a positive major radius");
    q.minor_radius = positive(p, "minor", at, "a positive minor radius");
  } else {
    check_keys(p, at, {"point", "normal"});
    q.kind = PrimitiveKind::Plane;
    q.origin = point(p, "point", at, "a point on the plane");
    q.rotation = frame_with_z_axis(direction(p, "normal", at, "outward normal"));
  }
  return node;
}

SceneNode read_node(const json& value, const std::string& path) {
  if (!value.is_object() || value.size() != 1)
    fail(std::string("a node: an object with one key, ") + kNodeKinds, value, path);
  const std::string kind = value.begin().key();
  const json& body = value.begin().value();
  const std::string at = key_path(path, kind);
  if (kind == "sphere" || kind == "ellipsoid" || kind == "cylinder" || kind == "cone" || kind == "torus" || kind == "plane")
    return read_primitive(kind, body, at);
  SceneNode node;
  if (kind == "union" || kind == "intersection") {
    node.operation = kind == "union" ? SceneOperation::Union : SceneOperation::Intersection;
    node.children = read_children(body, at, 1, SIZE_MAX);
  } else if (kind == "difference") {
    node.operation = SceneOperation::Difference;
    node.children = read_children(body, at, 2, 2);
  } else if (kind == "blend") {
    if (!body.is_object()) fail("{\"radius\": r, \"of\": [NODE, ...]}", body, at);
    check_keys(body, at, {"radius", "of"});
    node.operation = SceneOperation::Blend;
    node.radius = positive(body, "radius", at, "a positive blend radius");
    node.children = read_children(required(body, "of", at, "the nodes to blend"), key_path(at, "of"), 1, SIZE_MAX);
  } else if (kind == "place") {
    if (!body.is_object()) fail("{\"translate\": [x, y, z], \"rotate\": {...}, \"of\": NODE}", body, at);
    check_keys(body, at, {"translate", "rotate", "of"});
    node = read_node(required(body, "of", at, "the node to place"), key_path(at, "of"));
    const Eigen::Vector3d t = body.contains("translate") ? point(body, "translate", at, "a translation") : Eigen::Vector3d::Zero();
    const Eigen::Matrix3d r = body.contains("rotate") ? rotation(body["rotate"], key_path(at, "rotate")) : Eigen::Matrix3d::Identity();
    place(node, r, t);
  } else {
    throw InvalidInput("unknown node \"" + kind + "\": expected one of " + kNodeKinds, at);
  }
  return node;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> read_box(const json& root, const char* key) {
  const json& box = required(root, key, "", std::string("{\"min\": [x, y, z], \"max\": [x, y, z]}"));
  const std::string at = key;
  if (!box.is_object()) fail("{\"min\": [x, y, z], \"max\": [x, y, z]}", box, at);
  check_keys(box, at, {"min", "max"});
  const Eigen::Vector3d lo = point(box, "min", at, "the lowest corner"), hi = point(box, "max", at, "the highest corner");
  for (int d = 0; d < 3; ++d)
    if (!(hi[d] > lo[d]))
      throw InvalidInput("expected a nonempty box, max > min in every coordinate, got min " + format_double(lo[d]) +
                             " and max " + format_double(hi[d]) + " in coordinate " + std::to_string(d),
                         at);
  return {lo, hi};
}

Scene read_document(const json& root) {
  if (!root.is_object()) fail("a JSON object with the keys \"volspline_scene\", \"spacing\", \"box\" and \"root\"", root, "");
  check_keys(root, "", {"volspline_scene", "spacing", "box", "domain", "root", "metadata"});
  const json& version = required(root, "volspline_scene", "", "the format version: 1");
  if (!version.is_number_integer() || version.get<std::int64_t>() != kSceneFormatVersion)
    fail("the scene format version 1", version, "volspline_scene");
  Scene scene;
  scene.spacing = positive(root, "spacing", "", "a positive lattice spacing");
  std::tie(scene.box_min, scene.box_max) = read_box(root, "box");
  double points = 1.0;
  for (int d = 0; d < 3; ++d) points *= std::ceil((scene.box_max[d] - scene.box_min[d]) / scene.spacing) + 5.0;
  if (!(points <= kMaxSceneLatticePoints))
    throw InvalidInput("expected a spacing that gives at most " + format_double(kMaxSceneLatticePoints) +
                           " lattice points over the box, got about " + format_double(std::round(points)) +
                           " (use a larger spacing or a smaller box)",
                       "spacing");
  if (root.contains("domain")) {
    scene.domain = read_box(root, "domain");
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) cells *= (std::max(scene.domain->second[d], scene.box_max[d]) - std::min(scene.domain->first[d], scene.box_min[d])) / scene.spacing + 1.0;
    if (!(cells <= kMaxSceneLatticePoints))
      throw InvalidInput("expected a domain of at most " + format_double(kMaxSceneLatticePoints) +
                             " lattice cells at the spacing, got about " + format_double(std::round(cells)),
                         "domain");
  }
  if (const auto it = root.find("metadata"); it != root.end() && !it->is_object()) fail("a JSON object", *it, "metadata");
  scene.root = read_node(required(root, "root", "", "the tree of primitives and operations"), "root");
  return scene;
}

// ------------------------------------------------------------------------------------------
// Writing.

json vector_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json node_json(const SceneNode& node) {
  switch (node.operation) {
    case SceneOperation::Primitive: {
      const ImplicitPrimitive& p = node.primitive;
      const Eigen::Vector3d axis = p.rotation.col(2);
      switch (p.kind) {
        case PrimitiveKind::Sphere:
          return {{"sphere", {{"center", vector_json(p.origin)}, {"radius", p.radius}}}};
        case PrimitiveKind::Ellipsoid: {
          const Eigen::AngleAxisd r(p.rotation);
          json body{{"center", vector_json(p.origin)}, {"radii", vector_json(p.radii)}};
          if (r.angle() != 0.0) body["rotation"] = {{"axis", vector_json(r.axis())}, {"angle_deg", r.angle() * 180.0 / std::numbers::pi}};
          return {{"ellipsoid", body}};
        }
        case PrimitiveKind::Cylinder:
          return {{"cylinder", {{"point", vector_json(p.origin)}, {"axis", vector_json(axis)}, {"radius", p.radius}}}};
        case PrimitiveKind::Cone:
          return {{"cone", {{"apex", vector_json(p.origin)}, {"axis", vector_json(axis)}, {"half_angle_deg", p.half_angle * 180.0 / std::numbers::pi}}}};
        case PrimitiveKind::Torus:
          return {{"torus", {{"center", vector_json(p.origin)}, {"axis", vector_json(axis)}, {"major", p.radius}, {"minor", p.minor_radius}}}};
        case PrimitiveKind::Plane:
          return {{"plane", {{"point", vector_json(p.origin)}, {"normal", vector_json(axis)}}}};
      }
      return nullptr;
    }
    case SceneOperation::Blend: {
      json of = json::array();
      for (const auto& c : node.children) of.push_back(node_json(c));
      return {{"blend", {{"radius", node.radius}, {"of", of}}}};
    }
    default: {
      json children = json::array();
      for (const auto& c : node.children) children.push_back(node_json(c));
      const char* name = node.operation == SceneOperation::Union ? "union" : node.operation == SceneOperation::Intersection ? "intersection" : "difference";
      return {{name, children}};
    }
  }
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source_name) {
  try {
    return read_document(parse_json_document(text));
  } catch (const InvalidInput& e) {
    throw located_in_source(e, source_name);
  }
}

Scene read_scene(const std::filesystem::path& path) { return parse_scene(read_file(path), path.string()); }

std::string scene_to_json(const Scene& scene) {
  json out;
  out["volspline_scene"] = kSceneFormatVersion;
  out["spacing"] = scene.spacing;
  out["box"] = {{"min", vector_json(scene.box_min)}, {"max", vector_json(scene.box_max)}};
  if (scene.domain) out["domain"] = {{"min", vector_json(scene.domain->first)}, {"max", vector_json(scene.domain->second)}};
  out["root"] = node_json(scene.root);
  return out.dump(2) + "\n";
}

}  // namespace volspline
