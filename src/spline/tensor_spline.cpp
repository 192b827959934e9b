#include "volspline/spline/tensor_spline.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

namespace {

std::string index_text(std::size_t i) { return "[" + std::to_string(i) + "]"; }

// A rational spline does not change when every homogeneous coefficient (w x, w) is multiplied by
// one factor (numerator and denominator of Lasser's eq. 5 scale together; a point at infinity's
// direction is its own homogeneous coefficient and scales with them). Weights far from 1 are
// legal but break what is computed from them: 4.9e-324 (the least subnormal) times a basis
// function underflows to a zero denominator, and the powers w^4 of rational Jacobians underflow
// long before. Every spline, whichever reader or algorithm made it, is therefore built with its
// largest weight in [2^-32, 2^32]; one outside is scaled by the power of two that brings it into
// [1, 2): exact for every weight scaled up, the geometry unchanged, and weights in the usual range
// (and so round trips of ordinary files) untouched. Returns that exponent, 0 when none is needed.
int rational_weight_exponent(double largest) {
  if (!(largest > 0.0) || (largest >= 0x1p-32 && largest <= 0x1p32)) return 0;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest = m 2^exponent, m in [0.5, 1)
  return 1 - exponent;
}

}  // namespace

template <int D>
std::vector<std::array<int, D>> derivative_multi_indices(int order) {
  std::vector<std::array<int, D>> result;
  for (int total = 0; total <= order; ++total) {
    // Descending lexicographic enumeration of compositions of `total` into D parts.
    std::array<int, D> alpha{};
    alpha[0] = total;
    while (true) {
      result.push_back(alpha);
      // Next composition: move one unit from the last nonzero entry before the tail rightwards.
      int j = D - 2;
      while (j >= 0 && alpha[static_cast<std::size_t>(j)] == 0) --j;
      if (j < 0) break;
      const int tail = alpha[static_cast<std::size_t>(D - 1)];
      alpha[static_cast<std::size_t>(D - 1)] = 0;
      alpha[static_cast<std::size_t>(j)] -= 1;
      alpha[static_cast<std::size_t>(j + 1)] = tail + 1;
    }
  }
  return result;
}

template <int D>
TensorSpline<D>::TensorSpline(std::array<KnotVector, D> knots, int dimension, std::vector<double> points,
                              std::vector<double> weights)
    : knots_(std::move(knots)), dimension_(dimension), points_(std::move(points)), weights_(std::move(weights)) {
  set_counts();
  const std::size_t n = static_cast<std::size_t>(total_);
  const std::size_t k = static_cast<std::size_t>(dimension_);
  if (points_.size() != n * k) {
    std::string shape;
    for (int d = 0; d < D; ++d) shape += (d ? " x " : "") + std::to_string(counts_[static_cast<std::size_t>(d)]);
    throw InvalidInput("expected " + std::to_string(n) + " control points (" + shape +
                           " from the degrees and knots), got " + std::to_string(points_.size() / std::max<std::size_t>(k, 1)),
                       "control_points");
  }
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!std::isfinite(points_[i])) {
      throw InvalidInput("expected a finite number, got " + format_double(points_[i]),
                         "control_points" + index_text(i / k) + index_text(i % k));
    }
  }
  if (!weights_.empty()) {
    if (weights_.size() != n) {
      throw InvalidInput("expected one weight per control point (" + std::to_string(n) + "), got " +
                             std::to_string(weights_.size()),
                         "weights");
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(weights_[i]) || weights_[i] < 0.0) {
        throw InvalidInput("expected a finite weight >= 0, got " + format_double(weights_[i]), "weights" + index_text(i));
      }
    }
    const int exponent = rational_weight_exponent(*std::max_element(weights_.begin(), weights_.end()));
    if (exponent != 0) {
      for (std::size_t i = 0; i < n; ++i) {
        if (weights_[i] != 0.0) {
          weights_[i] = std::ldexp(weights_[i], exponent);
          continue;
        }
        for (std::size_t c = 0; c < k; ++c) {
          double& x = points_[i * k + c];
          x = std::ldexp(x, exponent);
          if (!std::isfinite(x)) {
            throw InvalidInput("the direction of this point at infinity (weight 0) is too long for the other weights: scaled with "
                               "them by 2^" + std::to_string(exponent) + " to bring the largest weight near 1, it is no longer finite",
                               "control_points" + index_text(i) + index_text(c));
          }
        }
      }
    }
    rational_coefficients_.resize(n * (k + 1));
    for (std::size_t i = 0; i < n; ++i) {
      const double w = weights_[i];
      double* h = &rational_coefficients_[i * (k + 1)];
      // A weight-0 point is a direction and enters the numerator of eq. 5 unscaled (Lasser).
      for (std::size_t c = 0; c < k; ++c) h[c] = w == 0.0 ? points_[i * k + c] : w * points_[i * k + c];
      h[k] = w;
    }
    validate_weights();
  }
  set_local_origin();
}

template <int D>
TensorSpline<D>::TensorSpline(FromHomogeneous, std::array<KnotVector, D> knots, int dimension, bool rational,
                              std::vector<double> coefficients)
    : knots_(std::move(knots)), dimension_(dimension) {
  set_counts();
  const std::size_t n = static_cast<std::size_t>(total_);
  const std::size_t k = static_cast<std::size_t>(dimension_);
  const std::size_t c_size = k + (rational ? 1 : 0);
  if (coefficients.size() != n * c_size) {
    throw InvalidInput("expected " + std::to_string(n * c_size) + " homogeneous coefficients, got " +
                       std::to_string(coefficients.size()));
  }
  for (std::size_t i = 0; i < coefficients.size(); ++i) {
    if (!std::isfinite(coefficients[i])) {
      throw InvalidInput("expected a finite coefficient, got " + format_double(coefficients[i]),
                         "coefficients" + index_text(i));
    }
  }
  if (!rational) {
    points_ = std::move(coefficients);
    set_local_origin();
    return;
  }
  points_.resize(n * k);
  weights_.resize(n);
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(coefficients[i * c_size + k]));
  if (const int exponent = rational_weight_exponent(scale); exponent != 0) {
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
      coefficients[i] = std::ldexp(coefficients[i], exponent);
      if (!std::isfinite(coefficients[i])) {
        throw InvalidInput("this coefficient is too large for the weights: scaled with them by 2^" + std::to_string(exponent) +
                               " to bring the largest weight near 1, it is no longer finite",
                           "coefficients" + index_text(i));
      }
    }
    scale = std::ldexp(scale, exponent);
  }
  for (std::size_t i = 0; i < n; ++i) {
    double* h = &coefficients[i * c_size];
    // Algorithms that combine weights with cancellation (knot removal inside degree elevation)
    // can leave -1e-16-sized results where the exact weight is 0: treat those as 0.
    if (h[k] < 0.0 && h[k] >= -1e-9 * scale) h[k] = 0.0;
    const double w = h[k];
    if (w < 0.0) throw InvalidInput("a homogeneous weight is negative: " + format_double(w), "weights" + index_text(i));
    weights_[i] = w;
    for (std::size_t c = 0; c < k; ++c) points_[i * k + c] = w == 0.0 ? h[c] : h[c] / w;
  }
  rational_coefficients_ = std::move(coefficients);
  validate_weights();
  set_local_origin();
}

template <int D>
void TensorSpline<D>::set_local_origin() {
  const std::size_t n = static_cast<std::size_t>(total_);
  const std::size_t k = static_cast<std::size_t>(dimension_);
  local_origin_.assign(k, 0.0);
  local_coefficients_.clear();
  std::vector<double> lo(k, HUGE_VAL), hi(k, -HUGE_VAL);
  for (std::size_t i = 0; i < n; ++i) {
    if (is_rational() && weights_[i] == 0.0) continue;  // a direction, not a point
    for (std::size_t c = 0; c < k; ++c) {
      lo[c] = std::min(lo[c], points_[i * k + c]);
      hi[c] = std::max(hi[c], points_[i * k + c]);
    }
  }
  double extent = 0.0;
  for (std::size_t c = 0; c < k; ++c)
    if (lo[c] <= hi[c]) extent = std::max(extent, hi[c] - lo[c]);
  bool far = false;
  for (std::size_t c = 0; c < k; ++c) {
    if (!(lo[c] <= hi[c])) continue;
    const double centre = 0.5 * lo[c] + 0.5 * hi[c];  // halves first: no overflow near the largest double
    if (std::abs(centre) > extent) local_origin_[c] = centre, far = true;
  }
  if (!far) return;
  const std::size_t C = static_cast<std::size_t>(coefficient_size());
  local_coefficients_.resize(n * C);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = is_rational() ? weights_[i] : 1.0;
    for (std::size_t c = 0; c < k; ++c) {
      const double x = points_[i * k + c];
      // A point at infinity's direction is its own homogeneous coefficient: translations leave it.
      local_coefficients_[i * C + c] = w == 0.0 ? x : w * (x - local_origin_[c]);
    }
    if (is_rational()) local_coefficients_[i * C + k] = w;
  }
}

template <int D>
void TensorSpline<D>::add_local_origin(double* positions, std::size_t count, std::size_t stride) const {
  if (local_coefficients_.empty()) return;
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t c = 0; c < local_origin_.size(); ++c) positions[i * stride + c] += local_origin_[c];
}

template <int D>
TensorSpline<D> TensorSpline<D>::translated_to_local_origin() const {
  if (local_coefficients_.empty()) return *this;
  return from_homogeneous(knots_, dimension_, is_rational(), local_coefficients_);
}

template <int D>
TensorSpline<D> TensorSpline<D>::from_homogeneous(std::array<KnotVector, D> knots, int dimension, bool rational,
                                                  std::vector<double> coefficients) {
  return TensorSpline(FromHomogeneous{}, std::move(knots), dimension, rational, std::move(coefficients));
}

template <int D>
void TensorSpline<D>::set_counts() {
  if (dimension_ < 1) throw InvalidInput("control points need at least one coordinate");
  for (int d = 0; d < D; ++d) counts_[static_cast<std::size_t>(d)] = knots_[static_cast<std::size_t>(d)].num_basis();
  // Indices into the homogeneous coefficients are ints: count * (dimension + 1) must fit, or a
  // wrapped total would make a short array of control points look complete.
  std::array<long long, D + 1> factors{};
  for (int d = 0; d < D; ++d) factors[static_cast<std::size_t>(d)] = counts_[static_cast<std::size_t>(d)];
  factors[D] = static_cast<long long>(dimension_) + 1;
  checked_product<int>(factors, "control points x (coordinates + 1)", "control_points");
  total_ = checked_product<int>(counts_, "control points");
}

template <int D>
void TensorSpline<D>::validate_weights() const {
  // With weights >= 0 the denominator of Lasser's eq. 5 vanishes at t exactly when every control
  // point whose basis function is nonzero at t has weight 0. The sets of nonzero basis functions
  // are smallest at knot values (inside a span all p+1 are positive), so checking every
  // combination of breakpoints decides the question for the whole domain.
  std::array<std::vector<std::vector<int>>, D> support;
  std::array<std::vector<double>, D> where;
  for (int d = 0; d < D; ++d) {
    const KnotVector& kv = knots_[static_cast<std::size_t>(d)];
    const int p = kv.degree();
    std::vector<double> basis(static_cast<std::size_t>(p + 1));
    for (double t : kv.breakpoints()) {
      // Both one-sided limits: at a knot of multiplicity p + 1 the spline is discontinuous and
      // the piece on the left ends with control points that the right limit never sees.
      for (const int span : {kv.find_span(t), kv.find_span_left(t)}) {
        kv.basis(span, t, basis.data());
        std::vector<int> nonzero;
        for (int j = 0; j <= p; ++j)
          if (basis[static_cast<std::size_t>(j)] != 0.0) nonzero.push_back(span - p + j);
        support[static_cast<std::size_t>(d)].push_back(std::move(nonzero));
        where[static_cast<std::size_t>(d)].push_back(t);
      }
    }
  }
  Index combo{};
  while (true) {
    // Any positive weight among the product of the per-direction nonzero sets?
    bool positive = false;
    Index ii{};
    std::array<std::size_t, D> pos{};
    while (!positive) {
      for (int d = 0; d < D; ++d)
        ii[static_cast<std::size_t>(d)] =
            support[static_cast<std::size_t>(d)][static_cast<std::size_t>(combo[static_cast<std::size_t>(d)])][pos[static_cast<std::size_t>(d)]];
      if (weights_[static_cast<std::size_t>(linear_index(ii))] > 0.0) positive = true;
      int d = 0;
      for (; d < D; ++d) {
        auto& set = support[static_cast<std::size_t>(d)][static_cast<std::size_t>(combo[static_cast<std::size_t>(d)])];
        if (++pos[static_cast<std::size_t>(d)] < set.size()) break;
        pos[static_cast<std::size_t>(d)] = 0;
      }
      if (d == D) break;
    }
    if (!positive) {
      std::string at;
      for (int d = 0; d < D; ++d)
        at += (d ? ", " : "") + format_double(where[static_cast<std::size_t>(d)][static_cast<std::size_t>(combo[static_cast<std::size_t>(d)])]);
      throw InvalidInput("the weights of all control points that influence the parameter (" + at +
                             ") are 0, so the rational spline is undefined there (Lasser 1994, eq. 5 needs a "
                             "nonzero denominator)",
                         "weights");
    }
    int d = 0;
    for (; d < D; ++d) {
      if (++combo[static_cast<std::size_t>(d)] < static_cast<int>(support[static_cast<std::size_t>(d)].size())) break;
      combo[static_cast<std::size_t>(d)] = 0;
    }
    if (d == D) break;
  }
}

template <int D>
typename TensorSpline<D>::Index TensorSpline<D>::degrees() const {
  Index p{};
  for (int d = 0; d < D; ++d) p[static_cast<std::size_t>(d)] = knots_[static_cast<std::size_t>(d)].degree();
  return p;
}

template <int D>
int TensorSpline<D>::linear_index(const Index& i) const {
  int index = 0;
  for (int d = D - 1; d >= 0; --d) index = index * counts_[static_cast<std::size_t>(d)] + i[static_cast<std::size_t>(d)];
  return index;
}

template <int D>
bool TensorSpline<D>::contains(const Parameter& t) const {
  for (int d = 0; d < D; ++d)
    if (!knots_[static_cast<std::size_t>(d)].contains(t[static_cast<std::size_t>(d)])) return false;
  return true;
}

template <int D>
void TensorSpline<D>::check_in_domain(const Parameter& t) const {
  static const char* names[] = {"u", "v", "w", "s"};
  for (int d = 0; d < D; ++d) {
    const KnotVector& kv = knots_[static_cast<std::size_t>(d)];
    const double x = t[static_cast<std::size_t>(d)];
    if (!kv.contains(x)) {
      throw InvalidInput(std::string("parameter ") + names[d] + " = " + format_double(x) + " is outside the domain [" +
                         format_double(kv.domain_min()) + ", " + format_double(kv.domain_max()) + "]");
    }
  }
}

template std::vector<std::array<int, 1>> derivative_multi_indices<1>(int);
template std::vector<std::array<int, 2>> derivative_multi_indices<2>(int);
template std::vector<std::array<int, 3>> derivative_multi_indices<3>(int);
template std::vector<std::array<int, 4>> derivative_multi_indices<4>(int);
template class TensorSpline<1>;
template class TensorSpline<2>;
template class TensorSpline<3>;
template class TensorSpline<4>;

}  // namespace volspline
