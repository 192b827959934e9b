#include "volspline/core/coordinate_range.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline {

void check_point_coordinate_range(const double* coordinates, std::size_t count, std::size_t dimension, std::size_t stride,
                                  const std::function<std::string(std::size_t, std::size_t)>& locate, const std::string& whole,
                                  std::string_view points, std::string_view reference,
                                  const std::function<bool(std::size_t)>& is_direction) {
  std::vector<double> lo(dimension, HUGE_VAL), hi(dimension, -HUGE_VAL);
  for (std::size_t i = 0; i < count; ++i) {
    const bool direction = is_direction && is_direction(i);
    for (std::size_t c = 0; c < dimension; ++c) {
      const double x = coordinates[i * stride + c];
      if (std::abs(x) > kMaxCoordinate) {
        throw InvalidInput("expected a coordinate of magnitude at most 2^200 (about 1.6e60), got " + format_double(x) +
                               ": volumes, Jacobian determinants and moments of inertia grow like the cube and the fifth "
                               "power of the size and would overflow; scale the input (" + std::string(reference) +
                               ", \"Range of coordinates\")",
                           locate(i, c));
      }
      if (direction) continue;
      lo[c] = std::min(lo[c], x);
      hi[c] = std::max(hi[c], x);
    }
  }
  double extent = 0.0;
  for (std::size_t c = 0; c < dimension; ++c)
    if (lo[c] <= hi[c]) extent = std::max(extent, hi[c] - lo[c]);
  if (extent > 0.0 && extent < kMinExtent) {
    throw InvalidInput("expected " + std::string(points) +
                           " spanning at least 2^-200 (about 6.2e-61) where they are not all one point, got " +
                           format_double(extent) +
                           " (the largest edge of their bounding box): volumes and Jacobian determinants grow like the "
                           "cube of the size and would underflow; scale the input (" + std::string(reference) +
                           ", \"Range of coordinates\")",
                       whole);
  }
}

void check_length_range(double length, const std::string& where, std::string_view what, std::string_view reference) {
  if (length > 0.0 && (length < kMinExtent || length > kMaxCoordinate)) {
    throw InvalidInput("expected " + std::string(what) + " between 2^-200 and 2^200 (about 6.2e-61 and 1.6e60), got " +
                           format_double(length) + "; scale the input (" + std::string(reference) + ", \"Range of coordinates\")",
                       where);
  }
}

}  // namespace volspline
