#include "volspline/construct/revolution.h"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

// cos and sin of an angle in degrees, exact at multiples of 90 degrees, so that a full turn
// reproduces the first control points and a 180-degree segment gets weights of exactly 0.
std::pair<double, double> cos_sin_deg(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  if (r == 0.0) return {1.0, 0.0};
  if (r == 90.0) return {0.0, 1.0};
  if (r == 180.0) return {-1.0, 0.0};
  if (r == 270.0) return {0.0, -1.0};
  const double rad = deg * std::numbers::pi / 180.0;
  return {std::cos(rad), std::sin(rad)};
}

struct Axis {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;  // unit
};

Axis check_arguments(const BSplineSurface& profile, const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction) {
  if (profile.dimension() != 3)
    throw InvalidInput("a profile for a revolution must be a surface in R^3, got one in R^" + std::to_string(profile.dimension()),
                       "profile");
  if (!axis_point.allFinite()) throw InvalidInput("the axis point must be finite", "axis_point");
  const double length = axis_direction.norm();
  if (!axis_direction.allFinite() || !(length > 0.0) || !std::isfinite(length))
    throw InvalidInput("the axis direction must be finite and nonzero", "axis_direction");
  return {axis_point, axis_direction / length};
}

// The homogeneous map M of eq. 8 about an arbitrary axis: (X, W) = (w x, w) is moved to the
// axis frame (X - W a), its component across the axis rotated by phi, its component along the
// axis multiplied by `scale`, W multiplied by `scale`, and moved back. scale = 1 is a rotation
// (M_0, M_2); scale = cos(alpha/2) with phi = alpha/2 is M_1, the arc's middle point pushed out
// to the tangent intersection by 1/cos(alpha/2) with its weight multiplied by cos(alpha/2).
// Linear in (X, W), so directions (W = 0) need no special case.
void apply_m(const Axis& axis, double c, double s, double scale, const double* in, double* out) {
  const Eigen::Vector3d X(in[0], in[1], in[2]);
  const double W = in[3];
  const Eigen::Vector3d rel = X - W * axis.point;
  const Eigen::Vector3d along = axis.direction * axis.direction.dot(rel);
  const Eigen::Vector3d across = rel - along;
  const Eigen::Vector3d result = scale * along + c * across + s * axis.direction.cross(across) + (scale * W) * axis.point;
  out[0] = result.x(), out[1] = result.y(), out[2] = result.z(), out[3] = scale * W;
}

// Homogeneous coefficients (w x, w) of the profile, with w = 1 for a polynomial one.
std::vector<double> homogeneous4(const BSplineSurface& profile) {
  if (profile.is_rational()) return profile.homogeneous();
  std::vector<double> h;
  const auto& p = profile.points();
  for (std::size_t i = 0; i < p.size(); i += 3) h.insert(h.end(), {p[i], p[i + 1], p[i + 2], 1.0});
  return h;
}

// The layers V_{.,.,k} = M_k F for the given rotation angles and scales, k slowest.
BSplineVolume build(const BSplineSurface& profile, const Axis& axis, const KnotVector& kw, const std::vector<double>& angles,
                    const std::vector<double>& scales) {
  const auto f = homogeneous4(profile);
  const std::size_t layer = f.size();
  std::vector<double> coefficients(layer * angles.size());
  for (std::size_t k = 0; k < angles.size(); ++k) {
    double* out = coefficients.data() + k * layer;
    const auto [c, s] = cos_sin_deg(angles[k]);
    if (c == 1.0 && scales[k] == 1.0) {
      // M_0 = I_4: the profile itself, bit for bit (V(u,v,0) = F, and a full turn closes).
      std::copy(f.begin(), f.end(), out);
      continue;
    }
    for (std::size_t i = 0; i < layer; i += 4) apply_m(axis, c, s, scales[k], f.data() + i, out + i);
  }
  return BSplineVolume::from_homogeneous({profile.knot_vector(0), profile.knot_vector(1), kw}, 3, true, std::move(coefficients));
}

}  // namespace

BSplineVolume revolve(const BSplineSurface& profile, const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                      double angle_deg) {
  const Axis axis = check_arguments(profile, axis_point, axis_direction);
  if (!(angle_deg > 0.0 && angle_deg <= 360.0))
    throw InvalidInput("the angle must be in (0, 360] degrees, got " + format_double(angle_deg), "angle");
  // Arcs of at most 90 degrees keep every weight >= cos 45 deg > 0 (no points at infinity
  // added) and the control net close to the solid.
  const int n = std::max(1, static_cast<int>(std::ceil(angle_deg / 90.0)));
  std::vector<double> knots{0.0, 0.0, 0.0};
  for (int i = 1; i < n; ++i) knots.insert(knots.end(), {static_cast<double>(i) / n, static_cast<double>(i) / n});
  knots.insert(knots.end(), {1.0, 1.0, 1.0});
  const double half = angle_deg / (2.0 * n);
  const double mid_scale = cos_sin_deg(half).first;
  std::vector<double> angles, scales;
  for (int k = 0; k <= 2 * n; ++k) {
    // angle_deg * k / (2n), not k * half: the last angle is then exactly angle_deg (360 closes)
    angles.push_back(angle_deg * k / (2.0 * n));
    scales.push_back(k % 2 == 1 ? mid_scale : 1.0);
  }
  return build(profile, axis, KnotVector(2, std::move(knots)), angles, scales);
}

BSplineVolume revolve_single_segment(const BSplineSurface& profile, const Eigen::Vector3d& axis_point,
                                     const Eigen::Vector3d& axis_direction, double angle_deg) {
  const Axis axis = check_arguments(profile, axis_point, axis_direction);
  if (!(angle_deg > 0.0 && angle_deg <= 180.0))
    throw InvalidInput("a single segment revolution needs an angle in (0, 180] degrees, got " + format_double(angle_deg), "angle");
  // eq. 8: M_0 = I, M_1 (alpha/2, weight factor cos(alpha/2), exactly 0 at 180 degrees), M_2.
  return build(profile, axis, KnotVector::bezier(2), {0.0, angle_deg / 2.0, angle_deg},
               {1.0, cos_sin_deg(angle_deg / 2.0).first, 1.0});
}

}  // namespace volspline
