#include "volspline/spline/affine_map.h"

#include <algorithm>
#include <string>

#include "volspline/core/error.h"
#include "volspline/spline/degree_elevation.h"
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

template <int D>
std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>& spline, int subdivisions) {
  TensorSpline<D> s = spline;
  for (int d = 0; d < D; ++d) {
    for (int round = 0; round < subdivisions; ++round) {
      const auto breaks = s.knot_vector(d).breakpoints();
      std::vector<double> midpoints;
      for (std::size_t i = 0; i + 1 < breaks.size(); ++i) midpoints.push_back(0.5 * (breaks[i] + breaks[i + 1]));
      s = refine_knots(s, d, midpoints);
    }
  }
  auto has_zero_weight = [](const TensorSpline<D>& x) {
    return std::any_of(x.weights().begin(), x.weights().end(), [](double w) { return w == 0.0; });
  };
  // Each elevation replaces every interior weight by a positive combination of it and its
  // neighbour; a few rounds suffice for any spline whose denominator is nonzero on the domain.
  for (int round = 0; round < 8 && has_zero_weight(s); ++round)
    for (int d = 0; d < D; ++d) s = elevate_degree(s, d, 1);
  if (has_zero_weight(s)) throw Error("internal: weight-0 control points survived degree elevation");
  const int k = s.dimension();
  Eigen::Map<const Eigen::MatrixXd> P(s.points().data(), k, s.num_control_points_total());
  return {P.rowwise().minCoeff(), P.rowwise().maxCoeff()};
}

#define VOLSPLINE_INSTANTIATE(D)                                                                                 \
  template TensorSpline<D> transform_affine(const TensorSpline<D>&, const Eigen::MatrixXd&, const Eigen::VectorXd&); \
  template std::pair<Eigen::VectorXd, Eigen::VectorXd> bounding_box(const TensorSpline<D>&, int);
VOLSPLINE_INSTANTIATE(1)
VOLSPLINE_INSTANTIATE(2)
VOLSPLINE_INSTANTIATE(3)
VOLSPLINE_INSTANTIATE(4)

}  // namespace volspline
