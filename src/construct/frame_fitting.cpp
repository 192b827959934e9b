#include "volspline/construct/frame_fitting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "path_geometry.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using namespace detail;

// A path that is a single point makes every sweep flat (zero volume).
void require_nonzero_length(const BSplineCurve& path) {
  const int n = path.num_control_points_total();
  const double tol = 1e-14 * path_scale(path);
  Vector3d first = Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (int i = 0; i < n; ++i) {
    const Vector3d p = Eigen::Map<const Vector3d>(&path.points()[static_cast<std::size_t>(3 * i)]);
    if (path.is_rational() && path.weights()[static_cast<std::size_t>(i)] == 0.0) {
      if (p.norm() > 0.0) return;  // a point at infinity with a direction: the curve moves
      continue;
    }
    if (std::isnan(first.x())) first = p;
    else if ((p - first).norm() > tol) return;
  }
  throw InvalidInput("the sweep path has zero length (all its control points coincide)");
}

// Rotation-minimising and Frenet frames need a tangent that neither vanishes nor jumps; at
// breakpoints the two one-sided tangents come from the neighbouring Bézier pieces.
void require_continuous_tangent(const BSplineCurve& path) {
  const auto pieces = bezier_pieces(path);
  for (std::size_t s = 0; s + 1 < pieces.size(); ++s) {
    const double t = pieces[s].domain_max(0);
    const Vector3d left = derivatives_at(pieces[s], t, 1)[1], right = derivatives_at(pieces[s + 1], t, 1)[1];
    if (!(left.norm() > speed_floor(path)) || !(right.norm() > speed_floor(path)))
      throw InvalidInput("the sweep path's tangent vanishes at w = " + format_double(t) + ": no frame is defined there");
    if ((left.normalized() - right.normalized()).norm() > 1e-9)
      throw InvalidInput("the sweep path's tangent jumps at w = " + format_double(t) + ": a moving frame needs a G1 path");
  }
}

// The Frenet frame must exist on the whole path, not only at the fit's samples: on a fine
// sampling, a zero curvature throws in frenet_frame, and a binormal (or tangent) that reverses
// between neighbouring samples means the curvature (or the speed) passed through zero there.
void require_frenet_frame(const BSplineCurve& path) {
  const double a = path.domain_min(0), b = path.domain_max(0);
  std::vector<double> samples;
  for (int i = 0; i <= 4096; ++i) samples.push_back(a + (b - a) * i / 4096.0);
  const auto breaks = path.knot_vector(0).breakpoints();
  samples.insert(samples.end(), breaks.begin(), breaks.end());
  std::sort(samples.begin(), samples.end());
  Matrix3d previous = frenet_frame(path, samples.front());
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Matrix3d f = frenet_frame(path, samples[i]);
    if (f.col(1).dot(previous.col(1)) < 0.0 || f.col(2).dot(previous.col(2)) < 0.0)
      throw InvalidInput("the sweep path's curvature vanishes between its parameters " + format_double(samples[i - 1]) + " and " +
                         format_double(samples[i]) + ": the Frenet frame is undefined there");
    previous = f;
  }
  // The Frenet frame depends on c'', which may jump at a breakpoint: compare the one-sided
  // frames of the neighbouring Bézier pieces.
  const auto pieces = bezier_pieces(path);
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    const double t = pieces[i].domain_max(0);
    if ((frenet_frame(pieces[i], t) - frenet_frame(pieces[i + 1], t)).cwiseAbs().maxCoeff() > 1e-9)
      throw InvalidInput("the sweep path's Frenet frame jumps at w = " + format_double(t) +
                         " (its curvature vector changes direction there); use the rotation-minimising frame");
  }
}

// The frame is less smooth than the path at its breakpoints: where the path is C^k, its tangent
// is C^(k-1), the rotation-minimising frame (r' = -(r . t') t) C^(k-1) and the Frenet frame,
// built from c'', C^(k-2). Interpolating it with the path's own continuity would force a
// smoothness it lacks and the fit would converge like O(h) instead of O(h^(p+1)), so those
// knots get one (RMF) or two (Frenet) more copies, keeping at least C^0.
BSplineCurve frame_knots(const BSplineCurve& path, SweepFrame frame) {
  const KnotVector& kv = path.knot_vector(0);
  const int p = kv.degree(), extra = frame == SweepFrame::Frenet ? 2 : 1;
  const auto breaks = kv.breakpoints();
  std::vector<double> insert;
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    const int m = kv.multiplicity(breaks[i]);
    for (int k = m; k < std::min(p, m + extra); ++k) insert.push_back(breaks[i]);
  }
  return insert.empty() ? path : refine_knots(path, 0, insert);
}
// R = I exactly: numerators gamma(w) e_a, i.e. the path's weights times e_a, which is Lasser's
// translation matrix M_k of Theorem 1 once the sweep multiplies it out.
SweepFrameFit identity_frame(const BSplineCurve& current) {
  SweepFrameFit fit{{current, current, current}, current, 0.0, 0.0, current.knot_vector(0).num_spans()};
  const int n = current.num_control_points_total();
  for (int col = 0; col < 3; ++col) {
    std::vector<double> h;
    for (int i = 0; i < n; ++i) {
      const double w = current.is_rational() ? current.weights()[static_cast<std::size_t>(i)] : 1.0;
      for (int e = 0; e < 3; ++e) h.push_back(e == col ? w : 0.0);
      if (current.is_rational()) h.push_back(w);
    }
    fit.curves[static_cast<std::size_t>(col)] =
        BSplineCurve::from_homogeneous({current.knot_vector(0)}, 3, current.is_rational(), std::move(h));
  }
  return fit;
}

// One fit on the knots of `current`: the exact frame interpolated at the Greville abscissae,
// its errors measured at five check points per span.
SweepFrameFit interpolate_frame(const BSplineCurve& current, SweepFrame frame, const Matrix3d& start) {
  const KnotVector& kv = current.knot_vector(0);
  const int p = kv.degree(), n = kv.num_basis();
  const std::vector<double> sites = kv.greville_abscissae();
  const auto breaks = kv.breakpoints();
  std::vector<double> checks;
  for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
    for (double f : {0.125, 0.375, 0.5, 0.625, 0.875}) checks.push_back(breaks[s] + f * (breaks[s + 1] - breaks[s]));
  std::vector<double> all = sites;
  all.insert(all.end(), checks.begin(), checks.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());

  std::vector<Matrix3d> exact;
  if (frame == SweepFrame::RotationMinimizing) {
    exact = rotation_minimizing_frames(current, all, start);
  } else {
    for (double t : all) exact.push_back(frenet_frame(current, t));
  }
  auto exact_at = [&](double t) {
    return exact[static_cast<std::size_t>(std::lower_bound(all.begin(), all.end(), t) - all.begin())];
  };

  // Interpolate the numerators gamma(w) R(w) at the Greville abscissae with the path's own
  // weights as denominators: the frame curves then share the path's weight function, so
  // the sweep's common denominator is the path's and its degree stays deg(path).
  Eigen::SparseMatrix<double> collocation(n, n);
  std::vector<Eigen::Triplet<double>> entries;
  MatrixXd rhs(n, 9);
  std::vector<double> basis(static_cast<std::size_t>(p + 1));
  for (int j = 0; j < n; ++j) {
    const double t = sites[static_cast<std::size_t>(j)];
    const int span = kv.find_span(t);
    kv.basis(span, t, basis.data());
    double gamma = 0.0;
    for (int r = 0; r <= p; ++r) {
      entries.emplace_back(j, span - p + r, basis[static_cast<std::size_t>(r)]);
      if (current.is_rational()) gamma += basis[static_cast<std::size_t>(r)] * current.weights()[static_cast<std::size_t>(span - p + r)];
    }
    if (!current.is_rational()) gamma = 1.0;
    const Matrix3d f = exact_at(t);
    for (int col = 0; col < 3; ++col) rhs.block(j, 3 * col, 1, 3) = gamma * f.col(col).transpose();
  }
  collocation.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(collocation);
  if (lu.info() != Eigen::Success) throw Error("sweep: the frame interpolation matrix is singular");
  const MatrixXd numerators = lu.solve(rhs);

  SweepFrameFit fit{{current, current, current}, current, 0.0, 0.0, kv.num_spans()};
  for (int col = 0; col < 3; ++col) {
    std::vector<double> h;
    for (int i = 0; i < n; ++i) {
      for (int e = 0; e < 3; ++e) h.push_back(numerators(i, 3 * col + e));
      if (current.is_rational()) h.push_back(current.weights()[static_cast<std::size_t>(i)]);
    }
    fit.curves[static_cast<std::size_t>(col)] = BSplineCurve::from_homogeneous({kv}, 3, current.is_rational(), std::move(h));
  }
  for (double t : checks) {
    const Matrix3d r = evaluate_frame(fit.curves, t);
    fit.orthonormality_error = std::max(fit.orthonormality_error, (r.transpose() * r - Matrix3d::Identity()).cwiseAbs().maxCoeff());
    fit.frame_error = std::max(fit.frame_error, (r - exact_at(t)).cwiseAbs().maxCoeff());
  }
  return fit;
}

}  // namespace

SweepFrameFit fit_sweep_frame(const BSplineCurve& path, SweepFrame frame, double tolerance) {
  require_dimension(path.dimension(), "the sweep path");
  if (!(tolerance > 0.0)) throw InvalidInput("the frame tolerance must be positive, got " + format_double(tolerance));
  require_nonzero_length(path);
  if (frame != SweepFrame::Fixed) require_continuous_tangent(path);
  const double a = path.domain_min(0);
  BSplineCurve current = clamp(frame == SweepFrame::Fixed ? path : frame_knots(path, frame));
  if (frame == SweepFrame::Fixed) return identity_frame(current);
  if (frame == SweepFrame::Frenet) require_frenet_frame(path);
  Matrix3d start = Matrix3d::Zero();
  if (frame == SweepFrame::RotationMinimizing) start = rotation_minimizing_frames(path, {a}).front();

  for (int halvings = 0; halvings <= 12; ++halvings) {
    SweepFrameFit fit = interpolate_frame(current, frame, start);
    if (fit.orthonormality_error <= tolerance) return fit;
    const auto breaks = current.knot_vector(0).breakpoints();
    std::vector<double> midpoints;
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s) midpoints.push_back(0.5 * (breaks[s] + breaks[s + 1]));
    current = refine_knots(current, 0, midpoints);
  }
  throw NotConverged("the sweep frame fit did not reach the orthonormality tolerance " + format_double(tolerance) +
                     " after 12 halvings of the path's spans");
}

}  // namespace volspline
