#include "volspline/spline/affine_map.h"

#include <algorithm>
#include <limits>
#include <string>

#include "volspline/core/error.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/knot_insertion.h"

namespace volspline {

template <int D>
TensorSpline<D> transform_affine(const TensorSpline<D>& spline, const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int k = spline.dimension();
  if (A.cols() != k || A.rows() != b.size() || A.rows() < 1) {
    throw InvalidInput("affine map of size " + std::to_string(A.rows()) + "x" + std::to_string(A.cols()) + " + " +
                       std::to_string(b.size()) + " does not apply to points of dimension " + std::to_string(k));
  }
  const int m = static_cast<int>(A.rows());
  const int n = spline.num_control_points_total();
  std::vector<double> points(static_cast<std::size_t>(n) * static_cast<std::size_t>(m));
  const auto& w = spline.weights();
  for (int i = 0; i < n; ++i) {
    Eigen::Map<const Eigen::VectorXd> x(spline.points().data() + static_cast<std::ptrdiff_t>(i) * k, k);
    Eigen::Map<Eigen::VectorXd> y(points.data() + static_cast<std::ptrdiff_t>(i) * m, m);
    const bool at_infinity = !w.empty() && w[static_cast<std::size_t>(i)] == 0.0;
    y = A * x;
    if (!at_infinity) y += b;
  }
  return TensorSpline<D>(spline.knot_vectors(), m, std::move(points), w);
}

namespace {

template <int D>
bool has_zero_weight(const TensorSpline<D>& s) {
  return std::any_of(s.weights().begin(), s.weights().end(), [](double w) { return w == 0.0; });
}

template <int D>
void grow_box(const TensorSpline<D>& s, Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
  Eigen::Map<const Eigen::MatrixXd> P(s.points().data(), s.dimension(), s.num_control_points_total());
  lo = lo.cwiseMin(P.rowwise().minCoeff());
  hi = hi.cwiseMax(P.rowwise().maxCoeff());
}

// Halves a Bézier piece in every direction `depth` times (and further while it holds points at
// infinity), adding the control-net boxes of the leaves.
template <int D>
void subdivided_box(const TensorSpline<D>& piece, int depth, int extra, Eigen::VectorXd& lo, Eigen::VectorXd& hi) {
  const bool zero = has_zero_weight(piece);
  if (depth <= 0 && !zero) {
    grow_box(piece, lo, hi);
    return;
  }
  if (depth <= 0 && extra <= 0) throw Error("internal: points at infinity survived subdivision of a Bézier piece");
  std::vector<TensorSpline<D>> parts{piece};
  for (int d = 0; d < D; ++d) {
    std::vector<TensorSpline<D>> next;
    for (const auto& p : parts) {
      auto [left, right] = split(p, d, 0.5 * (p.domain_min(d) + p.domain_max(d)));
      next.push_back(std::move(left));
      next.push_back(std::move(right));
    }
    parts = std::move(next);
  }
  for (const auto& p : parts) subdivided_box(p, depth - 1, depth > 0 ? extra : extra - 1, lo, hi);
}

}  // namespace

template <int D>
std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>& spline, int subdivisions) {
  const int k = spline.dimension();
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(k, std::numeric_limits<double>::infinity());
  Eigen::VectorXd hi = -lo;
  if (subdivisions <= 0) {
    TensorSpline<D> s = spline;
    // Each elevation replaces every interior weight by a positive combination of it and its
    // neighbours, shortening every run of zero weights by one.
    for (int round = 0; round < 64 && has_zero_weight(s); ++round)
      for (int d = 0; d < D; ++d) s = elevate_degree(s, d, 1);
    if (has_zero_weight(s)) throw Error("internal: weight-0 control points survived degree elevation");
    grow_box(s, lo, hi);
    return {lo, hi};
  }
  for (const auto& piece : bezier_pieces(spline)) subdivided_box(piece, subdivisions, 16, lo, hi);
  return {lo, hi};
}

#define VOLSPLINE_INSTANTIATE(D)                                                                                 \
  template TensorSpline<D> transform_affine(const TensorSpline<D>&, const Eigen::MatrixXd&, const Eigen::VectorXd&); \
  template std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>&, int);
VOLSPLINE_INSTANTIATE(1)
VOLSPLINE_INSTANTIATE(2)
VOLSPLINE_INSTANTIATE(3)
VOLSPLINE_INSTANTIATE(4)
#undef VOLSPLINE_INSTANTIATE

}  // namespace volspline
