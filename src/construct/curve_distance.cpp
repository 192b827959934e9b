#include "curve_distance.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "bernstein_roots.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {

namespace {

// The dot product of two 3-component polynomials as a scalar one.
BernsteinTensor<1> dot(const BernsteinTensor<1>& f, const BernsteinTensor<1>& g) {
  const BernsteinTensor<1> product = bernstein_product(f, g);
  BernsteinTensor<1> sum({product.degrees[0]}, 1);
  for (std::size_t k = 0; k < sum.coefficients.size(); ++k)
    sum.coefficients[k] = product.coefficients[3 * k] + product.coefficients[3 * k + 1] + product.coefficients[3 * k + 2];
  return sum;
}

double max_abs(const BernsteinTensor<1>& f) { return bernstein_max_abs(f); }

}  // namespace

CurveDistance::CurveDistance(const BSplineCurve& curve) : rational_(curve.is_rational()) {
  if (curve.dimension() != 3) {
    throw InvalidInput("expected a curve in 3 dimensions (control points of 3 coordinates), got " +
                       std::to_string(curve.dimension()) + (curve.dimension() == 1 ? " coordinate" : " coordinates"));
  }
  for (const BSplineCurve& bezier : bezier_pieces(curve)) {
    Piece piece;
    const int p = bezier.knot_vector(0).degree();
    piece.homogeneous = BernsteinTensor<1>({p}, bezier.coefficient_size());
    piece.homogeneous.coefficients = bezier.homogeneous();
    const BernsteinTensor<1> position = bernstein_components(piece.homogeneous, 0, 3);
    const BernsteinTensor<1> velocity = bernstein_derivative(position, 0);
    if (rational_) {
      const BernsteinTensor<1> w = bernstein_components(piece.homogeneous, 3, 1);
      BernsteinTensor<1> t = bernstein_product(velocity, w);
      BernsteinTensor<1> minus = bernstein_product(position, bernstein_derivative(w, 0));
      for (double& v : minus.coefficients) v = -v;
      bernstein_add(t, minus);
      piece.a = dot(position, t);
      piece.b = bernstein_product(t, w);
    } else {
      piece.a = dot(position, velocity);
      piece.b = bernstein_elevate(velocity, {piece.a.degrees[0]});
    }
    piece.a_max = max_abs(piece.a);
    piece.b_max = max_abs(piece.b);
    const std::vector<double>& weights = bezier.weights();
    if (std::all_of(weights.begin(), weights.end(), [](double w) { return w > 0; })) {
      const std::vector<double>& points = bezier.points();
      for (std::size_t i = 0; i < points.size(); i += 3) piece.box.extend(Eigen::Vector3d(points[i], points[i + 1], points[i + 2]));
    }
    pieces_.push_back(std::move(piece));
  }
}

Eigen::Vector3d CurveDistance::point(const Piece& piece, double s) const {
  double value[4];
  bernstein_evaluate(piece.homogeneous, {s}, value);
  const Eigen::Vector3d p(value[0], value[1], value[2]);
  return rational_ ? Eigen::Vector3d(p / value[3]) : p;
}

double CurveDistance::operator()(const Eigen::Vector3d& x) const {
  // Nearest boxes first, so that farther pieces are skipped by their box's distance.
  std::vector<std::pair<double, std::size_t>> order;
  order.reserve(pieces_.size());
  for (std::size_t i = 0; i < pieces_.size(); ++i)
    order.emplace_back(pieces_[i].box.isEmpty() ? 0.0 : std::sqrt(pieces_[i].box.squaredExteriorDistance(x)), i);
  std::sort(order.begin(), order.end());

  const double eps = std::numeric_limits<double>::epsilon();
  double best = std::numeric_limits<double>::infinity();
  BernsteinTensor<1> derivative;
  for (const auto& [bound, index] : order) {
    if (bound >= best) break;
    const Piece& piece = pieces_[index];
    best = std::min({best, (point(piece, 0.0) - x).norm(), (point(piece, 1.0) - x).norm()});
    derivative = piece.a;
    for (std::size_t k = 0; k < derivative.coefficients.size(); ++k) {
      const double* b = &piece.b.coefficients[3 * k];
      derivative.coefficients[k] -= x[0] * b[0] + x[1] * b[1] + x[2] * b[2];
    }
    // Each coefficient is a sum of products with about 3 (p + 1) terms, each rounded.
    const double noise = 8.0 * static_cast<double>(derivative.coefficients.size() + 4) * eps *
                         (piece.a_max + x.cwiseAbs().sum() * piece.b_max);
    for (const double s : bernstein_roots(derivative, noise)) best = std::min(best, (point(piece, s) - x).norm());
  }
  return best;
}

}  // namespace volspline
