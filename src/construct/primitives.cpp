#include "volspline/construct/primitives.h"

#include <cmath>
#include <string>
#include <vector>

#include "volspline/construct/revolution.h"
#include "volspline/construct/translation.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

const Eigen::Vector3d kZ(0.0, 0.0, 1.0);
// The weight of the corner control point of a rational quadratic quarter circle: cos 45 deg.
const double kQuarter = std::sqrt(0.5);

void require(bool ok, const std::string& message, const std::string& where) {
  if (!ok) throw InvalidInput(message, where);
}

void require_positive(double x, const std::string& name) {
  require(std::isfinite(x) && x > 0.0, "must be a positive finite number, got " + format_double(x), name);
}

void require_center(const Eigen::Vector3d& center) { require(center.allFinite(), "the center must be finite", "center"); }

// A profile in the half plane through the z axis: (x, z) pairs relative to the center, u
// fastest, with optional weights (empty: polynomial).
BSplineSurface profile(std::array<KnotVector, 2> knots, const std::vector<std::array<double, 2>>& xz, std::vector<double> weights,
                       const Eigen::Vector3d& center) {
  std::vector<double> p;
  for (const auto& q : xz) p.insert(p.end(), {center.x() + q[0], center.y(), center.z() + q[1]});
  return BSplineSurface(std::move(knots), 3, std::move(p), std::move(weights));
}

// A disk sector profile: u = 0 at `middle`, u = 1 on the circle arc `arc` (x, z, weight per
// control point). Control points at u = 0 share the arc's weights so the surface is the
// homogeneous ruled surface between the constant point and the arc, i.e. radial segments.
BSplineSurface fan(const KnotVector& kv, std::array<double, 2> middle, const std::vector<std::array<double, 3>>& arc,
                   const Eigen::Vector3d& center) {
  std::vector<std::array<double, 2>> xz;
  std::vector<double> w;
  for (const auto& a : arc) {
    xz.push_back(middle), w.push_back(a[2]);
    xz.push_back({a[0], a[1]}), w.push_back(a[2]);
  }
  return profile({KnotVector::bezier(1), kv}, xz, std::move(w), center);
}

// A full circle of radius r about (cx, cz) in four quarter arcs, starting at angle 0 and going
// counter-clockwise in the (x, z) plane: 9 control points on knots 0,0,0,1/4,1/4,...,1,1,1.
std::vector<std::array<double, 3>> circle(double cx, double cz, double r) {
  return {{cx + r, cz, 1.0}, {cx + r, cz + r, kQuarter}, {cx, cz + r, 1.0},        {cx - r, cz + r, kQuarter}, {cx - r, cz, 1.0},
          {cx - r, cz - r, kQuarter}, {cx, cz - r, 1.0}, {cx + r, cz - r, kQuarter}, {cx + r, cz, 1.0}};
}

KnotVector quarters(int arcs) {
  std::vector<double> k{0.0, 0.0, 0.0};
  for (int i = 1; i < arcs; ++i) k.insert(k.end(), 2, static_cast<double>(i) / arcs);  // C^0 joins of the arcs
  k.insert(k.end(), 3, 1.0);
  return KnotVector(2, std::move(k));
}

}  // namespace

BSplineVolume box(const Eigen::Vector3d& size, const Eigen::Vector3d& center) {
  require(size.allFinite() && (size.array() > 0.0).all(), "every box size must be a positive finite number", "size");
  require_center(center);
  std::vector<double> p;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        p.insert(p.end(), {center.x() + (i - 0.5) * size.x(), center.y() + (j - 0.5) * size.y(), center.z() + (k - 0.5) * size.z()});
  const KnotVector k1 = KnotVector::bezier(1);
  return BSplineVolume({k1, k1, k1}, 3, std::move(p));
}

BSplineVolume ball(double radius, const Eigen::Vector3d& center) {
  require_positive(radius, "radius");
  require_center(center);
  const double r = radius;
  // The half disk x >= 0 of the (x, z) plane: a meridian from the south pole through the
  // equator to the north pole in two quarter arcs, joined to the center by radial segments.
  const auto half_disk = fan(quarters(2), {0.0, 0.0}, {{0, -r, 1}, {r, -r, kQuarter}, {r, 0, 1}, {r, r, kQuarter}, {0, r, 1}}, center);
  return revolve(half_disk, center, kZ, 360.0);
}

BSplineVolume cylinder(double radius, double height, double inner, const Eigen::Vector3d& center) {
  require_positive(radius, "radius");
  require_positive(height, "height");
  require(std::isfinite(inner) && inner >= 0.0 && inner < radius, "the inner radius must be >= 0 and below the radius " + format_double(radius) + ", got " + format_double(inner), "inner");
  require_center(center);
  const double h = height / 2.0;
  const auto rectangle = profile({KnotVector::bezier(1), KnotVector::bezier(1)}, {{inner, -h}, {radius, -h}, {inner, h}, {radius, h}}, {}, center);
  return revolve(rectangle, center, kZ, 360.0);
}

BSplineVolume cone(double radius1, double radius2, double height, const Eigen::Vector3d& center) {
  require(std::isfinite(radius1) && radius1 >= 0.0, "must be a finite number >= 0, got " + format_double(radius1), "radius1");
  require(std::isfinite(radius2) && radius2 >= 0.0, "must be a finite number >= 0, got " + format_double(radius2), "radius2");
  require(radius1 > 0.0 || radius2 > 0.0, "at least one of the radii must be positive", "radius1");
  require_positive(height, "height");
  require_center(center);
  const double h = height / 2.0;
  const auto trapezoid = profile({KnotVector::bezier(1), KnotVector::bezier(1)}, {{0.0, -h}, {radius1, -h}, {0.0, h}, {radius2, h}}, {}, center);
  return revolve(trapezoid, center, kZ, 360.0);
}

BSplineVolume torus(double major, double minor, double angle_deg, const Eigen::Vector3d& center) {
  require_positive(minor, "minor");
  require(std::isfinite(major) && major > minor, "the major radius must exceed the minor radius " + format_double(minor) + ", got " + format_double(major), "major");
  require_center(center);
  const auto disk = fan(quarters(4), {major, 0.0}, circle(major, 0.0, minor), center);
  return revolve(disk, center, kZ, angle_deg);
}

BSplineVolume half_torus(double major, double minor, const Eigen::Vector3d& center) {
  require_positive(minor, "minor");
  require(std::isfinite(major) && major > minor, "the major radius must exceed the minor radius " + format_double(minor) + ", got " + format_double(major), "major");
  require_center(center);
  // The disk of degree (1, 2): u blends the upper half circle (middle control point the
  // direction +z at infinity, weight 0) with the lower one (direction -z). Both have the same
  // denominator, so every u-line is the vertical chord between the two half circles.
  std::vector<double> p, w;
  const double R = major, r = minor;
  const std::array<std::array<double, 4>, 6> net{{{R + r, 0, 0, 1}, {R + r, 0, 0, 1}, {0, 0, r, 0}, {0, 0, -r, 0}, {R - r, 0, 0, 1}, {R - r, 0, 0, 1}}};
  for (const auto& q : net) {
    const bool direction = q[3] == 0.0;  // directions are not offset by the center
    p.insert(p.end(), {q[0] + (direction ? 0.0 : center.x()), q[1] + (direction ? 0.0 : center.y()), q[2] + (direction ? 0.0 : center.z())});
    w.push_back(q[3]);
  }
  const BSplineSurface disk({KnotVector::bezier(1), KnotVector::bezier(2)}, 3, std::move(p), std::move(w));
  return revolve_single_segment(disk, center, kZ, 180.0);
}

BSplineVolume hyperboloid_segment(double throat_radius, double half_height, const Eigen::Vector3d& center) {
  require_positive(throat_radius, "throat_radius");
  require_positive(half_height, "half_height");
  require_center(center);
  const double a = throat_radius, h = half_height;
  // The bilinear patch between the axis segment and the line (a, z, z): the line is at distance
  // a from the axis and skew to it, so it sweeps rho^2 = a^2 + z^2 (Fig. 3).
  std::vector<double> p;
  for (const auto& q : std::array<std::array<double, 3>, 4>{{{0, 0, -h}, {a, -h, -h}, {0, 0, h}, {a, h, h}}})
    p.insert(p.end(), {center.x() + q[0], center.y() + q[1], center.z() + q[2]});
  const BSplineSurface patch({KnotVector::bezier(1), KnotVector::bezier(1)}, 3, std::move(p));
  return revolve_single_segment(patch, center, kZ, 180.0);
}

BSplineVolume half_cylinder_sweep() {
  // The half circle (cos, sin) as the rational quadratic with weights 1, 0, 1 (Lasser Theorem 2
  // at 180 degrees), times the segment z in [0, 1]; then moved along (3, 0, 0) (Theorem 1, n = 1).
  const BSplineSurface half_cylinder({KnotVector::bezier(2), KnotVector::bezier(1)}, 3,
                                     {1, 0, 0, 0, 1, 0, -1, 0, 0, 1, 0, 1, 0, 1, 0, -1, 0, 1}, {1, 0, 1, 1, 0, 1});
  return extrude(half_cylinder, Eigen::Vector3d(3.0, 0.0, 0.0));
}

}  // namespace volspline
