#pragma once
// The simplex_spline_volume object of model files (docs/model-format.md, "Simplex spline
// volumes"): a DMS spline volume (simplex/dms_spline_volume.h) with its domain, knot clouds,
// control points and attributes.
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

inline constexpr const char* kSimplexSplineVolumeType = "simplex_spline_volume";

/// Reads the keys of a simplex_spline_volume object other than "name", "type" and "metadata".
/// \throw InvalidInput located below `path` (a key, an index, "tetrahedra[i]" for a degenerate,
/// negatively oriented or non-conforming tetrahedron or invalid knot clouds around it).
DmsSplineVolume read_simplex_spline_volume(const nlohmann::json& object, const std::string& path);

/// Writes those keys, each on its own line(s), starting with ",\n" after the "type" line is not
/// needed: the caller has written `"type": ...,\n`; this writes the rest without a trailing comma.
void write_simplex_spline_volume(std::ostringstream& out, const DmsSplineVolume& volume, const std::string& indent,
                                 const std::string& path);

}  // namespace volspline
