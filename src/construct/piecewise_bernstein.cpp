#include "piecewise_bernstein.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline::detail {

namespace {

int degree_of(const PiecewiseBernstein& f) { return f.front().degrees[0]; }

double max_abs(const PiecewiseBernstein& f) {
  double m = 0.0;
  for (const auto& piece : f) m = std::max(m, bernstein_max_abs(piece));
  return m;
}

// The knots of the B-spline of degree q with continuity smoothness[i] at breaks[i], and for each
// knot the piece that starts there.
std::pair<std::vector<double>, std::vector<int>> knots_for(int q, const std::vector<double>& breaks,
                                                           const std::vector<int>& smoothness) {
  std::vector<double> knots(static_cast<std::size_t>(q + 1), breaks.front());
  std::vector<int> span_of_knot(static_cast<std::size_t>(q + 1), 0);
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i) {
    const int mult = std::clamp(q - smoothness[i], 1, q + 1);
    knots.insert(knots.end(), static_cast<std::size_t>(mult), breaks[i]);
    span_of_knot.insert(span_of_knot.end(), static_cast<std::size_t>(mult), static_cast<int>(i));
  }
  knots.insert(knots.end(), static_cast<std::size_t>(q + 1), breaks.back());
  span_of_knot.insert(span_of_knot.end(), static_cast<std::size_t>(q + 1), static_cast<int>(breaks.size()) - 1);
  return {std::move(knots), std::move(span_of_knot)};
}

// Smoothness of `curve` at t: C^(p - multiplicity); a value that is no knot imposes nothing.
int continuity(const BSplineCurve& curve, double t) {
  const KnotVector& kv = curve.knot_vector(0);
  const int m = kv.multiplicity(t);
  return m == 0 ? std::numeric_limits<int>::max() : kv.degree() - m;
}

}  // namespace

// The merged breakpoints of the curves, and the smallest continuity of the curves at each.
std::pair<std::vector<double>, std::vector<int>> merged_breakpoints(const std::vector<const BSplineCurve*>& curves) {
  std::vector<double> breaks;
  for (const auto* c : curves) {
    const auto bp = c->knot_vector(0).breakpoints();
    breaks.insert(breaks.end(), bp.begin(), bp.end());
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<int> smoothness(breaks.size(), std::numeric_limits<int>::max());
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
    for (const auto* c : curves) smoothness[i] = std::min(smoothness[i], continuity(*c, breaks[i]));
  return {std::move(breaks), std::move(smoothness)};
}

PiecewiseBernstein homogeneous_pieces(const BSplineCurve& curve, const std::vector<double>& breaks) {
  std::vector<double> missing;
  for (std::size_t i = 1; i + 1 < breaks.size(); ++i)
    if (curve.knot_vector(0).multiplicity(breaks[i]) == 0) missing.push_back(breaks[i]);
  const BSplineCurve refined = missing.empty() ? curve : refine_knots(curve, 0, missing);
  const auto pieces = bezier_pieces(refined);
  if (pieces.size() + 1 != breaks.size()) throw Error("sweep: Bézier extraction gave an unexpected number of pieces");
  PiecewiseBernstein f;
  for (const auto& piece : pieces) {
    // A Bézier piece's homogeneous control points are its Bernstein coefficients.
    BernsteinTensor<1> b({curve.knot_vector(0).degree()}, curve.coefficient_size());
    b.coefficients = piece.homogeneous();
    f.push_back(std::move(b));
  }
  return f;
}

PiecewiseBernstein constant_one(std::size_t spans) {
  BernsteinTensor<1> one({0}, 1);
  one.coefficients[0] = 1.0;
  return PiecewiseBernstein(spans, one);
}

PiecewiseBernstein elevate(const PiecewiseBernstein& f, int q) {
  PiecewiseBernstein e;
  for (const auto& piece : f) e.push_back(bernstein_elevate(piece, {q}));
  return e;
}

PiecewiseBernstein multiply(const PiecewiseBernstein& scalar, const PiecewiseBernstein& f) {
  PiecewiseBernstein r;
  for (std::size_t s = 0; s < f.size(); ++s) r.push_back(bernstein_product(scalar[s], f[s]));
  return r;
}

PiecewiseBernstein components(const PiecewiseBernstein& f, int first, int count) {
  PiecewiseBernstein r;
  for (const auto& piece : f) r.push_back(bernstein_components(piece, first, count));
  return r;
}

bool same_function(const PiecewiseBernstein& a, const PiecewiseBernstein& b) {
  const int q = std::max(degree_of(a), degree_of(b));
  const PiecewiseBernstein ea = elevate(a, q), eb = elevate(b, q);
  const double scale = std::max(max_abs(a), max_abs(b));
  for (std::size_t s = 0; s < ea.size(); ++s) {
    for (std::size_t i = 0; i < ea[s].coefficients.size(); ++i) {
      if (std::abs(ea[s].coefficients[i] - eb[s].coefficients[i]) > 1e-13 * scale) return false;
    }
  }
  return true;
}

std::pair<KnotVector, Eigen::MatrixXd> to_bspline(const PiecewiseBernstein& f, const std::vector<double>& breaks,
                                                  const std::vector<int>& smoothness) {
  const int q = degree_of(f);
  const int components = f.front().components;
  auto [knots, span_of_knot] = knots_for(q, breaks, smoothness);
  KnotVector kv(q, knots);
  const int n = kv.num_basis();
  Eigen::MatrixXd coefficients(n, components);
  std::vector<double> local(static_cast<std::size_t>(q)), value(static_cast<std::size_t>(components));
  for (int i = 0; i < n; ++i) {
    const double* args = &knots[static_cast<std::size_t>(i + 1)];
    double mean = 0.0;
    for (int r = 0; r < q; ++r) mean += args[r];
    mean /= q;
    // Any nonempty span s in [i, i + q] works in exact arithmetic; the one nearest the
    // arguments keeps the blossom an interpolation rather than an extrapolation.
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int s = std::max(i, q); s <= std::min(i + q, n - 1); ++s) {
      if (!(knots[static_cast<std::size_t>(s)] < knots[static_cast<std::size_t>(s + 1)])) continue;
      const double d = std::abs(0.5 * (knots[static_cast<std::size_t>(s)] + knots[static_cast<std::size_t>(s + 1)]) - mean);
      if (d < best_distance) best_distance = d, best = s;
    }
    const std::size_t piece = static_cast<std::size_t>(span_of_knot[static_cast<std::size_t>(best)]);
    const double lo = breaks[piece], hi = breaks[piece + 1];
    for (int r = 0; r < q; ++r) local[static_cast<std::size_t>(r)] = (args[r] - lo) / (hi - lo);
    bernstein_blossom(f[piece], local.data(), value.data());
    for (int c = 0; c < components; ++c) coefficients(i, c) = value[static_cast<std::size_t>(c)];
  }
  return {std::move(kv), std::move(coefficients)};
}

}  // namespace volspline::detail
