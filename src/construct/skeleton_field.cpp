#include "volspline/construct/skeleton_field.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>

#include "bernstein_roots.h"
#include "curve_distance.h"
#include "volspline/core/binomial.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

constexpr double kRotationTolerance = 1e-9;

std::string index_text(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

[[noreturn]] void reject(const std::string& expected, double got, const std::string& where) {
  throw InvalidInput("expected " + expected + ", got " + format_double(got), where);
}

void check_finite(const Eigen::Vector3d& v, const std::string& where) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(v[k])) reject("a finite number", v[k], index_text(where, static_cast<std::size_t>(k)));
}

double point_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& x) { return (x - p).norm(); }

double segment_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& x) {
  const Eigen::Vector3d v = b - a;
  const double length2 = v.squaredNorm();
  if (!(length2 > 0)) return point_distance(a, x);
  const double t = std::clamp((x - a).dot(v) / length2, 0.0, 1.0);
  return (x - (a + t * v)).norm();
}

// The solid ellipsoid {Σ (y_k / a_k)² <= 1} in local coordinates y. Outside it, the nearest
// point is y_k r_k / (r_k + s) with r_k = (a_k / a_min)² >= 1 and s > 0 the root of
// G(s) = Σ (n_k / (r_k + s))² - 1, n_k = r_k y_k / a_k (Eberly, "Distance from a point to an
// ellipse, an ellipsoid, or a hyperellipsoid", 2013). G is convex and decreasing on s > -1, so
// Newton's method started left of the root climbs to it monotonically, and
// max(0, |n| - r_max) <= root <= |n| - 1.
double ellipsoid_distance(const Eigen::Vector3d& semi_axes, const Eigen::Vector3d& y) {
  const Eigen::Vector3d z = y.cwiseQuotient(semi_axes);
  if (z.squaredNorm() <= 1.0) return 0.0;
  const double a_min = semi_axes.minCoeff();
  const Eigen::Vector3d r = (semi_axes / a_min).cwiseAbs2();
  const Eigen::Vector3d n = r.cwiseProduct(z);
  const double upper = n.norm() - 1.0;
  double s = std::max(0.0, n.norm() - r.maxCoeff());
  for (int iteration = 0; iteration < 200; ++iteration) {
    double g = -1.0, slope = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double q = n[k] / (r[k] + s);
      g += q * q;
      slope -= 2.0 * q * q / (r[k] + s);
    }
    if (!(g > 0.0) || !(slope < 0.0)) break;
    const double next = std::min(upper, s - g / slope);
    if (!(next > s)) break;
    s = next;
  }
  double distance2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double offset = y[k] * s / (r[k] + s);  // y_k minus the nearest point's coordinate
    distance2 += offset * offset;
  }
  return std::sqrt(distance2);
}

// G on [0, radius] as a Bernstein polynomial in u = d / radius: the monomial coefficients
// c_k = a_k radius^k become b_j = Σ_{k <= j} C(j, k) / C(n, k) c_k.
BernsteinTensor<1> polynomial_on_radius(const SkeletonFalloff& falloff) {
  const int n = static_cast<int>(falloff.coefficients.size()) - 1;
  BernsteinTensor<1> f({n}, 1);
  double power = 1.0;
  std::vector<double> c(falloff.coefficients.size());
  for (std::size_t k = 0; k < c.size(); ++k, power *= falloff.radius) c[k] = falloff.coefficients[k] * power;
  for (int j = 0; j <= n; ++j) {
    double sum = 0.0;
    for (int k = 0; k <= j; ++k) sum += binomial_coefficient(j, k) / binomial_coefficient(n, k) * c[static_cast<std::size_t>(k)];
    f.coefficients[static_cast<std::size_t>(j)] = sum;
  }
  return f;
}

void validate_falloff(const SkeletonFalloff& falloff, const std::string& where) {
  if (falloff.kind == SkeletonFalloff::Kind::InverseSquare) {
    if (!(falloff.scale > 0.0) || !std::isfinite(falloff.scale)) reject("a finite scale > 0", falloff.scale, where + ".scale");
    return;
  }
  if (falloff.coefficients.empty())
    throw InvalidInput("expected at least one coefficient (G(d) = Σ a_k d^k), got none", where + ".coefficients");
  if (falloff.coefficients.size() > static_cast<std::size_t>(kMaxFalloffDegree) + 1)
    throw InvalidInput("expected at most " + std::to_string(kMaxFalloffDegree + 1) + " coefficients (degree " +
                           std::to_string(kMaxFalloffDegree) + "), got " + std::to_string(falloff.coefficients.size()),
                       where + ".coefficients");
  for (std::size_t k = 0; k < falloff.coefficients.size(); ++k)
    if (!std::isfinite(falloff.coefficients[k])) reject("a finite number", falloff.coefficients[k], index_text(where + ".coefficients", k));
  if (!(falloff.radius > 0.0) || !std::isfinite(falloff.radius)) reject("a finite radius > 0", falloff.radius, where + ".radius");
  // The minimum on [0, radius] is at an end or a root of G'.
  const BernsteinTensor<1> g = polynomial_on_radius(falloff);
  double scale = 0.0, power = 1.0;
  for (std::size_t k = 0; k < falloff.coefficients.size(); ++k, power *= falloff.radius)
    scale += std::abs(falloff.coefficients[k] * power);
  if (!std::isfinite(scale)) reject("coefficients whose terms stay finite up to the radius", falloff.radius, where + ".radius");
  const double eps = std::numeric_limits<double>::epsilon();
  const double noise = 16.0 * static_cast<double>(falloff.coefficients.size() + 1) * eps * scale;
  // The end values are the first and last Bernstein coefficients.
  double lowest = g.coefficients.front(), at = 0.0;
  if (g.coefficients.back() < lowest) {
    lowest = g.coefficients.back();
    at = falloff.radius;
  }
  if (g.degrees[0] >= 1) {
    const BernsteinTensor<1> slope = bernstein_derivative(g, 0);
    for (const double u : bernstein_roots(slope, noise)) {
      const double value = bernstein_evaluate(g, {u});
      if (value < lowest) {
        lowest = value;
        at = u * falloff.radius;
      }
    }
  }
  if (lowest < -noise) {
    throw InvalidInput("expected a polynomial >= 0 on [0, radius] (a falloff is a nonnegative bump; use a negative weight "
                       "for a negative contribution), got G(" + format_double(at) + ") = " + format_double(lowest),
                       where + ".coefficients");
  }
}

void validate(const SkeletonElement& element, const std::string& where) {
  using Kind = SkeletonElement::Kind;
  const std::string points = where + ".points";
  const std::size_t count = element.points.size();
  switch (element.kind) {
    case Kind::Point:
      if (count != 1) throw InvalidInput("expected 1 point for a point element, got " + std::to_string(count), points);
      break;
    case Kind::Segment:
      if (count != 2) throw InvalidInput("expected 2 points for a segment, got " + std::to_string(count), points);
      break;
    case Kind::Polyline:
      if (count < 2) throw InvalidInput("expected at least 2 points for a polyline, got " + std::to_string(count), points);
      break;
    case Kind::Curve:
      if (!element.curve) throw InvalidInput("a curve element needs its curve", where + ".curve");
      if (element.curve->dimension() != 3) {
        throw InvalidInput("expected a curve in 3 dimensions (control points of 3 coordinates), got " +
                               std::to_string(element.curve->dimension()),
                           where + ".curve.control_points");
      }
      break;
    case Kind::Ellipsoid: {
      check_finite(element.centre, where + ".centre");
      for (int k = 0; k < 3; ++k) {
        const double a = element.semi_axes[k];
        if (!(a > 0.0) || !std::isfinite(a)) reject("a finite semi-axis > 0", a, index_text(where + ".semi_axes", static_cast<std::size_t>(k)));
      }
      const Eigen::Matrix3d& r = element.rotation;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (!std::isfinite(r(i, j)))
            reject("a finite number", r(i, j), index_text(index_text(where + ".rotation", static_cast<std::size_t>(i)), static_cast<std::size_t>(j)));
      const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      if (!(error <= kRotationTolerance) || !(r.determinant() > 0.0)) {
        throw InvalidInput("expected a rotation (orthonormal columns to 1e-9, determinant +1), got a matrix with |R^T R - I| = " +
                               format_double(error) + " and determinant " + format_double(r.determinant()),
                           where + ".rotation");
      }
      break;
    }
  }
  if (element.kind != Kind::Curve && element.kind != Kind::Ellipsoid)
    for (std::size_t i = 0; i < count; ++i) check_finite(element.points[i], index_text(points, i));
  if (!std::isfinite(element.weight)) reject("a finite weight", element.weight, where + ".weight");
  validate_falloff(element.falloff, where + ".falloff");
}

double distance_with(const SkeletonElement& element, const CurveDistance* curve, const Eigen::Vector3d& x) {
  using Kind = SkeletonElement::Kind;
  switch (element.kind) {
    case Kind::Point:
      return point_distance(element.points[0], x);
    case Kind::Segment:
      return segment_distance(element.points[0], element.points[1], x);
    case Kind::Polyline: {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i + 1 < element.points.size(); ++i)
        best = std::min(best, segment_distance(element.points[i], element.points[i + 1], x));
      return best;
    }
    case Kind::Curve:
      return (*curve)(x);
    case Kind::Ellipsoid:
      return ellipsoid_distance(element.semi_axes, element.rotation.transpose() * (x - element.centre));
  }
  return 0.0;
}

}  // namespace

double SkeletonFalloff::operator()(double d) const {
  if (kind == Kind::InverseSquare) {
    const double q = d / scale;
    return 1.0 / (1.0 + q * q);
  }
  if (!(d < radius)) return 0.0;
  double value = 0.0;
  for (std::size_t k = coefficients.size(); k-- > 0;) value = value * d + coefficients[k];
  return value;
}

double skeleton_distance(const SkeletonElement& element, const Eigen::Vector3d& x) {
  validate(element, "element");
  if (element.kind == SkeletonElement::Kind::Curve) {
    const CurveDistance curve(*element.curve);
    return distance_with(element, &curve, x);
  }
  return distance_with(element, nullptr, x);
}

SkeletonField::SkeletonField(std::vector<SkeletonElement> elements) : elements_(std::move(elements)) {
  curves_.resize(elements_.size());
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    validate(elements_[i], index_text("elements", i));
    if (elements_[i].kind == SkeletonElement::Kind::Curve) curves_[i] = std::make_shared<const CurveDistance>(*elements_[i].curve);
  }
}

double SkeletonField::distance(std::size_t element, const Eigen::Vector3d& x) const {
  if (element >= elements_.size())
    throw InvalidInput("no element " + std::to_string(element) + " (the field has " + std::to_string(elements_.size()) + ")");
  return distance_with(elements_[element], curves_[element].get(), x);
}

double SkeletonField::operator()(const Eigen::Vector3d& x) const {
  double sum = 0.0;
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const SkeletonElement& element = elements_[i];
    sum += element.weight * element.falloff(distance_with(element, curves_[i].get(), x));
  }
  return sum;
}

}  // namespace volspline
