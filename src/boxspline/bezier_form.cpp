#include "volspline/boxspline/bezier_form.h"

#include <cmath>
#include <string>

#include "quartic_tables.h"
#include "volspline/boxspline/seven_direction_box_spline.h"
#include "volspline/core/error.h"

namespace volspline {

BezierFormField::BezierFormField(const LatticeField& field)
    : origin_(field.origin - field.spacing * Eigen::Vector3d(0.5, 0.5, 2.5)), inverse_spacing_(1.0 / field.spacing) {
  std::tie(lo_, hi_) = field.domain();
  // Knot cubes q (uncentred units, u = (x − o)/h + (1/2, 1/2, 5/2)) of the domain: see
  // LatticeField::evaluate.
  first_[0] = 2, first_[1] = 2, first_[2] = 4;
  cubes_[0] = field.size[0] - 4, cubes_[1] = field.size[1] - 4, cubes_[2] = field.size[2] - 4;
  const std::size_t total = static_cast<std::size_t>(cubes_[0]) * cubes_[1] * cubes_[2];
  if (total > kMaxCubes)
    throw InvalidInput("expected at most " + std::to_string(kMaxCubes) + " knot cubes for the Bezier form, got " +
                       std::to_string(total));
  bb_.assign(total * kCubeTetrahedra * kQuarticCoefficients, 0.0);
  const SevenDirectionBoxSpline& m = seven_direction_box_spline();
  double* out = bb_.data();
  for (int cz = 0; cz < cubes_[2]; ++cz)
    for (int cy = 0; cy < cubes_[1]; ++cy)
      for (int cx = 0; cx < cubes_[0]; ++cx) {
        const int q[3] = {cx + first_[0], cy + first_[1], cz + first_[2]};
        for (int t = 0; t < kCubeTetrahedra; ++t, out += kQuarticCoefficients)
          for (const int p : m.pieces_on_tetrahedron[t]) {
            const auto& piece = m.pieces[static_cast<std::size_t>(p)];
            const double c = field.at(q[0] - piece.cube[0], q[1] - piece.cube[1], q[2] - piece.cube[2]);
            for (int k = 0; k < kQuarticCoefficients; ++k) out[k] += c * piece.bb[k];
          }
      }
}

bool BezierFormField::in_domain(const Eigen::Vector3d& x) const {
  return (x.array() >= lo_.array()).all() && (x.array() <= hi_.array()).all();
}

double BezierFormField::evaluate(const Eigen::Vector3d& x, Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian) const {
  double local[3];
  std::size_t cube = 0;
  for (int d = 2; d >= 0; --d) {
    const double u = (x[d] - origin_[d]) * inverse_spacing_;
    int q = static_cast<int>(std::floor(u)) - first_[d];
    q = q < 0 ? 0 : (q >= cubes_[d] ? cubes_[d] - 1 : q);
    local[d] = u - (q + first_[d]);
    cube = cube * static_cast<std::size_t>(cubes_[d]) + static_cast<std::size_t>(q);
  }
  const CubeLocation at = quartic::locate(local[0], local[1], local[2]);
  const double* bb = bb_.data() + (cube * kCubeTetrahedra + static_cast<std::size_t>(at.tetrahedron)) * kQuarticCoefficients;
  const double value = quartic::evaluate(bb, at.tetrahedron, at.barycentric.data(), gradient, hessian);
  if (gradient != nullptr) *gradient *= inverse_spacing_;
  if (hessian != nullptr) *hessian *= inverse_spacing_ * inverse_spacing_;
  return value;
}

}  // namespace volspline
