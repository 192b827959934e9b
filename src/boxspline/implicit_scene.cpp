#include "volspline/boxspline/implicit_scene.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "volspline/core/error.h"

namespace volspline {

double ImplicitPrimitive::value(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d y = rotation.transpose() * (x - origin);
  double f = 0.0;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();  // local gradient
  switch (kind) {
    case PrimitiveKind::Plane:
      f = y.z();
      g = Eigen::Vector3d::UnitZ();
      break;
    case PrimitiveKind::Sphere:
      f = (y.squaredNorm() - radius * radius) / (2.0 * radius);
      g = y / radius;
      break;
    case PrimitiveKind::Ellipsoid: {
      const double rho = std::cbrt(radii.prod());
      const Eigen::Vector3d scaled = y.cwiseQuotient(radii);
      f = (scaled.squaredNorm() - 1.0) * rho / 2.0;
      g = rho * scaled.cwiseQuotient(radii);
      break;
    }
    case PrimitiveKind::Cylinder:
      f = (y.x() * y.x() + y.y() * y.y() - radius * radius) / (2.0 * radius);
      g = Eigen::Vector3d(y.x(), y.y(), 0.0) / radius;
      break;
    case PrimitiveKind::Cone: {
      const double c = std::cos(half_angle), s = std::sin(half_angle);
      f = ((y.x() * y.x() + y.y() * y.y()) * c * c - y.z() * y.z() * s * s) / (2.0 * s);
      g = Eigen::Vector3d(y.x() * c * c, y.y() * c * c, -y.z() * s * s) / s;
      break;
    }
    case PrimitiveKind::Torus: {
      const double R = radius, r = minor_radius;
      const double q = y.squaredNorm() + R * R - r * r;
      const double scale = 1.0 / (8.0 * R * R * r);
      f = (q * q - 4.0 * R * R * (y.x() * y.x() + y.y() * y.y())) * scale;
      g = Eigen::Vector3d(4.0 * q * y.x() - 8.0 * R * R * y.x(), 4.0 * q * y.y() - 8.0 * R * R * y.y(), 4.0 * q * y.z()) * scale;
      break;
    }
  }
  if (gradient != nullptr) *gradient = rotation * g;
  return f;
}

Eigen::Matrix3d frame_with_z_axis(const Eigen::Vector3d& axis) {
  const double length = axis.norm();
  if (!(length > 0.0) || !std::isfinite(length)) throw InvalidInput("expected a nonzero, finite direction");
  const Eigen::Vector3d z = axis / length;
  // The coordinate axis least aligned with z gives a well-conditioned x.
  Eigen::Index smallest = 0;
  z.cwiseAbs().minCoeff(&smallest);
  const Eigen::Vector3d x = Eigen::Vector3d::Unit(smallest).cross(z).normalized();
  Eigen::Matrix3d frame;
  frame.col(0) = x;
  frame.col(1) = z.cross(x);
  frame.col(2) = z;
  return frame;
}

double scene_value(const SceneNode& node, const Eigen::Vector3d& x, Eigen::Vector3d* gradient) {
  switch (node.operation) {
    case SceneOperation::Primitive:
      return node.primitive.value(x, gradient);
    case SceneOperation::Union:
    case SceneOperation::Intersection:
    case SceneOperation::Difference: {
      Eigen::Vector3d best_gradient = Eigen::Vector3d::Zero();
      double best = 0.0;
      for (std::size_t i = 0; i < node.children.size(); ++i) {
        Eigen::Vector3d g;
        double v = scene_value(node.children[i], x, gradient != nullptr ? &g : nullptr);
        if (node.operation == SceneOperation::Difference && i > 0) v = -v, g = -g;
        const bool take = i == 0 || (node.operation == SceneOperation::Union ? v < best : v > best);
        if (take) best = v, best_gradient = g;
      }
      if (gradient != nullptr) *gradient = best_gradient;
      return best;
    }
    case SceneOperation::Blend: {
      const std::size_t n = node.children.size();
      std::vector<double> values(n), weights(gradient != nullptr ? n : 0);
      std::vector<Eigen::Vector3d> gradients(gradient != nullptr ? n : 0);
      for (std::size_t i = 0; i < n; ++i) values[i] = scene_value(node.children[i], x, gradient != nullptr ? &gradients[i] : nullptr);
      const double value = smooth_minimum(values, node.radius, weights);
      if (gradient != nullptr) {
        gradient->setZero();
        for (std::size_t i = 0; i < n; ++i) *gradient += weights[i] * gradients[i];
      }
      return value;
    }
  }
  return 0.0;
}

namespace {

std::vector<double> node_coefficients(const SceneNode& node, const LatticeField& lattice) {
  if (node.operation == SceneOperation::Primitive) {
    LatticeField field = lattice;
    quasi_interpolate(field, [&](const Eigen::Vector3d& x) { return node.primitive.value(x); });
    return std::move(field.coefficients);
  }
  if (node.operation == SceneOperation::Blend) {
    // The n-ary smooth minimum, entry by entry (symmetric in the children).
    std::vector<std::vector<double>> children;
    for (const SceneNode& child : node.children) children.push_back(node_coefficients(child, lattice));
    std::vector<double> out(children.front().size()), entry(children.size());
    for (std::size_t j = 0; j < out.size(); ++j) {
      for (std::size_t i = 0; i < children.size(); ++i) entry[i] = children[i][j];
      out[j] = volspline::smooth_minimum(entry, node.radius);
    }
    return out;
  }
  std::vector<double> acc;
  for (std::size_t i = 0; i < node.children.size(); ++i) {
    std::vector<double> c = node_coefficients(node.children[i], lattice);
    if (i == 0) {
      acc = std::move(c);
      continue;
    }
    for (std::size_t j = 0; j < acc.size(); ++j) {
      switch (node.operation) {
        case SceneOperation::Union:
          acc[j] = std::min(acc[j], c[j]);
          break;
        case SceneOperation::Intersection:
          acc[j] = std::max(acc[j], c[j]);
          break;
        case SceneOperation::Difference:
          acc[j] = std::max(acc[j], -c[j]);
          break;
        case SceneOperation::Blend:
        case SceneOperation::Primitive:
          break;
      }
    }
  }
  return acc;
}

}  // namespace

LatticeField scene_field(const Scene& scene) {
  LatticeField field = lattice_covering(scene.box_min, scene.box_max, scene.spacing);
  field.coefficients = node_coefficients(scene.root, field);
  return field;
}

int count_primitives(const SceneNode& node) {
  if (node.operation == SceneOperation::Primitive) return 1;
  int n = 0;
  for (const auto& c : node.children) n += count_primitives(c);
  return n;
}

}  // namespace volspline
