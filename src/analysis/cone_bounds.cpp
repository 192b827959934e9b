#include "volspline/analysis/cone_bounds.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace volspline {

namespace {

constexpr double kPi = std::numbers::pi;

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // atan2 of |a x b| and a . b is accurate for small and large angles alike.
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

std::pair<double, double> multiply(std::pair<double, double> a, std::pair<double, double> b) {
  const double p[4] = {a.first * b.first, a.first * b.second, a.second * b.first, a.second * b.second};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}

// The interval of |v| over the convex hull of `vectors` with cone `cone`.
std::pair<double, double> length_interval(const std::vector<Eigen::Vector3d>& vectors, const Cone& cone) {
  double hi = 0, lo = std::numeric_limits<double>::infinity();
  for (const auto& v : vectors) {
    hi = std::max(hi, v.norm());
    lo = std::min(lo, v.dot(cone.axis));
  }
  if (cone.spread >= kPi / 2 || !(lo > 0)) lo = 0;
  return {lo, hi};
}

}  // namespace

Cone bounding_cone(const std::vector<Eigen::Vector3d>& vectors) {
  Cone cone;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& v : vectors) {
    const double n = v.norm();
    if (!(n > 0)) {
      cone.spread = kPi;
      return cone;
    }
    sum += v / n;
  }
  const double n = sum.norm();
  if (!(n > 1e-12 * static_cast<double>(vectors.size()))) {
    cone.spread = kPi;
    return cone;
  }
  cone.axis = sum / n;
  for (const auto& v : vectors) cone.spread = std::max(cone.spread, angle_between(cone.axis, v));
  // A cone wider than a half-space is not convex: convex combinations of its vectors can point
  // anywhere (even opposite to the axis), so it bounds nothing.
  if (cone.spread >= kPi / 2) cone.spread = kPi;
  return cone;
}

std::pair<double, double> cone_dot(const Cone& a, const Cone& b) {
  const double theta = angle_between(a.axis, b.axis);
  const double smallest = std::max(0.0, theta - a.spread - b.spread);
  const double largest = std::min(kPi, theta + a.spread + b.spread);
  return {std::cos(largest), std::cos(smallest)};
}

std::pair<double, double> cone_triple_product(const Cone& u, const Cone& v, const Cone& w) {
  // Lengths of v x w: sin of the angle between v and w.
  const double theta = angle_between(v.axis, w.axis);
  const double smallest = std::max(0.0, theta - v.spread - w.spread);
  const double largest = std::min(kPi, theta + v.spread + w.spread);
  double sin_lo = std::min(std::sin(smallest), std::sin(largest));
  const double sin_hi = (smallest <= kPi / 2 && largest >= kPi / 2) ? 1.0 : std::max(std::sin(smallest), std::sin(largest));
  if (smallest <= 0 || largest >= kPi) sin_lo = 0;
  // Direction of v x w: within asin(rho / sin theta) of a_v x a_w, where rho bounds the change of
  // the cross product when each axis moves by at most the chord 2 sin(spread / 2).
  Cone cross;
  const Eigen::Vector3d n = v.axis.cross(w.axis);
  const double e_v = 2 * std::sin(std::min(v.spread, kPi) / 2), e_w = 2 * std::sin(std::min(w.spread, kPi) / 2);
  const double rho = e_v + e_w + e_v * e_w;
  const double s = n.norm();
  if (s > 0 && rho < s) {
    cross.axis = n / s;
    cross.spread = std::asin(std::min(1.0, rho / s));
  } else {
    cross.spread = kPi;
  }
  return multiply(cone_dot(u, cross), {sin_lo, sin_hi});
}

std::pair<double, double> cone_jacobian_bound(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                                              const std::vector<Eigen::Vector3d>& c) {
  const Cone ca = bounding_cone(a), cb = bounding_cone(b), cc = bounding_cone(c);
  const auto la = length_interval(a, ca), lb = length_interval(b, cb), lc = length_interval(c, cc);
  const std::pair<double, double> L{la.first * lb.first * lc.first, la.second * lb.second * lc.second};
  auto bound = multiply(L, cone_triple_product(ca, cb, cc));
  const double margin = 1e-9 * L.second;
  return {bound.first - margin, bound.second + margin};
}

}  // namespace volspline
