#pragma once
// Colour maps for scalar fields on surfaces: a perceptually uniform sequential map for fields of
// one sign (parameters, attributes) and a diverging map for signed fields, so that the sign of
// the Jacobian reads at a glance (blue negative, white zero, red positive).
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace volspline {

enum class Colormap {
  /// Dark blue through green to yellow, lightness increasing monotonically (after the shape of
  /// matplotlib's viridis; our own piecewise-linear table).
  Sequential,
  /// Blue – near white – red, symmetric about the middle of the range.
  Diverging,
};

/// A map and the range it spans, for the values of a field.
struct ScalarColoring {
  Colormap map = Colormap::Sequential;
  double min = 0;
  double max = 1;
};

/// The sequential map over [min, max] of `values`; but if `signed_field` (a Jacobian) and the
/// values take both signs (beyond 1e-9 of the largest magnitude), the diverging map over [−m, m] with m = max |value|, so zero is the
/// middle (white) colour and the sign reads at a glance. Empty values give [0, 1]. A constant
/// field (max − min within 1e-12 of the largest magnitude: constant up to rounding) gets the
/// range widened_range gives its middle, so it draws the middle colour.
ScalarColoring suggested_coloring(const std::vector<double>& values, bool signed_field);

/// [lo, hi] itself where lo < hi; otherwise (a constant field, lo = hi) the range centred on it,
/// widened by max(1e-12, 1e-6 |lo|) each way, in which the value takes the middle colour and the
/// colour bar still reads; within 1e-6 of the largest double the range ends at the value instead
/// of overflowing.
std::pair<double, double> widened_range(double lo, double hi);

/// The sRGB colour (components in [0, 1]) of `t` in [0, 1]; t outside is clamped, NaN gives grey.
Eigen::Vector3d colormap_color(Colormap map, double t);

}  // namespace volspline
