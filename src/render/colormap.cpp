#include "volspline/render/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace volspline {
namespace {

// Samples at t = 0, 1/(n-1), ..., 1, interpolated linearly in sRGB.
template <std::size_t N>
Eigen::Vector3d interpolate(const std::array<std::array<double, 3>, N>& table, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * (N - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), N - 2);
  const double f = x - static_cast<double>(i);
  const Eigen::Vector3d a(table[i][0], table[i][1], table[i][2]), b(table[i + 1][0], table[i + 1][1], table[i + 1][2]);
  return (1 - f) * a + f * b;
}

constexpr std::array<std::array<double, 3>, 9> kSequential{{{0.267, 0.005, 0.329},
                                                            {0.278, 0.175, 0.483},
                                                            {0.231, 0.322, 0.546},
                                                            {0.173, 0.449, 0.558},
                                                            {0.128, 0.567, 0.551},
                                                            {0.153, 0.683, 0.502},
                                                            {0.362, 0.786, 0.387},
                                                            {0.663, 0.862, 0.196},
                                                            {0.993, 0.906, 0.144}}};

constexpr std::array<std::array<double, 3>, 7> kDiverging{{{0.130, 0.250, 0.650},
                                                           {0.320, 0.510, 0.830},
                                                           {0.660, 0.780, 0.920},
                                                           {0.950, 0.950, 0.950},
                                                           {0.960, 0.730, 0.620},
                                                           {0.860, 0.400, 0.300},
                                                           {0.680, 0.090, 0.140}}};

}  // namespace

ScalarColoring suggested_coloring(const std::vector<double>& values, bool signed_field) {
  if (values.empty()) return {};
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  // Rounding leaves values like 1e-15 where the field vanishes (a degenerate axis); those do
  // not make a field of one sign "signed".
  const double noise = 1e-9 * std::max(std::abs(*lo), std::abs(*hi));
  if (signed_field && *lo < -noise && *hi > noise) {
    const double m = std::max(-*lo, *hi);
    return {Colormap::Diverging, -m, m};
  }
  // A field constant up to rounding (the Jacobian of a trilinear box) is drawn as constant: one
  // colour, not its rounding noise stretched over the whole map.
  const bool constant = *hi - *lo <= 1e-12 * std::max(std::abs(*lo), std::abs(*hi));
  const double middle = 0.5 * *lo + 0.5 * *hi;
  const auto [from, to] = constant ? widened_range(middle, middle) : widened_range(*lo, *hi);
  return {Colormap::Sequential, from, to};
}

std::pair<double, double> widened_range(double lo, double hi) {
  if (hi > lo) return {lo, hi};
  const double pad = std::max(1e-12, 1e-6 * std::abs(lo));
  // Within 1e-6 of the largest double one end would overflow: the range then ends at the value
  // (which takes the end colour) and keeps its width on the other side.
  if (!std::isfinite(hi + pad)) return {lo - 2 * pad, hi};
  if (!std::isfinite(lo - pad)) return {lo, hi + 2 * pad};
  return {lo - pad, hi + pad};
}

Eigen::Vector3d colormap_color(Colormap map, double t) {
  if (std::isnan(t)) return {0.6, 0.6, 0.6};
  return map == Colormap::Sequential ? interpolate(kSequential, t) : interpolate(kDiverging, t);
}

}  // namespace volspline
