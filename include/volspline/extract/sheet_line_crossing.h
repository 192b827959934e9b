#pragma once
// Where a line segment crosses one sheet of the superset of an image's boundary, to rounding, by
// Newton's method on the sheet's defining equations in the parameters of its spline map
// s : R^D -> R^3 (D = 3: a trivariate solid; D = 4: a swept solid s(u, v, w, t)). The unknowns
// are the sheet's free parameters and lambda, the position along the segment a + lambda (b - a):
//  - a face of the domain (every parameter but two fixed at a domain bound):
//    s(p) = a + lambda (b - a), 3 equations in 3 unknowns;
//  - a fold of a 3-face, or of a trivariate map (three free parameters f0, f1, f2): also
//    det[s_f0 s_f1 s_f2] = 0 (Joy–Duchaineau 1999, Theorem 4.1), 4 in 4;
//  - the rank-deficient set of a 4-variate map (all four free): also J_abc = J_abd = 0 for the
//    pair of columns (a, b) with the largest |s_a x s_b| at the start, which, with s_a x s_b != 0,
//    puts all four columns in one plane: rank 2 (Abdel-Malek–Yeh; Conkey–Joy 2000, §3), 5 in 5.
// The square systems are regular where the line crosses the sheet transversally (at a fold
// the 3 x 3 block is singular, the bordered one is not). The contouring trimmer
// (extract/image_contouring.h) places its vertices with it, so that they lie on the true sheets
// rather than on the superset's chords. docs/envelopes.md, "Trimming by contouring".
#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// Which sheet of the superset a point lies on, in its map's parameters.
struct SupersetSheet {
  /// Bit d set: parameter d is fixed (at the start point's value, a domain bound).
  std::uint8_t fixed = 0;
  /// The Jacobian determinant of the three free parameters vanishes (a fold).
  bool fold = false;
};

template <int D>
struct SheetLineCrossing {
  std::array<double, D> parameter{};
  /// The crossing is a + lambda (b - a), lambda in [0, 1].
  double lambda = 0;
  /// Unit normal of the sheet's image there (sign arbitrary); zero where the sheet's tangent
  /// plane is not defined by the derivatives (a pole of a ball's parameterisation).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// The crossing of the segment [a, b] with the sheet, by damped Newton from `start` (in the
/// domain, the fixed parameters at their values) and `lambda_start`; parameters are kept in the
/// closed domain. \return nothing when Newton does not converge (to 1e-10 of the segment's
/// length) to a point of the domain with lambda in [0, 1], when the sheet is not one of the
/// three kinds above, or when the system is singular there.
template <int D>
std::optional<SheetLineCrossing<D>> sheet_line_crossing(const TensorSpline<D>& s, const SupersetSheet& sheet,
                                                        const std::array<double, D>& start, double lambda_start,
                                                        const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace volspline
