#pragma once
// Wall-clock time of a phase, for the per-phase timings in the statistics of long computations
// (envelopes, trimming, fits).
#include <chrono>

namespace volspline {

/// Seconds of the steady clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace volspline
