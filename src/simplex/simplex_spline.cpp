// Single simplex splines: the unmemoised reference recurrence, the memoised jet, line integrals
// and the bivariate splines of the projection identity (docs/simplex-splines.md).
#include "volspline/simplex/simplex_spline.h"

#include <array>
#include <cmath>
#include <string>

#include "simplex_recurrence.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using simplex_detail::BarycentricChoice;
using simplex_detail::BarycentricFrame;
using simplex_detail::KnotBinding;
using simplex_detail::KnotMask;

constexpr int kMaxTrivariateKnots = kMaxSimplexSplineDegree + 4;
constexpr int kMaxBivariateKnots = kMaxSimplexSplineDegree + 5;

void check_knot_count(std::size_t count) {
  if (count < 4 || count > static_cast<std::size_t>(kMaxTrivariateKnots)) {
    throw InvalidInput("a trivariate simplex spline needs 4.." + std::to_string(kMaxTrivariateKnots) +
                       " knots (degree 0.." + std::to_string(kMaxSimplexSplineDegree) + "), got " +
                       std::to_string(count));
  }
}

KnotMask all_knots(std::size_t count) { return (KnotMask{1} << count) - 1; }

void check_finite(const Eigen::Vector3d& v, const char* what) {
  if (!v.allFinite()) throw InvalidInput(std::string(what) + " must be finite");
}

void check_finite(std::span<const Eigen::Vector3d> knots) {
  for (const auto& k : knots) {
    if (!k.allFinite()) throw InvalidInput("simplex spline knots must be finite");
  }
}

// Eq. 1 without memoisation over the knots of `subset`.
double reference_value(const Eigen::Vector3d& x, int knot,
                       const std::array<Eigen::Vector3d, kMaxTrivariateKnots>& knots, const KnotBinding& binding,
                       KnotMask subset) {
  std::array<int, simplex_detail::kMaxRecurrenceKnots> idx{};
  const int count = simplex_detail::subset_indices(subset, idx);
  if (count == 4) {
    BarycentricFrame frame;
    const auto& a = knots[idx[0]];
    const auto& b = knots[idx[1]];
    const auto& c = knots[idx[2]];
    const auto& d = knots[idx[3]];
    if (!simplex_detail::make_frame(a, b, c, d, frame)) return 0;
    return simplex_detail::half_open_contains(simplex_detail::face_barycentric(x, a, b, c, d, frame.det), x, knot >= 0,
                                              a, b, c, d)
               ? 1.0 / std::abs(frame.det)
               : 0.0;
  }
  std::array<int, 4> w{};
  BarycentricFrame frame;
  if (!binding.choose(subset, &x, w, frame)) return 0;
  auto l = simplex_detail::face_barycentric(x, knots[w[0]], knots[w[1]], knots[w[2]], knots[w[3]], frame.det);
  if (knot >= 0) simplex_detail::snap_to_knot(l, w, knot);
  double v = 0;
  for (int j = 0; j < 4; ++j) {
    if (l[j] != 0) v += l[j] * reference_value(x, knot, knots, binding, subset & ~(KnotMask{1} << w[j]));
  }
  return v;
}

// The bivariate analogue of BarycentricFrame: λ_j(y) = g[j]·(y - origin) + [j == 0].
struct PlanarFrame {
  Eigen::Vector2d origin;
  std::array<Eigen::Vector2d, 3> g;
  double det = 0;
};

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

bool make_planar_frame(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       PlanarFrame& frame) {
  const Eigen::Vector2d e1 = b - a;
  const Eigen::Vector2d e2 = c - a;
  const double det = cross2(e1, e2);
  if (det == 0) return false;
  // Rounding can make collinear knots look independent: the exact predicate decides when close.
  if (det * det <= 1e-20 * e1.squaredNorm() * e2.squaredNorm() && simplex_detail::exactly_collinear(a, b, c)) {
    return false;
  }
  frame.origin = a;
  frame.det = det;
  frame.g[1] = Eigen::Vector2d(e2.y(), -e2.x()) / det;
  frame.g[2] = Eigen::Vector2d(-e1.y(), e1.x()) / det;
  frame.g[0] = -(frame.g[1] + frame.g[2]);
  return true;
}

double bivariate_value(const Eigen::Vector2d& y, const std::array<Eigen::Vector2d, kMaxBivariateKnots>& knots,
                       KnotMask subset) {
  std::array<int, simplex_detail::kMaxRecurrenceKnots> idx{};
  const int count = simplex_detail::subset_indices(subset, idx);
  if (count == 3) {
    PlanarFrame frame;
    if (!make_planar_frame(knots[idx[0]], knots[idx[1]], knots[idx[2]], frame)) return 0;
    return in_half_open_triangle(y, knots[idx[0]], knots[idx[1]], knots[idx[2]]) ? 1.0 / std::abs(frame.det) : 0.0;
  }
  // Three knots containing y, the largest |det| among them (the largest overall if none does).
  std::array<int, 3> w{};
  PlanarFrame best;
  bool found = false;
  bool best_contains = false;
  double best_size = 0;
  for (int i0 = 0; i0 < count; ++i0) {
    for (int i1 = i0 + 1; i1 < count; ++i1) {
      for (int i2 = i1 + 1; i2 < count; ++i2) {
        PlanarFrame candidate;
        if (!make_planar_frame(knots[idx[i0]], knots[idx[i1]], knots[idx[i2]], candidate)) continue;
        const Eigen::Vector2d r = y - candidate.origin;
        const double l1 = candidate.g[1].dot(r);
        const double l2 = candidate.g[2].dot(r);
        const bool contains = l1 >= 0 && l2 >= 0 && 1 - l1 - l2 >= 0;
        const double size = std::abs(candidate.det);
        if (found && (contains < best_contains || (contains == best_contains && size <= best_size))) continue;
        found = true;
        best = candidate;
        best_contains = contains;
        best_size = size;
        w = {idx[i0], idx[i1], idx[i2]};
      }
    }
  }
  if (!found) return 0;  // all knots collinear: a measure-zero distribution
  const Eigen::Vector2d r = y - best.origin;
  const double l1 = best.g[1].dot(r);
  const double l2 = best.g[2].dot(r);
  const std::array<double, 3> l = {1 - l1 - l2, l1, l2};
  double v = 0;
  for (int j = 0; j < 3; ++j) {
    if (l[j] != 0) v += l[j] * bivariate_value(y, knots, subset & ~(KnotMask{1} << w[j]));
  }
  return v;
}

// The memoised recurrences of one thread, reused so that their tables are allocated once.
struct ThreadRecurrences {
  KnotBinding binding;
  simplex_detail::PointRecurrence point;
  simplex_detail::LineRecurrence line;
  ThreadRecurrences() {
    point.attach(&binding, 1 << kMaxTrivariateKnots);
    line.attach(&binding, 1 << kMaxTrivariateKnots);
  }
};

ThreadRecurrences& thread_recurrences() {
  thread_local ThreadRecurrences recurrences;
  return recurrences;
}

}  // namespace

double simplex_spline_value(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots) {
  check_knot_count(knots.size());
  check_finite(knots);
  check_finite(x, "the point");
  std::array<Eigen::Vector3d, kMaxTrivariateKnots> copy{};
  std::copy(knots.begin(), knots.end(), copy.begin());
  KnotBinding binding;
  binding.bind(copy.data(), static_cast<int>(knots.size()), BarycentricChoice::kContainingThenLargest);
  const int knot = simplex_detail::knot_at(x, copy.data(), static_cast<int>(knots.size()));
  return reference_value(x, knot, copy, binding, all_knots(knots.size()));
}

SimplexSplineJet simplex_spline_jet(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots, int order) {
  check_knot_count(knots.size());
  check_finite(knots);
  check_finite(x, "the point");
  if (order < 0 || order > 2) throw InvalidInput("derivative order must be 0, 1 or 2, got " + std::to_string(order));
  auto& r = thread_recurrences();
  r.binding.bind(knots.data(), static_cast<int>(knots.size()), BarycentricChoice::kContainingThenLargest);
  r.point.set_point(x);
  return r.point.jet(all_knots(knots.size()), order);
}

double simplex_spline_directional_derivative(const Eigen::Vector3d& x, std::span<const Eigen::Vector3d> knots,
                                             const Eigen::Vector3d& v) {
  check_knot_count(knots.size());
  check_finite(knots);
  check_finite(x, "the point");
  check_finite(v, "the direction");
  auto& r = thread_recurrences();
  r.binding.bind(knots.data(), static_cast<int>(knots.size()), BarycentricChoice::kContainingThenLargest);
  r.point.set_point(x);
  return r.point.directional_derivative(all_knots(knots.size()), v);
}

double bivariate_simplex_spline_value(const Eigen::Vector2d& y, std::span<const Eigen::Vector2d> knots) {
  if (knots.size() < 3 || knots.size() > static_cast<std::size_t>(kMaxBivariateKnots)) {
    throw InvalidInput("a bivariate simplex spline needs 3.." + std::to_string(kMaxBivariateKnots) + " knots, got " +
                       std::to_string(knots.size()));
  }
  if (!y.allFinite()) throw InvalidInput("the point must be finite");
  for (const auto& k : knots) {
    if (!k.allFinite()) throw InvalidInput("simplex spline knots must be finite");
  }
  std::array<Eigen::Vector2d, kMaxBivariateKnots> copy{};
  std::copy(knots.begin(), knots.end(), copy.begin());
  return bivariate_value(y, copy, all_knots(knots.size()));
}

double simplex_spline_line_integral(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double a,
                                    double b, std::span<const Eigen::Vector3d> knots) {
  check_knot_count(knots.size());
  check_finite(knots);
  check_finite(origin, "the line's origin");
  check_finite(direction, "the line's direction");
  if (!(a <= b)) throw InvalidInput("line integral bounds must satisfy a <= b");
  auto& r = thread_recurrences();
  r.binding.bind(knots.data(), static_cast<int>(knots.size()), BarycentricChoice::kLargest);
  r.line.set_line(origin, direction, a, b);
  return r.line.integral(all_knots(knots.size()));
}

double simplex_spline_full_line_integral_by_projection(const Eigen::Vector3d& x, const Eigen::Vector3d& d,
                                                       std::span<const Eigen::Vector3d> knots) {
  check_knot_count(knots.size());
  check_finite(knots);
  check_finite(x, "the point");
  const double length = d.norm();
  if (!(length > 0) || !std::isfinite(length)) throw InvalidInput("line direction must be nonzero and finite");
  const Eigen::Vector3d u = d / length;
  // An orthonormal basis (e1, e2) of u^⊥, from the coordinate axis least aligned with u.
  Eigen::Index axis = 0;
  u.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d e1 = u.cross(Eigen::Vector3d::Unit(axis)).normalized();
  const Eigen::Vector3d e2 = u.cross(e1);
  std::array<Eigen::Vector2d, kMaxTrivariateKnots> projected{};
  for (std::size_t i = 0; i < knots.size(); ++i) projected[i] = Eigen::Vector2d(e1.dot(knots[i]), e2.dot(knots[i]));
  const int degree = static_cast<int>(knots.size()) - 4;
  const double m2 = bivariate_simplex_spline_value(Eigen::Vector2d(e1.dot(x), e2.dot(x)),
                                                   std::span<const Eigen::Vector2d>(projected.data(), knots.size()));
  return m2 / ((degree + 1) * length);
}

}  // namespace volspline
