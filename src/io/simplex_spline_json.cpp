#include "simplex_spline_json.h"

#include <cstdint>
#include <limits>

#include "model_json_support.h"
#include "volspline/core/error.h"
#include "volspline/io/strict_json.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

using nlohmann::json;
using namespace model_json;

Eigen::Vector3d read_point(const json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 3) fail("a point [x, y, z]", value, path);
  return {number(value[0], json_index_path(path, 0)), number(value[1], json_index_path(path, 1)), number(value[2], json_index_path(path, 2))};
}

std::vector<Eigen::Vector3d> read_points(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array()) fail(what, value, path);
  std::vector<Eigen::Vector3d> points;
  points.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) points.push_back(read_point(value[i], json_index_path(path, i)));
  return points;
}

int read_index(const json& value, const std::string& path, std::size_t count) {
  const std::string what = "a point index from 0 to " + std::to_string(count == 0 ? 0 : count - 1);
  if (!value.is_number_integer()) fail(what, value, path);
  if (value.is_number_unsigned() ? value.get<std::uint64_t>() >= count
                                 : (value.get<std::int64_t>() < 0 || static_cast<std::uint64_t>(value.get<std::int64_t>()) >= count))
    fail(what, value, path);
  return static_cast<int>(value.get<std::int64_t>());
}

void write_point_lines(std::ostringstream& out, const std::vector<Eigen::Vector3d>& points, const std::string& indent) {
  out << "[\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    out << indent << "  ";
    write_numbers(out, points[i].data(), 3, indent + "  ");
    out << (i + 1 < points.size() ? ",\n" : "\n");
  }
  out << indent << "]";
}

}  // namespace

DmsSplineVolume read_simplex_spline_volume(const json& object, const std::string& path) {
  check_keys(object, path,
             {"name", "type", "degree", "points", "tetrahedra", "knot_clouds", "control", "control_points", "attributes", "metadata"});
  const std::string degree_path = json_key_path(path, "degree");
  const json& degree_json = required(object, "degree", path, "the degree, an integer from 0 to " + std::to_string(kMaxSimplexSplineDegree));
  const std::string degree_what = "an integer from 0 to " + std::to_string(kMaxSimplexSplineDegree);
  if (!degree_json.is_number_integer()) fail(degree_what, degree_json, degree_path);
  const std::int64_t degree64 = degree_json.is_number_unsigned() ? static_cast<std::int64_t>(std::min<std::uint64_t>(degree_json.get<std::uint64_t>(), 1000))
                                                                 : degree_json.get<std::int64_t>();
  if (degree64 < 0 || degree64 > kMaxSimplexSplineDegree) fail(degree_what, degree_json, degree_path);
  const int degree = static_cast<int>(degree64);

  TetrahedralMesh domain;
  domain.points = read_points(required(object, "points", path, "the domain's points, the primary knots, each [x, y, z]"),
                              json_key_path(path, "points"), "an array of points [x, y, z] (the domain's vertices)");
  if (domain.points.size() < 4) fail("at least 4 points", object["points"], json_key_path(path, "points"));
  const std::string tet_path = json_key_path(path, "tetrahedra");
  const json& tets = required(object, "tetrahedra", path, "the domain's tetrahedra, each [a, b, c, d] point indices");
  if (!tets.is_array() || tets.empty()) fail("a nonempty array of tetrahedra [a, b, c, d]", tets, tet_path);
  domain.tetrahedra.reserve(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const std::string at = json_index_path(tet_path, t);
    if (!tets[t].is_array() || tets[t].size() != 4) fail("a tetrahedron [a, b, c, d] of 4 point indices", tets[t], at);
    std::array<int, 4> tet;
    for (std::size_t c = 0; c < 4; ++c) tet[c] = read_index(tets[t][c], json_index_path(at, c), domain.points.size());
    domain.tetrahedra.push_back(tet);
  }

  KnotClouds knots;
  knots.degree = degree;
  const std::string cloud_path = json_key_path(path, "knot_clouds");
  const std::string cloud_what = "an array with one knot cloud per point: " + std::to_string(degree) + " sub-knots [x, y, z] each (t_1..t_n; t_0 is the point)";
  const json& clouds = required(object, "knot_clouds", path, cloud_what);
  if (!clouds.is_array() || clouds.size() != domain.points.size()) fail(cloud_what + ", " + std::to_string(domain.points.size()) + " in all", clouds, cloud_path);
  knots.knots.reserve(domain.points.size() * static_cast<std::size_t>(degree + 1));
  for (std::size_t v = 0; v < clouds.size(); ++v) {
    const std::string at = json_index_path(cloud_path, v);
    if (!clouds[v].is_array() || clouds[v].size() != static_cast<std::size_t>(degree))
      fail("an array of " + std::to_string(degree) + " sub-knots [x, y, z]", clouds[v], at);
    knots.knots.push_back(domain.points[v]);
    for (std::size_t l = 0; l < clouds[v].size(); ++l) knots.knots.push_back(read_point(clouds[v][l], json_index_path(at, l)));
  }

  const std::string control_path = json_key_path(path, "control");
  const json& control = required(object, "control", path, "\"shared\" or \"per_tetrahedron\"");
  if (!control.is_string() || (control.get_ref<const std::string&>() != "shared" && control.get_ref<const std::string&>() != "per_tetrahedron"))
    fail("\"shared\" (one control vector per domain point) or \"per_tetrahedron\"", control, control_path);
  const DmsControlSharing sharing = control.get_ref<const std::string&>() == "shared" ? DmsControlSharing::Shared : DmsControlSharing::PerTetrahedron;

  std::vector<std::string> names;
  const auto attributes_it = object.find("attributes");
  if (attributes_it != object.end()) {
    if (!attributes_it->is_object()) fail("an object of named arrays of numbers (one number per control point)", *attributes_it, json_key_path(path, "attributes"));
    for (const auto& item : attributes_it->items()) names.push_back(item.key());
  }
  std::optional<DmsSplineVolume> volume;
  try {
    volume.emplace(std::move(domain), std::move(knots), sharing, names);
  } catch (const InvalidInput& e) {
    // The volume names "tetrahedra[i]", "knot_clouds", "control" or "attributes[i]".
    if (e.where().rfind("attributes", 0) == 0) throw InvalidInput(e.message(), json_key_path(path, "attributes"));
    throw e.located(path);
  }
  const std::size_t count = static_cast<std::size_t>(volume->control_vector_count());
  const std::string points_path = json_key_path(path, "control_points");
  const std::string points_what = "an array of " + std::to_string(count) + " control points [x, y, z] (" +
                                  (sharing == DmsControlSharing::Shared ? "one per domain point" : "one per tetrahedron and multi-index") + ")";
  const json& control_points = required(object, "control_points", path, points_what);
  if (!control_points.is_array() || control_points.size() != count) fail(points_what, control_points, points_path);
  for (std::size_t r = 0; r < count; ++r)
    volume->control_vectors().row(static_cast<Eigen::Index>(r)).head<3>() = read_point(control_points[r], json_index_path(points_path, r)).transpose();
  for (std::size_t a = 0; a < names.size(); ++a) {
    const std::string at = json_key_path(json_key_path(path, "attributes"), names[a]);
    const std::string what = "an array of " + std::to_string(count) + " numbers (one per control point)";
    const json& values = (*attributes_it)[names[a]];
    if (!values.is_array() || values.size() != count) fail(what, values, at);
    const std::vector<double> numbers_read = numbers(values, at, what);
    for (std::size_t r = 0; r < count; ++r) volume->control_vectors()(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(3 + a)) = numbers_read[r];
  }
  return std::move(*volume);
}

void write_simplex_spline_volume(std::ostringstream& out, const DmsSplineVolume& volume, const std::string& indent, const std::string& path) {
  out << indent << "\"degree\": " << volume.degree() << ",\n";
  out << indent << "\"control\": \"" << (volume.sharing() == DmsControlSharing::Shared ? "shared" : "per_tetrahedron") << "\",\n";
  out << indent << "\"points\": ";
  write_point_lines(out, volume.domain().points, indent);
  out << ",\n" << indent << "\"tetrahedra\": [\n";
  const auto& tets = volume.domain().tetrahedra;
  for (std::size_t t = 0; t < tets.size(); ++t)
    out << indent << "  [" << tets[t][0] << ", " << tets[t][1] << ", " << tets[t][2] << ", " << tets[t][3] << "]" << (t + 1 < tets.size() ? ",\n" : "\n");
  out << indent << "],\n" << indent << "\"knot_clouds\": [\n";
  const int n = volume.degree();
  for (std::size_t v = 0; v < volume.domain().points.size(); ++v) {
    out << indent << "  [";
    const Eigen::Vector3d* cloud = volume.knots().cloud(static_cast<int>(v));
    for (int l = 1; l <= n; ++l) {
      out << (l > 1 ? ", " : "");
      write_numbers(out, cloud[l].data(), 3, indent + "  ");
    }
    out << "]" << (v + 1 < volume.domain().points.size() ? ",\n" : "\n");
  }
  out << indent << "],\n" << indent << "\"control_points\": [\n";
  const Eigen::MatrixXd& control = volume.control_vectors();
  for (Eigen::Index r = 0; r < control.rows(); ++r) {
    const Eigen::Vector3d p = control.row(r).head<3>().transpose();
    out << indent << "  ";
    write_numbers(out, p.data(), 3, indent + "  ");
    out << (r + 1 < control.rows() ? ",\n" : "\n");
  }
  out << indent << "]";
  if (!volume.attribute_names().empty()) {
    out << ",\n" << indent << "\"attributes\": {\n";
    for (std::size_t a = 0; a < volume.attribute_names().size(); ++a) {
      const std::string& name = volume.attribute_names()[a];
      const std::string at = json_key_path(json_key_path(path, "attributes"), name);
      out << indent << "  " << json_text(json(name), at, indent, false) << ": ";
      const Eigen::VectorXd values = control.col(static_cast<Eigen::Index>(3 + a));
      for (Eigen::Index r = 0; r < values.size(); ++r)
        if (!std::isfinite(values[r])) throw InvalidInput("expected a finite number, got " + number_text(values[r]), json_index_path(at, static_cast<std::size_t>(r)));
      write_numbers(out, values.data(), static_cast<std::size_t>(values.size()), indent + "  ");
      out << (a + 1 < volume.attribute_names().size() ? ",\n" : "\n");
    }
    out << indent << "}";
  }
}

}  // namespace volspline
