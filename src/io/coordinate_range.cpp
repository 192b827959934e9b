#include "volspline/io/coordinate_range.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include "volspline/core/format.h"

namespace volspline {
namespace {

std::string coordinate_location(const std::string& path, std::size_t i, std::size_t c) {
  return path + "[" + std::to_string(i) + "][" + std::to_string(c) + "]";
}

// `count` points of `dimension` numbers at `points` (point i's coordinates at points + i * stride),
// those with skip(i) true being directions; `path` names the array ("control_points").
template <class Skip>
void check_coordinate_array(const double* points, std::size_t count, std::size_t dimension, std::size_t stride, Skip skip,
                  const std::string& path) {
  double extent = 0.0;
  std::vector<double> lo(dimension, HUGE_VAL), hi(dimension, -HUGE_VAL);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t c = 0; c < dimension; ++c) {
      const double x = points[i * stride + c];
      if (std::abs(x) > kMaxModelCoordinate) {
        throw InvalidInput("expected a coordinate of magnitude at most 2^200 (about 1.6e60), got " + format_double(x) +
                               ": the Jacobian determinant and the moments of inertia grow like the cube and the fifth "
                               "power of the size and would overflow; scale the model (docs/model-format.md, \"Range of "
                               "coordinates\")",
                           coordinate_location(path, i, c));
      }
      if (skip(i)) continue;
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
    }
  }
  for (std::size_t c = 0; c < dimension; ++c)
    if (lo[c] <= hi[c]) extent = std::max(extent, hi[c] - lo[c]);
  if (extent > 0.0 && extent < kMinModelExtent) {
    throw InvalidInput("expected control points spanning at least 2^-200 (about 6.2e-61) where they are not all one point, got " +
                           format_double(extent) +
                           " (the largest edge of their bounding box): the Jacobian determinant grows like the cube of the "
                           "size and would underflow; scale the model (docs/model-format.md, \"Range of coordinates\")",
                       path);
  }
}

template <int D>
void check_spline_coordinates(const TensorSpline<D>& spline, const std::string& prefix) {
  const std::vector<double>& w = spline.weights();
  check_coordinate_array(
      spline.points().data(), static_cast<std::size_t>(spline.num_control_points_total()), static_cast<std::size_t>(spline.dimension()),
      static_cast<std::size_t>(spline.dimension()), [&](std::size_t i) { return !w.empty() && w[i] == 0.0; }, prefix + "control_points");
}

}  // namespace

void check_coordinate_range(const Model& model) {
  for (std::size_t o = 0; o < model.objects.size(); ++o) {
    const std::string at = "objects[" + std::to_string(o) + "].";
    std::visit(
        [&](const auto& spline) {
          using T = std::decay_t<decltype(spline)>;
          if constexpr (std::is_same_v<T, SweptSolid>) {
            for (std::size_t g = 0; g < spline.generator.size(); ++g)
              check_spline_coordinates(spline.generator[g], at + "generator[" + std::to_string(g) + "].");
            check_spline_coordinates(spline.path, at + "path.");
            for (std::size_t k = 0; k < 3; ++k) check_spline_coordinates(spline.frame[k], at + "frame.curves[" + std::to_string(k) + "].");
          } else if constexpr (std::is_same_v<T, DmsSplineVolume>) {
            const auto& points = spline.domain().points;
            if (!points.empty())
              check_coordinate_array(points.front().data(), points.size(), 3, 3, [](std::size_t) { return false; }, at + "domain.points");
            // The geometry is the first three entries of each control vector (row-major copy:
            // Eigen stores columns).
            const Eigen::MatrixXd& control = spline.control_vectors();
            std::vector<double> xyz(static_cast<std::size_t>(control.rows()) * 3);
            for (Eigen::Index r = 0; r < control.rows(); ++r)
              for (Eigen::Index c = 0; c < 3 && c < control.cols(); ++c) xyz[static_cast<std::size_t>(r * 3 + c)] = control(r, c);
            check_coordinate_array(xyz.data(), static_cast<std::size_t>(control.rows()), 3, 3, [](std::size_t) { return false; },
                         at + "control_vectors");
          } else {
            check_spline_coordinates(spline, at);
          }
        },
        model.objects[o].spline);
  }
}

}  // namespace volspline
