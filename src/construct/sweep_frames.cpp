#include "volspline/construct/sweep_frames.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "path_geometry.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using namespace detail;

Vector3d unit_tangent(const BSplineCurve& path, double t) {
  const Vector3d d = derivatives_at(path, t, 1)[1];
  if (!(d.norm() > speed_floor(path)))
    throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no frame is defined there");
  return d.normalized();
}

// A unit normal to the path's plane if its control points (and directions) span one.
bool plane_normal(const BSplineCurve& path, Vector3d& normal) {
  const int n = path.num_control_points_total();
  Matrix3d scatter = Matrix3d::Zero();
  Vector3d origin = Vector3d::Zero();
  bool have_origin = false;
  for (int i = 0; i < n; ++i) {
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    Vector3d v;
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) {
      v = p;
    } else if (!have_origin) {
      origin = p, have_origin = true;
      continue;
    } else {
      v = p - origin;
    }
    scatter += v * v.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Matrix3d> eig(scatter);
  const Vector3d lambda = eig.eigenvalues();  // ascending
  if (!(lambda(2) > 0.0) || lambda(0) > 1e-24 * lambda(2) || lambda(1) <= 1e-20 * lambda(2)) return false;
  normal = eig.eigenvectors().col(0).normalized();
  return true;
}

Vector3d initial_normal(const BSplineCurve& path, double t0, const Vector3d& tangent) {
  try {
    return frenet_frame(path, t0).col(0);
  } catch (const InvalidInput&) {
  }
  Vector3d n;
  if (plane_normal(path, n)) return n.cross(tangent).normalized();
  Eigen::Index axis = 0;
  tangent.cwiseAbs().minCoeff(&axis);
  const Vector3d e = Vector3d::Unit(axis);
  return (e - e.dot(tangent) * tangent).normalized();
}

}  // namespace

Matrix3d frenet_frame(const BSplineCurve& path, double t) {
  require_dimension(path.dimension(), "the sweep path");
  const auto d = derivatives_at(path, t, 2);
  if (!(d[1].norm() > speed_floor(path)))
    throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no Frenet frame there");
  const Vector3d cross = d[1].cross(d[2]);
  const double curvature = cross.norm() / std::pow(d[1].norm(), 3);
  // Curvature times the path's size: dimensionless, so the test does not depend on scale.
  if (!(curvature * length_scale(path) > 1e-9))
    throw InvalidInput("the sweep path's curvature vanishes at its parameter " + format_double(t) + ": the Frenet frame is undefined there");
  Matrix3d r;
  r.col(2) = d[1].normalized();
  r.col(1) = cross.normalized();
  r.col(0) = r.col(1).cross(r.col(2));
  return r;
}

std::vector<Matrix3d> rotation_minimizing_frames(const BSplineCurve& path, const std::vector<double>& parameters,
                                                 const Matrix3d& start) {
  require_dimension(path.dimension(), "the sweep path");
  std::vector<Matrix3d> frames;
  if (parameters.empty()) return frames;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    path.check_in_domain({parameters[i]});
    if (i > 0 && parameters[i] < parameters[i - 1]) throw InvalidInput("parameters must be ascending", "[" + std::to_string(i) + "]");
  }
  const double h_max = (path.domain_max(0) - path.domain_min(0)) / 4096.0;
  double t = parameters.front();
  Vector3d x = point_at(path, t), tangent = unit_tangent(path, t);
  Vector3d r = start.isZero(0.0) ? initial_normal(path, t, tangent) : Vector3d(start.col(0));
  r = (r - r.dot(tangent) * tangent).normalized();
  auto push = [&] {
    Matrix3d f;
    f.col(0) = r, f.col(1) = tangent.cross(r), f.col(2) = tangent;
    frames.push_back(f);
  };
  push();
  for (std::size_t i = 1; i < parameters.size(); ++i) {
    const double t1 = parameters[i];
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t) / h_max)));
    const double t0 = t;
    for (int s = 1; s <= steps; ++s) {
      const double tn = s == steps ? t1 : t0 + (t1 - t0) * s / steps;
      const Vector3d xn = point_at(path, tn), tn_vec = unit_tangent(path, tn);
      // Steps are tiny, so a tangent that turns by more than 90 degrees in one is a cusp.
      if (tn_vec.dot(tangent) < 0.0)
        throw InvalidInput("the sweep path's tangent vanishes between w = " + format_double(t0 + (t1 - t0) * (s - 1) / steps) +
                           " and " + format_double(tn) + " (a cusp): no frame is defined there");
      // Double reflection (Wang et al. 2008, Algorithm "double reflection"): reflect in the
      // bisecting plane of x_i x_{i+1}, then in the plane that carries the reflected tangent
      // onto the new one. Each step is exactly a rotation, so r stays a unit normal.
      const Vector3d v1 = xn - x;
      const double c1 = v1.squaredNorm();
      Vector3d r_l = r, t_l = tangent;
      if (c1 > 0.0) {
        r_l = r - (2.0 / c1) * v1.dot(r) * v1;
        t_l = tangent - (2.0 / c1) * v1.dot(tangent) * v1;
      }
      const Vector3d v2 = tn_vec - t_l;
      const double c2 = v2.squaredNorm();
      r = c2 > 0.0 ? Vector3d(r_l - (2.0 / c2) * v2.dot(r_l) * v2) : r_l;
      // Rounding only: keep r exactly normal to the tangent and of unit length.
      r = (r - r.dot(tn_vec) * tn_vec).normalized();
      x = xn, tangent = tn_vec;
    }
    t = t1;
    push();
  }
  return frames;
}

}  // namespace volspline
