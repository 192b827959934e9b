#pragma once
// Tensor-product B-spline (and, as the special case of single-span clamped knot vectors,
// Bézier) maps from a D-dimensional parameter box into R^k, polynomial or rational.
// One template serves curves (D=1), surfaces (D=2) and volumes (D=3); D=4 is instantiated too,
// for 4-variate maps: a swept solid's patches s(u, v, w, t) (construct/swept_solid.h). Storage
// order and domain conventions: core/conventions.h.
//
// Rational splines are handled through their homogeneous form (Lasser 1994, eq. 4): every
// algorithm works on the polynomial spline in R^{k+1} with coefficients (w x, w) and projects at
// the end, so weight-0 control points (points at infinity, Lasser after eq. 5) need no special
// case anywhere except in the conversion between the two forms.
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "volspline/core/knot_vector.h"

namespace volspline {

/// Multi-indices of partial derivatives of total order <= `order` in D variables, graded by
/// total order and, within one order, in descending lexicographic order. For D = 3, order 2:
/// (0,0,0) (1,0,0) (0,1,0) (0,0,1) (2,0,0) (1,1,0) (1,0,1) (0,2,0) (0,1,1) (0,0,2).
/// Every derivative output in volspline uses this order.
template <int D>
std::vector<std::array<int, D>> derivative_multi_indices(int order);

template <int D>
class TensorSpline {
  static_assert(D >= 1 && D <= 4, "tensor-product splines have 1 to 4 parameters");

 public:
  static constexpr int num_parameters = D;
  using Parameter = std::array<double, D>;
  using Index = std::array<int, D>;

  /// Builds a spline from Cartesian control points (`points`: count * dimension numbers, u
  /// fastest) and, for a rational spline, one weight per control point (empty: polynomial).
  /// A weight of 0 makes that control point a point at infinity whose coordinates are a
  /// direction. \throw InvalidInput, located relative to a model object ("knots[1][3]",
  /// "control_points[5][2]", "weights[7]"), if the count does not match the knot vectors, a
  /// number is NaN or infinite, a weight is negative, or the weights vanish together somewhere
  /// in the domain (the denominator of Lasser's eq. 5 would be zero).
  TensorSpline(std::array<KnotVector, D> knots, int dimension, std::vector<double> points,
               std::vector<double> weights = {});

  /// Builds a spline from homogeneous coefficients: count * (dimension + 1) numbers
  /// (w x, w) per control point when `rational`, else count * dimension Cartesian numbers.
  static TensorSpline from_homogeneous(std::array<KnotVector, D> knots, int dimension, bool rational,
                                       std::vector<double> coefficients);

  int dimension() const { return dimension_; }
  bool is_rational() const { return !weights_.empty(); }
  const std::array<KnotVector, D>& knot_vectors() const { return knots_; }
  const KnotVector& knot_vector(int direction) const { return knots_[static_cast<std::size_t>(direction)]; }
  Index degrees() const;
  /// Control points per direction.
  Index num_control_points() const { return counts_; }
  int num_control_points_total() const { return total_; }
  /// Cartesian control points, count * dimension, u fastest.
  const std::vector<double>& points() const { return points_; }
  /// Weights, one per control point; empty for a polynomial spline.
  const std::vector<double>& weights() const { return weights_; }
  /// Coefficients of the homogeneous form: (w x, w) per control point for a rational spline,
  /// the Cartesian points for a polynomial one.
  const std::vector<double>& homogeneous() const { return rational_coefficients_.empty() ? points_ : rational_coefficients_; }
  /// Numbers per homogeneous coefficient: dimension, plus one if rational.
  int coefficient_size() const { return dimension_ + (is_rational() ? 1 : 0); }

  /// The local origin O (`dimension()` numbers): coordinate c is the centre of the control
  /// points' bounding box in c (points at infinity left out) where that centre lies farther from
  /// 0 than the box's largest edge, and 0 otherwise. Every evaluation (evaluate,
  /// evaluate_derivatives, evaluate_points, evaluate_grid) contracts the control points relative
  /// to O and adds O to the position only: a sum of basis functions times coordinates of size
  /// |x| rounds to about |x| u, so a model of size 1 placed at 1e15 would get derivatives with
  /// errors near 1 (basis derivatives sum to 0 and cancel the offset); relative to O the error is
  /// that of the model at 0, and positions are within a few ulp(|O|) (docs/testing.md, "far from
  /// the origin"). Models that contain or touch the origin's neighbourhood have O = 0 and are
  /// evaluated exactly as before.
  const std::vector<double>& local_origin() const { return local_origin_; }
  /// The spline translated by −local_origin() (control points x − O, weights unchanged): what
  /// translation-invariant computations on control points (Bézier extraction followed by
  /// differences, Jacobian coefficients, mass properties) start from, so their roundings are
  /// relative to the model's size, not to its distance from 0. x − O is exact wherever x and O
  /// agree to within a factor 2 (Sterbenz).
  TensorSpline translated_to_local_origin() const;
  /// Linear index of control point `i` (u fastest).
  int linear_index(const Index& i) const;
  double domain_min(int direction) const { return knot_vector(direction).domain_min(); }
  double domain_max(int direction) const { return knot_vector(direction).domain_max(); }
  bool contains(const Parameter& t) const;
  /// \throw InvalidInput naming the coordinate if t lies outside the domain or is not finite.
  void check_in_domain(const Parameter& t) const;

  /// The point at t (`dimension()` numbers). \throw InvalidInput if t is outside the domain.
  void evaluate(const Parameter& t, double* out) const;
  Eigen::VectorXd evaluate(const Parameter& t) const;
  /// All partial derivatives up to `order` at t, in the order of derivative_multi_indices<D>
  /// (the point itself first): out holds count * dimension numbers.
  void evaluate_derivatives(const Parameter& t, int order, double* out) const;
  std::vector<double> evaluate_derivatives(const Parameter& t, int order) const;

  /// evaluate_derivatives at many scattered points, in parallel (oneTBB): out[(point *
  /// num_multi_indices + alpha) * dimension + c]. \throw InvalidInput naming the first point
  /// outside the domain ("points[i]").
  std::vector<double> evaluate_points(const std::vector<Parameter>& t, int order = 0) const;

  /// Values and partial derivatives up to `order` on the tensor grid samples[0] x ... x
  /// samples[D-1], by sum factorisation (one direction at a time, never point by point).
  /// Layout: one block per derivative multi-index (derivative_multi_indices order), each block
  /// the grid points with the first parameter fastest, each point `dimension()` numbers:
  /// out[(alpha * num_points + point) * dimension + c].
  std::vector<double> evaluate_grid(const std::array<std::vector<double>, D>& samples, int order = 0) const;
  /// The same into a caller's buffer of num_multi_indices * num_points * dimension() numbers,
  /// for repeated evaluation without allocation.
  void evaluate_grid(const std::array<std::vector<double>, D>& samples, int order, double* out) const;

 private:
  struct FromHomogeneous {};
  TensorSpline(FromHomogeneous, std::array<KnotVector, D> knots, int dimension, bool rational,
               std::vector<double> coefficients);
  void set_counts();
  void validate_weights() const;
  void set_local_origin();
  /// The coefficients the evaluation kernels contract: homogeneous() relative to local_origin().
  const std::vector<double>& evaluation_coefficients() const {
    return local_coefficients_.empty() ? homogeneous() : local_coefficients_;
  }
  /// Adds the local origin to `count` positions of dimension() numbers, `stride` numbers apart.
  void add_local_origin(double* positions, std::size_t count, std::size_t stride) const;

  std::array<KnotVector, D> knots_;
  int dimension_ = 0;
  Index counts_{};
  int total_ = 0;
  std::vector<double> points_;
  std::vector<double> weights_;
  std::vector<double> rational_coefficients_;
  std::vector<double> local_origin_;
  std::vector<double> local_coefficients_;  // empty where the local origin is 0
};

using BSplineCurve = TensorSpline<1>;
using BSplineSurface = TensorSpline<2>;
using BSplineVolume = TensorSpline<3>;
using BSplineHypervolume = TensorSpline<4>;

extern template class TensorSpline<1>;
extern template class TensorSpline<2>;
extern template class TensorSpline<3>;
extern template class TensorSpline<4>;

}  // namespace volspline
