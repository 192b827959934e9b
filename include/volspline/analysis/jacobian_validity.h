#pragma once
// Is a volume a valid parameterisation, J != 0 everywhere? The check isogeometric analysis runs
// on every model, decided rigorously: "valid" is only answered when certified bounds of J on
// cells covering the domain all exclude zero with one sign (docs/jacobian.md).
#include <array>
#include <cstdint>
#include <optional>

#include "volspline/analysis/jacobian_subdivision.h"
#include "volspline/core/progress.h"

namespace volspline {

enum class JacobianVerdict {
  /// J has one sign on the whole closed domain (certified).
  Valid,
  /// J takes both signs (certified values at two points), or vanishes at a corner of the domain
  /// whose control points collapse (exactly zero derivative there).
  Invalid,
  /// Neither could be shown within the budget (J may touch zero without changing sign).
  Undecided,
};

struct JacobianValidityOptions {
  JacobianBoundMethod bounds = JacobianBoundMethod::Bezier;
  /// Cells are not split once their bound is narrower than tolerance * scale (the largest |J|
  /// bound over the domain); such cells leave the verdict undecided unless a witness is found.
  double tolerance = 1e-12;
  /// Budget of cells examined (bounded), roots included.
  std::int64_t max_cells = 200000;
  /// Receives the phase "certification" (counts the cells examined). Null: nobody listens.
  Progress* progress = nullptr;
};

struct JacobianValidity {
  JacobianVerdict verdict = JacobianVerdict::Undecided;
  /// +1 or -1 for a valid volume (right- or left-handed), 0 otherwise.
  int orientation = 0;
  /// Certified bounds of J over the domain (for rational volumes from the bounds of w^4 J and of
  /// w; infinite where w's bound reaches 0).
  double lower = 0, upper = 0;
  /// For Invalid: a point (u, v, w) where J has the sign opposite to `reference_point`'s, or is 0.
  std::optional<std::array<double, 3>> witness;
  /// J (w^4 J for a rational volume) at the witness, from the certified coefficients.
  double witness_value = 0;
  /// For Invalid: a point with the other sign (the reference), if one was found.
  std::optional<std::array<double, 3>> reference_point;
  std::int64_t cells = 0;
  double seconds = 0;
};

/// Decides the sign of J on the whole domain by certified bounds refined by subdivision (widest
/// bound first). \throw InvalidInput as JacobianSubdivision, or for options out of range.
JacobianValidity check_jacobian(const BSplineVolume& volume, const JacobianValidityOptions& options = {});

/// The largest cell budget (max_cells) the memory and work limits of core/resource_limits.h allow
/// for `volume`, 0 if even its Bézier cells alone exceed them. check_jacobian refuses a budget
/// above it (InvalidInput) before allocating anything.
std::int64_t jacobian_cells_within_limits(const BSplineVolume& volume, JacobianBoundMethod bounds);

/// "valid", "invalid", "undecided".
const char* verdict_name(JacobianVerdict verdict);

}  // namespace volspline
