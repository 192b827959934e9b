#pragma once
// A hash of a fixed number of doubles taken exactly (their values, not a tolerance), for maps that
// remember answers by the exact inputs that produced them: membership answers by point, refinement
// splits by an edge's ends, crease points by their Newton inputs, mesh vertices by position.
// Callers add 0.0 to each coordinate first where -0 and +0 must be one key (std::hash<double>
// hashes them alike, and == compares them equal).
#include <array>
#include <cstddef>
#include <functional>

namespace volspline {

struct ExactDoublesHash {
  template <std::size_t N>
  std::size_t operator()(const std::array<double, N>& values) const {
    std::size_t h = 0;
    for (const double c : values) h = h * 0x9e3779b97f4a7c15ull + std::hash<double>{}(c);
    return h;
  }
};

}  // namespace volspline
