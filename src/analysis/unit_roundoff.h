#pragma once
// The unit roundoff u = ε/2 of IEEE double, the unit of the proven rounding-error bounds in the
// Jacobian's Bernstein coefficients, their subdivision and the image-membership margins
// (Higham, "Accuracy and Stability of Numerical Algorithms", §2.2).
#include <limits>

namespace volspline {

inline constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() / 2;

}  // namespace volspline
