#include "volspline/analysis/jacobian_subdivision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "volspline/analysis/cone_bounds.h"
#include "unit_roundoff.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {

namespace {

// The control vectors of the partial derivative of the geometry along `directions` (one or two
// local derivatives), as 3-vectors.
std::vector<Eigen::Vector3d> derivative_vectors(const BernsteinTensor<3>& g, std::initializer_list<int> directions) {
  BernsteinTensor<3> d = g;
  for (int dir : directions) d = bernstein_derivative(d, dir);
  std::vector<Eigen::Vector3d> v(d.count());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = Eigen::Map<const Eigen::Vector3d>(d.coefficients.data() + 3 * i);
  return v;
}

std::pair<double, double> add(std::pair<double, double> a, std::pair<double, double> b) {
  return {a.first + b.first, a.second + b.second};
}

}  // namespace

JacobianSubdivision::JacobianSubdivision(const BSplineVolume& volume, JacobianBoundMethod method)
    : volume_(volume), method_(method) {
  if (volume.dimension() != 3) {
    throw InvalidInput("the Jacobian determinant needs a volume in R^3, got control points of dimension " +
                       std::to_string(volume.dimension()));
  }
  if (method == JacobianBoundMethod::Cone && volume.is_rational()) {
    throw InvalidInput("cone bounds (Joy–Duchaineau §5) apply to polynomial volumes; use Bézier bounds for a rational volume");
  }
  // Extracted at the local origin: Bézier extraction rounds relative to the coefficients, and
  // the differences that make J must see the model's size, not its distance from 0.
  pieces_ = bezier_pieces(volume.translated_to_local_origin());
  for (int d = 0; d < 3; ++d) {
    breakpoints_[static_cast<std::size_t>(d)] = volume.knot_vector(d).breakpoints();
    counts_[static_cast<std::size_t>(d)] = static_cast<int>(breakpoints_[static_cast<std::size_t>(d)].size()) - 1;
  }
  bool bezier = true;
  for (int d = 0; d < 3; ++d) bezier = bezier && volume.knot_vector(d).is_bezier();
  input_error_ = extraction_error_bound(volume);
  if (bezier && !volume.is_rational()) input_error_ = 0;
  roots_ = make_roots();
  for (const auto& cell : roots_) scale_ = std::max({scale_, std::abs(cell.lower), std::abs(cell.upper)});
}

std::vector<JacobianCell> JacobianSubdivision::make_roots() const {
  std::vector<JacobianCell> cells;
  cells.reserve(pieces_.size());
  for (std::size_t p = 0; p < pieces_.size(); ++p) {
    JacobianCell cell;
    cell.piece = static_cast<int>(p);
    const int i = static_cast<int>(p) % counts_[0];
    const int j = (static_cast<int>(p) / counts_[0]) % counts_[1];
    const int k = static_cast<int>(p) / (counts_[0] * counts_[1]);
    cell.origin = {std::int64_t{i} << kMaxLevel, std::int64_t{j} << kMaxLevel, std::int64_t{k} << kMaxLevel};
    const BSplineVolume& piece = pieces_[p];
    if (method_ == JacobianBoundMethod::Bezier) {
      cell.jacobian = jacobian_bezier_coefficients(piece, input_error_);
    } else {
      cell.geometry = BernsteinTensor<3>(piece.degrees(), 3);
      cell.geometry.coefficients = piece.points();
    }
    bound(cell);
    cells.push_back(std::move(cell));
  }
  return cells;
}

void JacobianSubdivision::bound(JacobianCell& cell) const {
  if (method_ == JacobianBoundMethod::Bezier) {
    const auto [lo, hi] = bernstein_coefficient_range(cell.jacobian.coefficients);
    cell.lower = lo - cell.jacobian.error_bound;
    cell.upper = hi + cell.jacobian.error_bound;
    return;
  }
  // Cone bounds of the local derivatives; J in global parameters divides by the cell's sizes.
  const auto b = cone_jacobian_bound(derivative_vectors(cell.geometry, {0}), derivative_vectors(cell.geometry, {1}),
                                     derivative_vectors(cell.geometry, {2}));
  double volume = 1;
  for (int d = 0; d < 3; ++d) {
    const Eigen::Vector3d lo = parameter(cell.origin);
    std::array<std::int64_t, 3> top = cell.origin;
    top[static_cast<std::size_t>(d)] += extent(cell, d);
    volume *= parameter(top)[d] - lo[d];
  }
  cell.lower = b.first / volume;
  cell.upper = b.second / volume;
}

std::pair<JacobianCell, JacobianCell> JacobianSubdivision::split(const JacobianCell& cell, int direction) const {
  if (direction < 0 || direction > 2 || cell.level[static_cast<std::size_t>(direction)] >= kMaxLevel) {
    throw InvalidInput("cannot split the cell further along direction " + std::to_string(direction));
  }
  JacobianCell a, b;
  a.piece = b.piece = cell.piece;
  a.level = b.level = cell.level;
  a.level[static_cast<std::size_t>(direction)] += 1;
  b.level = a.level;
  a.origin = b.origin = cell.origin;
  b.origin[static_cast<std::size_t>(direction)] += extent(a, direction);
  if (method_ == JacobianBoundMethod::Bezier) {
    auto [left, right] = bernstein_split(cell.jacobian.coefficients, direction, 0.5);
    // Midpoint de Casteljau: exact halvings, one rounding of at most the largest |coefficient|
    // per level, and earlier errors are carried by convex combinations without growth.
    const double growth = 1.01 * cell.jacobian.coefficients.degrees[static_cast<std::size_t>(direction)] * kUnitRoundoff *
                          (bernstein_max_abs(cell.jacobian.coefficients) + cell.jacobian.error_bound);
    a.jacobian.coefficients = std::move(left);
    b.jacobian.coefficients = std::move(right);
    a.jacobian.error_bound = b.jacobian.error_bound = cell.jacobian.error_bound + growth;
    a.jacobian.homogeneous = b.jacobian.homogeneous = cell.jacobian.homogeneous;
    if (cell.jacobian.homogeneous) {
      auto [wl, wr] = bernstein_split(cell.jacobian.weights, direction, 0.5);
      a.jacobian.weights = std::move(wl);
      b.jacobian.weights = std::move(wr);
    }
  } else {
    auto [left, right] = bernstein_split(cell.geometry, direction, 0.5);
    a.geometry = std::move(left);
    b.geometry = std::move(right);
  }
  bound(a);
  bound(b);
  return {std::move(a), std::move(b)};
}

int JacobianSubdivision::split_direction(const JacobianCell& cell, bool by_magnitude) const {
  std::array<double, 3> g{};
  auto measure = [by_magnitude](std::pair<double, double> r) {
    return by_magnitude ? std::max(std::abs(r.first), std::abs(r.second)) : r.second - r.first;
  };
  if (method_ == JacobianBoundMethod::Bezier) {
    for (int d = 0; d < 3; ++d) g[static_cast<std::size_t>(d)] = measure(bernstein_derivative_range(cell.jacobian.coefficients, d));
  } else {
    // §6: J_d = det(D_dd..) summed over the three rows, each bounded by eq. 1; all in local
    // parameters, which already carries the factor "cell size in d".
    const auto du = derivative_vectors(cell.geometry, {0}), dv = derivative_vectors(cell.geometry, {1}),
               dw = derivative_vectors(cell.geometry, {2});
    const std::array<std::vector<Eigen::Vector3d>, 3> first{du, dv, dw};
    for (int d = 0; d < 3; ++d) {
      std::pair<double, double> sum{0, 0};
      for (int row = 0; row < 3; ++row) {
        std::array<std::vector<Eigen::Vector3d>, 3> rows = first;
        rows[static_cast<std::size_t>(row)] = derivative_vectors(cell.geometry, {row, d});
        sum = add(sum, cone_jacobian_bound(rows[0], rows[1], rows[2]));
      }
      g[static_cast<std::size_t>(d)] = measure(sum);
    }
  }
  int best = -1;
  for (int d = 0; d < 3; ++d) {
    if (cell.level[static_cast<std::size_t>(d)] >= kMaxLevel) continue;
    if (best < 0 || g[static_cast<std::size_t>(d)] > g[static_cast<std::size_t>(best)]) best = d;
  }
  return best;
}

double JacobianSubdivision::nonlinearity(const JacobianCell& cell) const {
  if (method_ != JacobianBoundMethod::Bezier) throw InvalidInput("nonlinearity needs Bézier bounds");
  const BernsteinTensor<3>& c = cell.jacobian.coefficients;
  // A(s) = mean + sum_d slope_d (s_d - 1/2), slope_d the mean end-to-end difference along d;
  // the Bernstein coefficients of A are its values at the Greville points i / n.
  double mean = 0;
  for (double x : c.coefficients) mean += x;
  mean /= static_cast<double>(c.count());
  std::array<double, 3> slope{};
  for (int d = 0; d < 3; ++d) {
    const int n = c.degrees[static_cast<std::size_t>(d)];
    if (n == 0) continue;
    double sum = 0;
    int lines = 0;
    for (int k = 0; k < c.size(2); ++k)
      for (int j = 0; j < c.size(1); ++j)
        for (int i = 0; i < c.size(0); ++i) {
          const std::array<int, 3> idx{i, j, k};
          if (idx[static_cast<std::size_t>(d)] != 0) continue;
          std::array<int, 3> end = idx;
          end[static_cast<std::size_t>(d)] = n;
          sum += c.at(end[0], end[1], end[2]) - c.at(i, j, k);
          ++lines;
        }
    slope[static_cast<std::size_t>(d)] = sum / lines;
  }
  double deviation = 0;
  for (int k = 0; k < c.size(2); ++k)
    for (int j = 0; j < c.size(1); ++j)
      for (int i = 0; i < c.size(0); ++i) {
        double a = mean;
        const std::array<int, 3> idx{i, j, k};
        for (int d = 0; d < 3; ++d) {
          const int n = c.degrees[static_cast<std::size_t>(d)];
          if (n > 0) a += slope[static_cast<std::size_t>(d)] * (static_cast<double>(idx[static_cast<std::size_t>(d)]) / n - 0.5);
        }
        deviation = std::max(deviation, std::abs(c.at(i, j, k) - a));
      }
  return deviation + cell.jacobian.error_bound;
}

Eigen::Vector3d JacobianSubdivision::parameter(const std::array<std::int64_t, 3>& lattice) const {
  Eigen::Vector3d t;
  for (int d = 0; d < 3; ++d) {
    const std::vector<double>& b = breakpoints_[static_cast<std::size_t>(d)];
    const std::int64_t x = lattice[static_cast<std::size_t>(d)];
    std::int64_t c = x >> kMaxLevel;
    const std::int64_t last = static_cast<std::int64_t>(b.size()) - 2;
    c = std::clamp<std::int64_t>(c, 0, last);
    const std::int64_t offset = x - (c << kMaxLevel);
    const double f = std::ldexp(static_cast<double>(offset), -kMaxLevel);
    const double lo = b[static_cast<std::size_t>(c)], hi = b[static_cast<std::size_t>(c + 1)];
    // The ends of a piece are its breakpoints exactly, so neighbouring pieces agree on them.
    t[d] = offset == 0 ? lo : (offset == (std::int64_t{1} << kMaxLevel) ? hi : lo + f * (hi - lo));
  }
  return t;
}

std::pair<double, double> JacobianSubdivision::jacobian_bounds(const JacobianCell& cell) const {
  if (method_ == JacobianBoundMethod::Cone || !cell.jacobian.homogeneous) return {cell.lower, cell.upper};
  auto [wlo, whi] = bernstein_coefficient_range(cell.jacobian.weights);
  wlo = std::max(wlo, 0.0);
  const double inf = std::numeric_limits<double>::infinity();
  const double w4lo = wlo * wlo * wlo * wlo, w4hi = whi * whi * whi * whi;
  // J = D / w^4 with w^4 in [w4lo, w4hi], w4lo >= 0.
  auto divide = [&](double d, bool lower) {
    if (d == 0) return 0.0;
    const bool toward_small = (d > 0) == lower;  // the lower end of a positive D divides by w4hi
    const double w4 = toward_small ? w4hi : w4lo;
    if (w4 <= 0) return d > 0 ? inf : -inf;
    return d / w4;
  };
  double lo = divide(cell.lower, true), hi = divide(cell.upper, false);
  if (cell.lower < 0 && cell.upper > 0) {
    lo = w4lo > 0 ? cell.lower / w4lo : -inf;
    hi = w4lo > 0 ? cell.upper / w4lo : inf;
  }
  return {lo, hi};
}

double JacobianSubdivision::corner_value(const JacobianCell& cell, int corner) const {
  const BernsteinTensor<3>& j = cell.jacobian.coefficients;
  return j.at((corner & 1) ? j.size(0) - 1 : 0, (corner & 2) ? j.size(1) - 1 : 0, (corner & 4) ? j.size(2) - 1 : 0);
}

int JacobianSubdivision::corner_sign(const JacobianCell& cell, int corner) const {
  if (method_ != JacobianBoundMethod::Bezier) return 0;
  const double v = corner_value(cell, corner);
  if (v > cell.jacobian.error_bound) return 1;
  if (v < -cell.jacobian.error_bound) return -1;
  return 0;
}

Eigen::Vector3d JacobianSubdivision::corner_parameter(const JacobianCell& cell, int corner) const {
  std::array<std::int64_t, 3> p = cell.origin;
  for (int d = 0; d < 3; ++d) {
    if (corner & (1 << d)) p[static_cast<std::size_t>(d)] += extent(cell, d);
  }
  return parameter(p);
}

}  // namespace volspline
