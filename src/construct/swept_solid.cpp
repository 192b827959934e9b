#include "volspline/construct/swept_solid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "path_geometry.h"
#include "piecewise_bernstein.h"
#include "volspline/analysis/jacobian_bezier.h"
#include "volspline/construct/sweep.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/reparameterization.h"

namespace volspline {

namespace {

using namespace detail;
using Eigen::Vector3d;

BSplineCurve on_unit_interval(const BSplineCurve& curve) {
  if (curve.domain_min(0) == 0.0 && curve.domain_max(0) == 1.0) return curve;
  return reparameterize(curve, 0, 0.0, 1.0);
}

// R = I as three linear curves that are constant.
std::array<BSplineCurve, 3> identity_frame() {
  const KnotVector line(1, {0.0, 0.0, 1.0, 1.0});
  auto column = [&](int i) {
    std::vector<double> points(6, 0.0);
    points[static_cast<std::size_t>(i)] = points[static_cast<std::size_t>(3 + i)] = 1.0;
    return BSplineCurve({line}, 3, std::move(points));
  };
  return {column(0), column(1), column(2)};
}

// The rotation about the unit axis a by theta(t), 0 -> total, as rational quadratic curves. The
// column R(theta) e_i = P_i + cos(theta) Q_i + sin(theta) S_i with P_i = (e_i . a) a,
// Q_i = e_i - P_i, S_i = a x e_i is an affine image of the unit circle (cos, sin); each arc of
// angle phi <= 90 degrees is the circle's rational quadratic with weights 1, cos(phi / 2), 1,
// whose middle control point is where the end tangents meet (construct/conic_arc.h). All three
// columns share those weights, so the sweep puts them over one denominator.
std::array<BSplineCurve, 3> rotation_frame(const Vector3d& axis, double total_degrees) {
  const int arcs = static_cast<int>(std::ceil(std::abs(total_degrees) / 90.0));
  if (arcs == 0) return identity_frame();
  const double phi = total_degrees / arcs * std::numbers::pi / 180.0;
  std::vector<double> knots(3, 0.0);
  for (int k = 1; k < arcs; ++k) knots.insert(knots.end(), 2, static_cast<double>(k) / arcs);
  knots.insert(knots.end(), 3, 1.0);
  const KnotVector kv(2, std::move(knots));
  // (cos, sin) control points of the circle and their weights, 2 arcs + 1 of them.
  std::vector<Eigen::Vector2d> circle;
  std::vector<double> weights;
  for (int k = 0; k < arcs; ++k) {
    const double start = total_degrees * k / arcs * std::numbers::pi / 180.0;
    circle.emplace_back(std::cos(start), std::sin(start));
    const double middle = start + 0.5 * phi;
    circle.emplace_back(Eigen::Vector2d(std::cos(middle), std::sin(middle)) / std::cos(0.5 * phi));
    weights.push_back(1.0);
    weights.push_back(std::cos(0.5 * phi));
  }
  circle.emplace_back(std::cos(total_degrees * std::numbers::pi / 180.0), std::sin(total_degrees * std::numbers::pi / 180.0));
  weights.push_back(1.0);
  std::array<BSplineCurve, 3> frame = identity_frame();
  for (int i = 0; i < 3; ++i) {
    const Vector3d e = Vector3d::Unit(i);
    const Vector3d p = e.dot(axis) * axis, q = e - p, s = axis.cross(e);
    std::vector<double> points;
    for (const auto& cs : circle) {
      const Vector3d x = p + cs.x() * q + cs.y() * s;
      points.insert(points.end(), {x.x(), x.y(), x.z()});
    }
    frame[static_cast<std::size_t>(i)] = BSplineCurve({kv}, 3, std::move(points), weights);
  }
  return frame;
}

// A parameter where det R vanishes, to the 6 digits a double root can be located to.
std::string text(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", t);
  return buffer;
}

// Certifies the sign of the scalar Bernstein polynomial f on [lo, hi] (a span's local [0, 1]
// mapped there), halving where its coefficients' signs are mixed.
struct DeterminantSign {
  double noise;  // below this, a coefficient's sign is not trusted
  int sign = 0;  // the sign found so far

  void certify(const BernsteinTensor<1>& f, double lo, double hi) {
    const auto [lowest, highest] = bernstein_coefficient_range(f);
    const double first = f.coefficients.front(), last = f.coefficients.back();
    // The end coefficients are the values at the ends.
    if (std::abs(first) <= noise) vanishes_at(lo);
    if (std::abs(last) <= noise) vanishes_at(hi);
    if ((first > 0) != (last > 0)) {
      // A sign change: the root by bisection of the polynomial itself.
      double a = 0.0, b = 1.0;
      while (b - a > 1e-12) {
        const double m = 0.5 * (a + b);
        ((bernstein_evaluate(f, {m}) > 0) == (first > 0) ? a : b) = m;
      }
      vanishes_at(lo + 0.5 * (a + b) * (hi - lo));
    }
    if (lowest > noise || highest < -noise) {
      note(lowest > noise ? 1 : -1, lo);
      return;
    }
    if (std::max(std::abs(lowest), std::abs(highest)) <= noise || hi - lo <= 1e-9) vanishes_at(0.5 * (lo + hi));
    const auto [left, right] = bernstein_split(f, 0, 0.5);
    const double mid = 0.5 * (lo + hi);
    certify(left, lo, mid);
    certify(right, mid, hi);
  }

  void note(int s, double t) {
    if (sign != 0 && s != sign) {
      throw InvalidInput("det R(t) = b(t) . (n(t) x t(t)) changes sign at t = " + text(t) + " (the frame is singular there)",
                         "frame");
    }
    sign = s;
  }

  [[noreturn]] static void vanishes_at(double t) {
    throw InvalidInput("det R(t) = b(t) . (n(t) x t(t)) vanishes at t = " + text(t) +
                           ": the frame curves are linearly dependent there",
                       "frame");
  }
};

// The largest |control point| of a curve's homogeneous numerator (its finite scale).
double numerator_scale(const PiecewiseBernstein& f) {
  double m = 0.0;
  for (const auto& piece : f) m = std::max(m, bernstein_max_abs(piece));
  return m;
}

BernsteinTensor<1> negated(BernsteinTensor<1> f) {
  for (double& x : f.coefficients) x = -x;
  return f;
}

}  // namespace

int require_nonsingular_frame(const std::array<BSplineCurve, 3>& frame) {
  for (std::size_t k = 0; k < 3; ++k) require_dimension(frame[k].dimension(), "frame curve " + std::to_string(k));
  const double a = frame[0].domain_min(0), b = frame[0].domain_max(0);
  for (std::size_t k = 1; k < 3; ++k) {
    if (frame[k].domain_min(0) != a || frame[k].domain_max(0) != b)
      throw InvalidInput("frame curve " + std::to_string(k) + " has another domain than frame curve 0", "frame");
  }
  const auto [breaks, smoothness] = merged_breakpoints({&frame[0], &frame[1], &frame[2]});
  std::array<PiecewiseBernstein, 3> numerators;
  double scale = 1.0;
  for (std::size_t k = 0; k < 3; ++k) {
    numerators[k] = components(homogeneous_pieces(frame[k], breaks), 0, 3);
    scale *= numerator_scale(numerators[k]);
  }
  // det = b . (n x t) has Bernstein coefficients that are convex combinations of products of
  // coefficients, each rounded a few times: 1e-12 of the product of the scales is far above the
  // rounding and far below any frame one would want to sweep with.
  DeterminantSign sign{1e-12 * scale};
  for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
    std::array<std::array<BernsteinTensor<1>, 3>, 3> x;  // x[k][c]: component c of curve k
    for (std::size_t k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) x[k][static_cast<std::size_t>(c)] = bernstein_components(numerators[k][s], c, 1);
    BernsteinTensor<1> det;
    for (int c = 0; c < 3; ++c) {
      const std::size_t c1 = static_cast<std::size_t>((c + 1) % 3), c2 = static_cast<std::size_t>((c + 2) % 3);
      BernsteinTensor<1> cross = bernstein_product(x[1][c1], x[2][c2]);
      bernstein_add(cross, negated(bernstein_product(x[1][c2], x[2][c1])));
      BernsteinTensor<1> term = bernstein_product(x[0][static_cast<std::size_t>(c)], cross);
      if (c == 0) det = std::move(term);
      else bernstein_add(det, term);
    }
    sign.certify(det, breaks[s], breaks[s + 1]);
  }
  return sign.sign;
}

// A generator patch whose Jacobian vanishes identically (all its points in a plane or on a curve)
// is no volume: its sweep has no interior and the envelope's superset is undefined (Conkey–Joy
// §3 assume a solid). Certified on the Bernstein coefficients of J (or w^4 J) of every Bézier
// piece: all within their rounding bound of zero (and of 1e-12 of the box's size cubed, times
// the largest weight to the fourth for rational patches, over the domain's volume).
bool jacobian_vanishes_identically(const BSplineVolume& patch) {
  Eigen::AlignedBox3d box;
  const auto& p = patch.points();
  for (std::size_t i = 0; i + 2 < p.size(); i += 3) box.extend(Eigen::Vector3d(p[i], p[i + 1], p[i + 2]));
  // The largest weight (1 for a polynomial patch): scaling all weights alike changes nothing.
  double weight = patch.weights().empty() ? 1.0 : 0.0;
  for (double w : patch.weights()) weight = std::max(weight, std::abs(w));
  const double size = box.diagonal().norm();
  // J is taken with respect to the patch's own parameters: a domain of length L per direction
  // scales it by 1 / (L_u L_v L_w).
  double lengths = 1;
  for (int d = 0; d < 3; ++d) lengths *= patch.domain_max(d) - patch.domain_min(d);
  const double input_error = extraction_error_bound(patch);
  for (const BSplineVolume& piece : bezier_pieces(patch)) {
    const JacobianBernstein j = jacobian_bezier_coefficients(piece, input_error);
    const double floor = std::max(j.error_bound, 1e-12 * size * size * size * std::pow(weight, 4) / lengths);
    for (double c : j.coefficients.coefficients)
      if (std::abs(c) > floor) return false;
  }
  return true;
}

SweptSolid make_swept_solid(std::vector<BSplineVolume> generator, BSplineCurve path, const SweptSolidFrame& frame) {
  if (generator.empty()) throw InvalidInput("expected at least one generator patch, got none", "generator");
  for (std::size_t i = 0; i < generator.size(); ++i) {
    try {
      require_dimension(generator[i].dimension(), "a generator patch");
      if (jacobian_vanishes_identically(generator[i]))
        throw InvalidInput("a generator patch must be a volume; this one's Jacobian vanishes identically (its points lie in a plane or "
                           "on a curve)");
    } catch (const InvalidInput& e) {
      throw e.located("generator[" + std::to_string(i) + "]");
    }
  }
  try {
    require_dimension(path.dimension(), "the path");
  } catch (const InvalidInput& e) {
    throw e.located("path");
  }
  BSplineCurve unit_path = on_unit_interval(path);
  std::array<BSplineCurve, 3> curves = identity_frame();
  std::string name = "fixed";
  double fit_error = 0.0;
  switch (frame.kind) {
    case SweptSolidFrame::Kind::Fixed:
      break;
    case SweptSolidFrame::Kind::Frenet:
    case SweptSolidFrame::Kind::RotationMinimizing: {
      const bool frenet = frame.kind == SweptSolidFrame::Kind::Frenet;
      const SweepFrameFit fit = fit_sweep_frame(unit_path, frenet ? SweepFrame::Frenet : SweepFrame::RotationMinimizing, frame.tolerance);
      curves = fit.curves;
      name = frenet ? "frenet" : "rmf";
      fit_error = fit.orthonormality_error;
      break;
    }
    case SweptSolidFrame::Kind::Rotation: {
      const double length = frame.axis.norm();
      if (!std::isfinite(length) || length == 0.0)
        throw InvalidInput("expected a nonzero finite rotation axis", "frame.rotate.axis");
      if (!(std::abs(frame.degrees) <= kMaxRotationDegrees))
        throw InvalidInput("expected an angle of at most " + format_double(kMaxRotationDegrees) + " degrees (100 turns), got " +
                               format_double(frame.degrees),
                           "frame.rotate.degrees");
      curves = rotation_frame(frame.axis / length, frame.degrees);
      name = "rotate";
      break;
    }
    case SweptSolidFrame::Kind::Curves: {
      if (frame.curves.size() != 3)
        throw InvalidInput("expected three frame curves (b, n, t), got " + std::to_string(frame.curves.size()), "frame.curves");
      for (std::size_t k = 0; k < 3; ++k) {
        try {
          require_dimension(frame.curves[k].dimension(), "a frame curve");
        } catch (const InvalidInput& e) {
          throw e.located("frame.curves[" + std::to_string(k) + "]");
        }
        curves[k] = on_unit_interval(frame.curves[k]);
      }
      name = "curves";
      break;
    }
  }
  require_nonsingular_frame(curves);
  return SweptSolid{std::move(generator), std::move(unit_path), std::move(curves), std::move(name), fit_error};
}

BSplineHypervolume swept_patch(const SweptSolid& solid, std::size_t patch) {
  if (patch >= solid.generator.size())
    throw InvalidInput("no generator patch " + std::to_string(patch) + " (the solid has " +
                       std::to_string(solid.generator.size()) + ")");
  return sweep_with_frame_curves(solid.generator[patch], solid.path, solid.frame);
}

std::vector<BSplineHypervolume> swept_patches(const SweptSolid& solid) {
  std::vector<BSplineHypervolume> patches;
  patches.reserve(solid.generator.size());
  for (std::size_t i = 0; i < solid.generator.size(); ++i) patches.push_back(swept_patch(solid, i));
  return patches;
}

Eigen::Matrix3d swept_frame_at(const SweptSolid& solid, double t) {
  if (!(t >= 0.0 && t <= 1.0)) throw InvalidInput("expected t in [0, 1], got " + format_double(t), "t");
  return evaluate_frame(solid.frame, t);
}

}  // namespace volspline
