#include "volspline/construct/swept_examples.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"
#include "volspline/spline/degree_elevation.h"

namespace volspline {

using Eigen::Vector3d;

std::vector<BSplineVolume> torus_quarter_patches(double major, double minor) {
  const BSplineVolume quarter = torus(major, minor, 90.0);
  std::vector<BSplineVolume> patches;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(k * std::numbers::pi / 2.0, Vector3d::UnitZ()).toRotationMatrix();
    patches.push_back(k == 0 ? quarter : transform_affine(quarter, turn, Vector3d::Zero()));
  }
  return patches;
}

BSplineVolume folded_cube() {
  std::vector<double> points;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) points.insert(points.end(), {0.5 * (i - 1), 0.5 * (j - 1), 0.5 * (k - 1)});
  points[3 * 13 + 2] = 2.5;  // the middle control point P_111
  const KnotVector quadratic = KnotVector::bezier(2);
  return BSplineVolume({quadratic, quadratic, quadratic}, 3, std::move(points));
}

BSplineVolume folded_cylinder() {
  const BSplineVolume elevated = elevate_degree(elevate_degree(cylinder(1.0, 2.0), 0), 1);
  std::vector<double> points = elevated.points();
  const auto n = elevated.num_control_points();
  for (int k = 0; k < n[2]; ++k) {
    const std::size_t i = static_cast<std::size_t>(elevated.linear_index({1, 1, k}));
    // The ring at half radius (its points lie at radius 1/2 times the arc's control polygon).
    for (int c = 0; c < 2; ++c) points[3 * i + static_cast<std::size_t>(c)] *= 5.0;
  }
  return BSplineVolume(elevated.knot_vectors(), 3, std::move(points), elevated.weights());
}

BSplineCurve semicircle_path(double radius) {
  if (!(std::isfinite(radius) && radius > 0.0)) throw InvalidInput("expected a positive finite radius", "radius");
  const double r = radius, w = std::sqrt(0.5);
  return BSplineCurve({KnotVector(2, {0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0})}, 3,
                      {r, 0.0, 0.0, r, r, 0.0, 0.0, r, 0.0, -r, r, 0.0, -r, 0.0, 0.0}, {1.0, w, 1.0, w, 1.0});
}

BSplineCurve line_path(const Vector3d& from, const Vector3d& to) {
  return BSplineCurve({KnotVector::bezier(1)}, 3, {from.x(), from.y(), from.z(), to.x(), to.y(), to.z()});
}

SweptSolid torus_along_semicircle() {
  return make_swept_solid(torus_quarter_patches(), semicircle_path(), SweptSolidFrame::of_kind(SweptSolidFrame::Kind::Frenet));
}

SweptSolid tumbling_cylinder() {
  return make_swept_solid({cylinder(1.0, 2.0)}, line_path(Vector3d::Zero(), Vector3d(6.0, 0.0, 0.0)), SweptSolidFrame::rotation(Vector3d::UnitX(), 180.0));
}

SweptSolid folded_cube_along_cubic() { return make_swept_solid({folded_cube()}, curved_loft_path(), SweptSolidFrame{}); }

SweptSolid turning_folded_cylinder() {
  return make_swept_solid({folded_cylinder()}, line_path(Vector3d::Zero(), Vector3d(0.0, 0.0, 6.0)), SweptSolidFrame::rotation(Vector3d::UnitZ(), 90.0));
}

SweptSolid tumbling_folded_cube() {
  return make_swept_solid({folded_cube()}, semicircle_path(), SweptSolidFrame::rotation(Vector3d::UnitX(), 180.0));
}

SweptSolid translated_box(const Vector3d& size, const Vector3d& displacement) {
  return make_swept_solid({box(size)}, line_path(Vector3d::Zero(), displacement), SweptSolidFrame{});
}

SweptSolid translated_ball(double radius, const Vector3d& displacement) {
  return make_swept_solid({ball(radius)}, line_path(Vector3d::Zero(), displacement), SweptSolidFrame{});
}

SweptSolid rotating_box() {
  return make_swept_solid({box(Vector3d(1.0, 1.0, 1.0), Vector3d(1.5, 0.0, 0.5))}, line_path(Vector3d::Zero(), Vector3d::Zero()),
                          SweptSolidFrame::rotation(Vector3d::UnitZ(), 360.0));
}

}  // namespace volspline
