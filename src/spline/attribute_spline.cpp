#include "volspline/spline/attribute_spline.h"

#include <cmath>
#include <string>

#include "volspline/core/error.h"

namespace volspline {

namespace {

template <int D>
void check_field(const TensorSpline<D>& geometry, const std::vector<double>& values, const std::string& where) {
  const auto n = static_cast<std::size_t>(geometry.num_control_points_total());
  if (values.size() != n) {
    throw InvalidInput("expected " + std::to_string(n) + " values (one per control point), got " +
                           std::to_string(values.size()),
                       where);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(values[i])) throw InvalidInput("expected a finite number", where + "[" + std::to_string(i) + "]");
  }
}

}  // namespace

template <int D>
TensorSpline<D> attribute_spline(const TensorSpline<D>& geometry, const std::vector<double>& values) {
  check_field(geometry, values, "");
  return TensorSpline<D>(geometry.knot_vectors(), 1, values, geometry.weights());
}

template <int D>
TensorSpline<D> append_coordinates(const TensorSpline<D>& geometry, const std::vector<std::vector<double>>& fields) {
  for (std::size_t f = 0; f < fields.size(); ++f) check_field(geometry, fields[f], "fields[" + std::to_string(f) + "]");
  const auto n = static_cast<std::size_t>(geometry.num_control_points_total());
  const auto k = static_cast<std::size_t>(geometry.dimension());
  const std::size_t m = k + fields.size();
  std::vector<double> points(n * m);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < k; ++c) points[i * m + c] = geometry.points()[i * k + c];
    for (std::size_t f = 0; f < fields.size(); ++f) points[i * m + k + f] = fields[f][i];
  }
  return TensorSpline<D>(geometry.knot_vectors(), static_cast<int>(m), std::move(points), geometry.weights());
}

template <int D>
std::pair<TensorSpline<D>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<D>& spline, int dimension) {
  const int m = spline.dimension();
  if (dimension < 1 || dimension > m) {
    throw InvalidInput("expected to keep 1 to " + std::to_string(m) + " coordinates, got " + std::to_string(dimension));
  }
  const auto n = static_cast<std::size_t>(spline.num_control_points_total());
  const auto k = static_cast<std::size_t>(dimension);
  const auto mm = static_cast<std::size_t>(m);
  std::vector<double> points(n * k);
  std::vector<std::vector<double>> fields(mm - k, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < k; ++c) points[i * k + c] = spline.points()[i * mm + c];
    for (std::size_t f = 0; f < mm - k; ++f) fields[f][i] = spline.points()[i * mm + k + f];
  }
  return {TensorSpline<D>(spline.knot_vectors(), dimension, std::move(points), spline.weights()), std::move(fields)};
}

template TensorSpline<1> attribute_spline(const TensorSpline<1>&, const std::vector<double>&);
template TensorSpline<2> attribute_spline(const TensorSpline<2>&, const std::vector<double>&);
template TensorSpline<3> attribute_spline(const TensorSpline<3>&, const std::vector<double>&);
template TensorSpline<4> attribute_spline(const TensorSpline<4>&, const std::vector<double>&);
template TensorSpline<1> append_coordinates(const TensorSpline<1>&, const std::vector<std::vector<double>>&);
template TensorSpline<2> append_coordinates(const TensorSpline<2>&, const std::vector<std::vector<double>>&);
template TensorSpline<3> append_coordinates(const TensorSpline<3>&, const std::vector<std::vector<double>>&);
template TensorSpline<4> append_coordinates(const TensorSpline<4>&, const std::vector<std::vector<double>>&);
template std::pair<TensorSpline<1>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<1>&, int);
template std::pair<TensorSpline<2>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<2>&, int);
template std::pair<TensorSpline<3>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<3>&, int);
template std::pair<TensorSpline<4>, std::vector<std::vector<double>>> split_coordinates(const TensorSpline<4>&, int);

}  // namespace volspline
