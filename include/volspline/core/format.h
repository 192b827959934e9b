#pragma once
// Number formatting shared by messages and writers: doubles with 17 significant digits, so
// that reading a written number gives back the same double.
#include <string>

namespace volspline {

/// Shortest-faithful is not needed; 17 significant digits always round-trip.
std::string format_double(double value);

}  // namespace volspline
