#include "volspline/construct/paper_examples.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "volspline/construct/sweep.h"
#include "volspline/spline/affine_map.h"

namespace volspline {

namespace {

const Eigen::Vector3d kSweepVector(0.0, 0.0, 2.0);

// Lofts compatible polynomial sections (same knots, same number of control points) with the
// degree-q B-spline in w on `w_knots` that passes through section m at sites[m]: one small
// collocation system, solved once and applied to every control point (Lasser 1994, eq. 7 with
// the intermediate nets found by interpolation, "skinning").
template <std::size_t N>
BSplineVolume loft(const std::array<BSplineSurface, N>& sections, const KnotVector& w_knots, const std::array<double, N>& sites) {
  const int n = static_cast<int>(N), p = w_knots.degree();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  std::vector<double> basis(static_cast<std::size_t>(p + 1));
  for (int m = 0; m < n; ++m) {
    const int span = w_knots.find_span(sites[static_cast<std::size_t>(m)]);
    w_knots.basis(span, sites[static_cast<std::size_t>(m)], basis.data());
    for (int r = 0; r <= p; ++r) a(m, span - p + r) = basis[static_cast<std::size_t>(r)];
  }
  const Eigen::MatrixXd inverse = a.partialPivLu().inverse();
  const std::size_t layer = sections.front().points().size();
  std::vector<double> points(layer * N, 0.0);
  for (int k = 0; k < n; ++k)
    for (int m = 0; m < n; ++m)
      for (std::size_t i = 0; i < layer; ++i)
        points[static_cast<std::size_t>(k) * layer + i] += inverse(k, m) * sections[static_cast<std::size_t>(m)].points()[i];
  return BSplineVolume({sections.front().knot_vector(0), sections.front().knot_vector(1), w_knots}, 3, std::move(points));
}

}  // namespace

BSplineSurface paper_example_patch() {
  const double y[4] = {-0.75, 0.75, 0.75, 0.375};
  const double z[4][4] = {{0.0, 0.2, 0.2, 0.0}, {0.3, 0.8, 0.8, 0.3}, {0.9, 1.4, 1.4, 0.9}, {1.2, 1.4, 1.4, 1.2}};
  std::vector<double> points;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) points.insert(points.end(), {i - 1.5, y[j], z[j][i]});
  return BSplineSurface({KnotVector::bezier(3), KnotVector::bezier(3)}, 3, std::move(points));
}

BSplineVolume swept_patch() {
  // A line path with the fixed frame is Lasser's Theorem 1 with n = 1: V = F + w d. With x
  // linear in u, y a function of v and d along z, J = det(F_u, F_v, d) = 3 y'(v) |d| depends on
  // v alone, and y' = 1.125 (2 - 3v)(2 - v) makes it vanish on the plane v = 2/3.
  const BSplineCurve line({KnotVector::bezier(1)}, 3, {0.0, 0.0, 0.0, kSweepVector.x(), kSweepVector.y(), kSweepVector.z()});
  return sweep(paper_example_patch(), line, SweepFrame::Fixed);
}

std::array<BSplineSurface, 4> twisted_loft_sections() {
  const BSplineSurface patch = paper_example_patch();
  std::array<BSplineSurface, 4> sections{patch, patch, patch, patch};
  for (int m = 0; m < 4; ++m) {
    const double angle = 35.0 * m / 3.0 * std::numbers::pi / 180.0;
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, kSweepVector.normalized()).toRotationMatrix();
    sections[static_cast<std::size_t>(m)] = transform_affine(patch, rotation, kSweepVector * (m / 3.0));
  }
  return sections;
}

BSplineVolume twisted_loft() {
  // Four sections and a cubic: the Bézier knot vector, interpolating at equally spaced sites.
  return loft(twisted_loft_sections(), KnotVector::bezier(3), {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0});
}

BSplineCurve curved_loft_path() {
  return BSplineCurve({KnotVector(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1})}, 3,
                      {0.0, 0.0, 0.0, 0.0, 0.0, 1.5, 0.5, 0.8, 3.0, 2.5, 1.2, 4.0, 4.5, 0.8, 4.0});
}

std::array<BSplineSurface, 5> curved_loft_sections() {
  const BSplineSurface patch = paper_example_patch();
  const BSplineCurve path = curved_loft_path();
  const std::vector<double> sites{0.0, 0.25, 0.5, 0.75, 1.0};
  const auto frames = rotation_minimizing_frames(path, sites);
  const auto start = path.evaluate({0.0});
  const Eigen::Vector3d c0(start[0], start[1], start[2]);
  std::array<BSplineSurface, 5> sections{patch, patch, patch, patch, patch};
  for (std::size_t m = 0; m < 5; ++m) {
    const auto x = path.evaluate({sites[m]});
    // A rigid motion taking the start frame to the frame at t_m, applied to the patch as placed
    // at the start: x -> c(t_m) + R_m R_0^T (x - c(0)).
    const Eigen::Matrix3d rotation = frames[m] * frames[0].transpose();
    sections[m] = transform_affine(patch, rotation, Eigen::Vector3d(x[0], x[1], x[2]) - rotation * c0);
  }
  return sections;
}

BSplineVolume curved_loft() {
  return loft(curved_loft_sections(), KnotVector(3, {0, 0, 0, 0, 0.5, 1, 1, 1, 1}), {0.0, 0.25, 0.5, 0.75, 1.0});
}

}  // namespace volspline
