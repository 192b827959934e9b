#pragma once
// Scene files (docs/scene-format.md): a JSON document naming the lattice spacing, the box the
// box spline replaces, optionally a larger domain to mesh, and a tree of implicit primitives and
// Boolean operations.
#include <filesystem>
#include <string>
#include <string_view>

#include "volspline/boxspline/implicit_scene.h"

namespace volspline {

inline constexpr int kSceneFormatVersion = 1;
/// Most coefficients the box-spline lattice of a scene may have (before refinement).
inline constexpr double kMaxSceneLatticePoints = 4.0e6;

/// Parses the text of a scene file. `source_name` (usually the file name) starts every error
/// message. \throw InvalidInput whose what() reads "SOURCE: JSON.PATH: what was expected, got
/// what" (for example "scene.json: root.union[1].sphere.radius: expected a positive radius,
/// got -1"), or "SOURCE: line L, column C: invalid JSON: ..." for text that is not JSON.
Scene parse_scene(std::string_view text, const std::string& source_name);

/// Reads and parses a scene file. \throw IoError if it cannot be read, InvalidInput as
/// parse_scene.
Scene read_scene(const std::filesystem::path& path);

/// The JSON text of a scene in the format parse_scene reads (primitives written with their
/// placement folded in), for the example files.
std::string scene_to_json(const Scene& scene);

}  // namespace volspline
