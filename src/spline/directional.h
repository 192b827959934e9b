#pragma once
// A tensor-product spline seen along one direction d is a univariate spline whose "control
// points" are blocks of B = C * n_0 * ... * n_{d-1} numbers (everything that varies faster than
// d), one such line for every index of the slower directions. Univariate algorithms (knot
// insertion, degree elevation, differentiation) run on those lines unchanged and so work for
// every D, for polynomial and (through the homogeneous coefficients) rational splines alike.
#include <cstddef>
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline::detail {

struct LineLayout {
  std::size_t block = 1;  // numbers per "control point" of a line
  std::size_t lines = 1;  // number of lines (product of the slower counts)
  int count = 0;          // control points along the direction
};

template <int D>
LineLayout line_layout(const TensorSpline<D>& s, int direction) {
  LineLayout l;
  l.block = static_cast<std::size_t>(s.coefficient_size());
  for (int d = 0; d < direction; ++d) l.block *= static_cast<std::size_t>(s.num_control_points()[static_cast<std::size_t>(d)]);
  for (int d = direction + 1; d < D; ++d) l.lines *= static_cast<std::size_t>(s.num_control_points()[static_cast<std::size_t>(d)]);
  l.count = s.num_control_points()[static_cast<std::size_t>(direction)];
  return l;
}

/// A new spline whose knot vector in `direction` is `knots` and whose lines along `direction`
/// are produced by op(const double* in, double* out, std::size_t block): `in` holds the old
/// line (count * block numbers), `out` must receive knots.num_basis() * block numbers.
template <int D, class LineOp>
TensorSpline<D> transform_lines(const TensorSpline<D>& s, int direction, const KnotVector& knots, LineOp&& op) {
  const LineLayout l = line_layout(s, direction);
  const std::size_t new_count = static_cast<std::size_t>(knots.num_basis());
  const std::size_t in_len = static_cast<std::size_t>(l.count) * l.block;
  const std::size_t out_len = new_count * l.block;
  std::vector<double> out(out_len * l.lines);
  const double* in = s.homogeneous().data();
  for (std::size_t line = 0; line < l.lines; ++line) op(in + line * in_len, out.data() + line * out_len, l.block);
  auto all = s.knot_vectors();
  all[static_cast<std::size_t>(direction)] = knots;
  return TensorSpline<D>::from_homogeneous(std::move(all), s.dimension(), s.is_rational(), std::move(out));
}

/// The sub-spline made of control-point rows [first, first + knots.num_basis()) along
/// `direction`, with the given knot vector.
template <int D>
TensorSpline<D> slice_rows(const TensorSpline<D>& s, int direction, int first, const KnotVector& knots) {
  return transform_lines(s, direction, knots, [&](const double* in, double* out, std::size_t block) {
    const std::size_t n = static_cast<std::size_t>(knots.num_basis()) * block;
    std::copy(in + static_cast<std::size_t>(first) * block, in + static_cast<std::size_t>(first) * block + n, out);
  });
}

inline void axpby(double a, const double* x, double b, const double* y, double* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = a * x[i] + b * y[i];
}

}  // namespace volspline::detail
