#pragma once
// A box-spline field converted once into its piecewise Bernstein–Bézier form: 35 coefficients on
// each of the 24 tetrahedra of every knot cube of the domain. Evaluation is then point location
// and one de Casteljau pass (no sum over basis functions), which is what makes scattered
// evaluation fast (figures in docs/performance.md). The price is memory: 6720 bytes per knot
// cube, about 5000 times a coefficient, so it is built for the region where many evaluations
// happen, not for every lattice.
#include <vector>

#include <Eigen/Core>

#include "volspline/boxspline/lattice_field.h"

namespace volspline {

class BezierFormField {
 public:
  /// Most knot cubes a BezierFormField may have (2^17, 880 MB).
  static constexpr std::size_t kMaxCubes = std::size_t{1} << 17;

  /// The BB form of `field` on its whole domain.
  /// \throw InvalidInput if the domain has more than kMaxCubes knot cubes.
  explicit BezierFormField(const LatticeField& field);

  /// f(x) with optional gradient and Hessian in world units; equal to LatticeField::evaluate
  /// up to rounding. Points outside the domain are clamped onto it (no check, no throw: this is
  /// the fast path; check with in_domain() where it matters).
  double evaluate(const Eigen::Vector3d& x, Eigen::Vector3d* gradient = nullptr, Eigen::Matrix3d* hessian = nullptr) const;
  bool in_domain(const Eigen::Vector3d& x) const;
  std::pair<Eigen::Vector3d, Eigen::Vector3d> domain() const { return {lo_, hi_}; }

 private:
  Eigen::Vector3d origin_;
  double inverse_spacing_ = 1.0;
  Eigen::Vector3d lo_, hi_;
  int cubes_[3] = {0, 0, 0};
  int first_[3] = {0, 0, 0};
  std::vector<double> bb_;
};

}  // namespace volspline
