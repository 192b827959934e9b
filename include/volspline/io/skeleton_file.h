#pragma once
// Skeleton files, format version 1 (docs/skeleton-files.md): a JSON document listing the
// skeleton elements of an attribute field (construct/skeleton_field.h; Hua–He–Qin eq. 8–9),
// each with its falloff and weight. Curves are curve objects as in model files.
#include <filesystem>
#include <string>
#include <string_view>

#include "volspline/construct/skeleton_field.h"

namespace volspline {

/// The format version this library reads and writes.
inline constexpr int kSkeletonFormatVersion = 1;

/// Parses the text of a skeleton file. `source_name` (usually the file name) starts every error
/// message. \throw InvalidInput whose what() reads "SOURCE: JSON.PATH: what was expected, got
/// what" (for example "skeleton.json: elements[2].points[1]: expected an array of 3 numbers,
/// got an array of 2 elements"), or "SOURCE: line L, column C: invalid JSON: ..." for text that
/// is not JSON; the checks of SkeletonField's constructor are located the same way.
SkeletonField parse_skeleton(std::string_view text, const std::string& source_name);

/// Reads and parses a skeleton file. \throw IoError if it cannot be read, InvalidInput as
/// parse_skeleton.
SkeletonField read_skeleton(const std::filesystem::path& path);

/// The text of a skeleton file holding `field`; parse_skeleton gives back the same numbers bit
/// for bit. Rotations are written as matrices. \throw InvalidInput for a field without
/// elements, located at "elements[i].curve" for a curve whose degree model files cannot hold,
/// or at "elements[i].name" for a name that is not UTF-8.
std::string skeleton_to_json(const SkeletonField& field);

/// Writes skeleton_to_json(field) to `path` atomically. \throw IoError if it cannot be written,
/// InvalidInput as skeleton_to_json.
void write_skeleton(const SkeletonField& field, const std::filesystem::path& path);

}  // namespace volspline
