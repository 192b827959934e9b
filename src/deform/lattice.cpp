#include "volspline/deform/lattice.h"

#include <cmath>
#include <utility>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

// Three vectors span space when the volume of their parallelepiped is not negligible against
// the product of their lengths (|det| = |U||V||W| for orthogonal ones, 0 for coplanar ones).
// The relative threshold makes the test independent of the lattice's size.
bool spans_space(const Eigen::Matrix3d& axes) {
  const double scale = axes.col(0).norm() * axes.col(1).norm() * axes.col(2).norm();
  return scale > 0 && std::isfinite(scale) && std::abs(axes.determinant()) > 1e-12 * scale;
}

const char* axis_name(int d) { return d == 0 ? "U" : d == 1 ? "V" : "W"; }

[[noreturn]] void lattice_model_error(const std::string& source, const std::string& path, const std::string& message) {
  throw InvalidInput(message, source.empty() ? path : source + ": " + path);
}

Eigen::Vector3d read_vector(const nlohmann::json& value, const std::string& source, const std::string& path) {
  if (!value.is_array() || value.size() != 3) lattice_model_error(source, path, "expected an array of three numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const auto& x = value[static_cast<std::size_t>(i)];
    if (!x.is_number()) lattice_model_error(source, path + "[" + std::to_string(i) + "]", "expected a number");
    v[i] = x.get<double>();
    if (!std::isfinite(v[i])) lattice_model_error(source, path + "[" + std::to_string(i) + "]", "expected a finite number");
  }
  return v;
}

}  // namespace

Eigen::Vector3d lattice_coordinates(const Lattice& lattice, const Eigen::Vector3d& point) {
  // Lasser eq. 10-11: each coordinate is the ratio of two triple products, the component of
  // X - P0 along one edge measured against the plane of the other two. This is Cramer's rule for
  // axes * (s, t, u) = X - P0, and works for any non-coplanar (skew) edges.
  const Eigen::Vector3d U = lattice.axes.col(0), V = lattice.axes.col(1), W = lattice.axes.col(2);
  const Eigen::Vector3d d = point - lattice.origin;
  const Eigen::Vector3d vw = V.cross(W), uw = U.cross(W), uv = U.cross(V);
  return {vw.dot(d) / vw.dot(U), uw.dot(d) / uw.dot(V), uv.dot(d) / uv.dot(W)};
}

Eigen::Vector3d lattice_box_point(const Lattice& lattice, const Eigen::Vector3d& coordinates) {
  return lattice.origin + lattice.axes * coordinates;
}

void validate_lattice(const Lattice& lattice) {
  if (lattice.volume.dimension() != 3) {
    throw InvalidInput("a lattice volume must map into 3-space, got dimension " +
                       std::to_string(lattice.volume.dimension()));
  }
  for (int d = 0; d < 3; ++d) {
    if (lattice.volume.domain_min(d) != 0.0 || lattice.volume.domain_max(d) != 1.0) {
      throw InvalidInput("a lattice volume's domain must be [0, 1] in every direction (lattice coordinates "
                         "are its parameters), got [" + format_double(lattice.volume.domain_min(d)) + ", " +
                         format_double(lattice.volume.domain_max(d)) + "] in direction " + std::to_string(d));
    }
  }
  if (!lattice.origin.allFinite()) throw InvalidInput("the lattice origin must be finite");
  if (!lattice.axes.allFinite() || !spans_space(lattice.axes)) {
    throw InvalidInput("the lattice axes must be three non-coplanar vectors");
  }
}

Lattice undeformed_lattice(const std::vector<Eigen::Vector3d>& points, std::array<int, 3> degree,
                           std::array<int, 3> divisions, double margin, const Eigen::Matrix3d& directions) {
  if (points.empty()) throw InvalidInput("a lattice needs at least one point to enclose");
  for (int d = 0; d < 3; ++d) {
    if (degree[d] < 1 || degree[d] > kMaxModelDegree) {
      throw InvalidInput("lattice degrees must be 1.." + std::to_string(kMaxModelDegree) + ", got " +
                         std::to_string(degree[d]));
    }
    if (divisions[d] < 1 || divisions[d] > 1024) {
      throw InvalidInput("lattice divisions must be 1..1024, got " + std::to_string(divisions[d]));
    }
  }
  if (!std::isfinite(margin) || margin < 0) {
    throw InvalidInput("the lattice margin must be a finite number >= 0, got " + format_double(margin));
  }
  if (!directions.allFinite() || !spans_space(directions)) {
    throw InvalidInput("the lattice directions must be three non-coplanar vectors");
  }
  // Unit directions, so that the margin is measured in lengths, not in multiples of whatever
  // lengths the caller's direction vectors had.
  Eigen::Matrix3d unit = directions;
  for (int d = 0; d < 3; ++d) unit.col(d).normalize();
  const Eigen::Matrix3d inverse = unit.inverse();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput("point " + std::to_string(i) + " is not finite");
    const Eigen::Vector3d c = inverse * points[i];
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const double pad = margin * (hi - lo).maxCoeff();
  lo.array() -= pad;
  hi.array() += pad;
  for (int d = 0; d < 3; ++d) {
    if (!(hi[d] > lo[d])) {
      throw InvalidInput(std::string("the points have no extent along ") + axis_name(d) +
                         " and the margin adds none: give a positive margin");
    }
  }

  Eigen::Matrix3d axes;
  for (int d = 0; d < 3; ++d) axes.col(d) = unit.col(d) * (hi[d] - lo[d]);
  const Eigen::Vector3d origin = unit * lo;

  std::array<KnotVector, 3> knots{KnotVector::uniform_clamped(degree[0], divisions[0]),
                                  KnotVector::uniform_clamped(degree[1], divisions[1]),
                                  KnotVector::uniform_clamped(degree[2], divisions[2])};
  // The Greville abscissae reproduce the linear function s (de Boor's identity), hence the
  // undeformed control points; for a single Bézier segment they are i / p, Lasser's eq. 11.
  const std::array<std::vector<double>, 3> g{knots[0].greville_abscissae(), knots[1].greville_abscissae(),
                                             knots[2].greville_abscissae()};
  std::vector<double> control;
  control.reserve(g[0].size() * g[1].size() * g[2].size() * 3);
  for (const double gk : g[2])
    for (const double gj : g[1])
      for (const double gi : g[0]) {
        const Eigen::Vector3d p = origin + axes * Eigen::Vector3d(gi, gj, gk);
        control.insert(control.end(), {p.x(), p.y(), p.z()});
      }
  return Lattice{BSplineVolume(std::move(knots), 3, std::move(control)), origin, axes};
}

Lattice undeformed_lattice(const TriangleMesh& mesh, std::array<int, 3> degree, std::array<int, 3> divisions,
                           double margin, const Eigen::Matrix3d& directions) {
  return undeformed_lattice(mesh.positions, degree, divisions, margin, directions);
}

Model lattice_to_model(const Lattice& lattice) {
  validate_lattice(lattice);
  bool single_cell = true;
  for (int d = 0; d < 3; ++d) single_cell = single_cell && lattice.volume.knot_vector(d).is_bezier();
  nlohmann::json axes = nlohmann::json::array();
  for (int d = 0; d < 3; ++d) axes.push_back({lattice.axes(0, d), lattice.axes(1, d), lattice.axes(2, d)});
  nlohmann::json metadata = {
      {"lattice", {{"origin", {lattice.origin.x(), lattice.origin.y(), lattice.origin.z()}}, {"axes", axes}}}};
  Model model;
  model.objects.push_back(ModelObject{"lattice", single_cell, lattice.volume, std::move(metadata)});
  return model;
}

Lattice lattice_from_model(const Model& model, const std::string& source) {
  if (model.objects.size() != 1) {
    lattice_model_error(source, "objects", "a lattice file holds exactly one object (the lattice volume), got " +
                                std::to_string(model.objects.size()));
  }
  const ModelObject& object = model.objects[0];
  const auto* volume = std::get_if<BSplineVolume>(&object.spline);
  if (volume == nullptr) lattice_model_error(source, "objects[0].type", "expected a bspline_volume or bezier_volume");
  const std::string path = "objects[0].metadata.lattice";
  if (!object.metadata.is_object() || !object.metadata.contains("lattice")) {
    lattice_model_error(source, "objects[0].metadata", "expected a \"lattice\" entry with \"origin\" and \"axes\"");
  }
  const nlohmann::json& entry = object.metadata["lattice"];
  if (!entry.is_object()) lattice_model_error(source, path, "expected an object with \"origin\" and \"axes\"");
  if (!entry.contains("origin")) lattice_model_error(source, path, "expected an \"origin\": [x, y, z]");
  if (!entry.contains("axes")) lattice_model_error(source, path, "expected \"axes\": [[Ux, Uy, Uz], [Vx, Vy, Vz], [Wx, Wy, Wz]]");
  const Eigen::Vector3d origin = read_vector(entry["origin"], source, path + ".origin");
  const nlohmann::json& axes_json = entry["axes"];
  if (!axes_json.is_array() || axes_json.size() != 3) lattice_model_error(source, path + ".axes", "expected three non-coplanar vectors");
  Eigen::Matrix3d axes;
  for (int d = 0; d < 3; ++d) {
    axes.col(d) = read_vector(axes_json[static_cast<std::size_t>(d)], source, path + ".axes[" + std::to_string(d) + "]");
  }
  if (!spans_space(axes)) lattice_model_error(source, path + ".axes", "expected three non-coplanar vectors");
  Lattice lattice{*volume, origin, axes};
  try {
    validate_lattice(lattice);
  } catch (const InvalidInput& e) {
    lattice_model_error(source, "objects[0]", e.message());
  }
  return lattice;
}

}  // namespace volspline
