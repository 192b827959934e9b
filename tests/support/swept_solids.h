#pragma once
// 4-variate solids made in code for tests and benchmarks: a trivariate solid moved along a
// segment, s(u, v, w, t) = g(u, v, w) + t * offset (Conkey–Joy 2000 with a pure translation),
// whose swept volume is g's image Minkowski-added to the segment: a ball gives a capsule, a box
// the convex hull of its two end positions. Needs no GoogleTest (the benchmarks include it).
#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline::test_support {

/// The control net of g, then of g + offset, as the two layers of degree 1 in t; a rational g
/// keeps its weights in both layers, so the quotient is g + t * offset exactly.
inline BSplineHypervolume translated_along(const BSplineVolume& g, const Eigen::Vector3d& offset) {
  std::vector<double> points = g.points();
  const std::size_t n = points.size();
  points.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) points[n + i] = points[i] + offset[static_cast<Eigen::Index>(i % 3)];
  std::vector<double> weights = g.weights();
  weights.insert(weights.end(), g.weights().begin(), g.weights().end());
  return BSplineHypervolume({g.knot_vector(0), g.knot_vector(1), g.knot_vector(2), KnotVector(1, {0, 0, 1, 1})}, 3,
                            std::move(points), std::move(weights));
}

}  // namespace volspline::test_support
