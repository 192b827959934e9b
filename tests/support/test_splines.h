#pragma once
// Splines made in code for tests: random but reproducible, polynomial and rational, with
// interior knots of every multiplicity, clamped and unclamped knot vectors.
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline::test_support {

inline KnotVector random_knots(std::mt19937& rng, int degree, int spans, bool clamped, int max_multiplicity) {
  std::uniform_real_distribution<double> gap(0.3, 1.0);
  std::uniform_int_distribution<int> mult(1, max_multiplicity);
  std::vector<double> k;
  double x = 0.0;
  const int end_copies = clamped ? degree + 1 : 1;
  if (clamped) {
    k.assign(static_cast<std::size_t>(end_copies), 0.0);
  } else {
    for (int i = 0; i <= degree; ++i) { k.push_back(x); x += gap(rng); }
    x -= gap(rng) * 0.5;
    k.back() = x;
  }
  for (int s = 1; s < spans; ++s) {
    x += gap(rng);
    const int m = mult(rng);
    k.insert(k.end(), static_cast<std::size_t>(m), x);
  }
  x += gap(rng);
  if (clamped) {
    k.insert(k.end(), static_cast<std::size_t>(end_copies), x);
  } else {
    for (int i = 0; i <= degree; ++i) { k.push_back(x); x += gap(rng); }
  }
  return KnotVector(degree, std::move(k));
}

template <int D>
TensorSpline<D> random_spline(std::mt19937& rng, std::array<int, D> degrees, int spans, int dimension, bool rational,
                              bool clamped = true, int max_multiplicity = 2, bool zero_weight = false) {
  auto knots = [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<KnotVector, D>{random_knots(rng, degrees[I], spans, clamped,
                                                   // a point at infinity must never be the only control point
                                                   // influencing a knot: keep multiplicities below the degree
                                                   std::max(1, std::min(max_multiplicity, degrees[I] - (zero_weight ? 1 : 0))))...};
  }(std::make_index_sequence<D>{});
  int n = 1;
  for (const auto& kv : knots) n *= kv.num_basis();
  std::uniform_real_distribution<double> coord(-2.0, 2.0), weight(0.5, 2.0);
  std::vector<double> points(static_cast<std::size_t>(n * dimension));
  for (auto& x : points) x = coord(rng);
  std::vector<double> weights;
  if (rational) {
    weights.resize(static_cast<std::size_t>(n));
    for (auto& w : weights) w = weight(rng);
    if (zero_weight) weights[static_cast<std::size_t>(n / 2)] = 0.0;  // an interior point at infinity
  }
  return TensorSpline<D>(std::move(knots), dimension, std::move(points), std::move(weights));
}

template <int D>
std::array<double, D> random_parameter(std::mt19937& rng, const TensorSpline<D>& s) {
  std::array<double, D> t{};
  for (int d = 0; d < D; ++d) {
    std::uniform_real_distribution<double> u(s.domain_min(d), s.domain_max(d));
    t[static_cast<std::size_t>(d)] = u(rng);
  }
  return t;
}

/// Largest absolute coordinate of the control points: the scale for relative tolerances.
template <int D>
double coefficient_scale(const TensorSpline<D>& s) {
  double m = 1.0;
  for (double x : s.points()) m = std::max(m, std::abs(x));
  return m;
}

/// The point of a curve, surface or volume with three or more coordinates (the first three).
inline Eigen::Vector3d at(const BSplineCurve& c, double t) {
  const auto x = c.evaluate({t});
  return {x[0], x[1], x[2]};
}
inline Eigen::Vector3d at(const BSplineSurface& s, double u, double v) {
  const auto x = s.evaluate({u, v});
  return {x[0], x[1], x[2]};
}
inline Eigen::Vector3d at(const BSplineVolume& s, double u, double v, double w) {
  const auto x = s.evaluate({u, v, w});
  return {x[0], x[1], x[2]};
}

/// Parameters t on the boundary of v's domain (a coordinate equal to a domain end).
inline bool on_domain_boundary(const BSplineVolume& v, const Eigen::Vector3d& t) {
  for (int d = 0; d < 3; ++d)
    if (t[d] == v.domain_min(d) || t[d] == v.domain_max(d)) return true;
  return false;
}

}  // namespace volspline::test_support
