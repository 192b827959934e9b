#pragma once
// The range of coordinates every input may hold (issue 16; docs/formats.md, "Range of
// coordinates"): magnitudes at most 2^200 and, for a set of points that are not all one point,
// an extent of at least 2^-200. Within it, a cubic (a Jacobian determinant, a volume) and a
// quintic (moments of inertia) of a size stay normal doubles; beyond it, commands gave messages
// about internal quantities ("weld tolerance must be finite", "parameter u = nan") or blank
// pictures instead of an answer. One rule for model files (io/coordinate_range.h), scenes,
// triangle and tetrahedral meshes, volume data, point files and skeleton files: each reader
// calls check_point_coordinate_range (or, for a single length, check_length_range) with the
// places of its own file.
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace volspline {

/// The largest magnitude of a coordinate: 2^200, about 1.6e60.
inline constexpr double kMaxCoordinate = 0x1p200;
/// The least extent (largest edge of the bounding box) of points that are not all one point,
/// and the least length: 2^-200, about 6.2e-61.
inline constexpr double kMinExtent = 0x1p-200;

/// Points stored as `count` rows of `dimension` numbers (point i's coordinate c at
/// coordinates[i * stride + c]). `locate(i, c)` names where the coordinate is in the input
/// ("mesh.ply: vertex 12 of 40, y"); `whole` names the set ("mesh.ply"); `points` says what the
/// points are ("vertices"); `reference` is the document that states the rule for this input.
/// Points with is_direction(i) true (points at infinity) count for the magnitude only.
/// \throw InvalidInput located at locate(i, c) for a magnitude beyond kMaxCoordinate, or at
/// `whole` for an extent in (0, kMinExtent), naming the number and the range.
void check_point_coordinate_range(const double* coordinates, std::size_t count, std::size_t dimension, std::size_t stride,
                                  const std::function<std::string(std::size_t, std::size_t)>& locate, const std::string& whole,
                                  std::string_view points, std::string_view reference,
                                  const std::function<bool(std::size_t)>& is_direction = {});

/// A positive length (a radius, a semi-axis, a spacing) must lie in [kMinExtent, kMaxCoordinate].
/// \throw InvalidInput located at `where`, naming `what` and the range; zero and negative
/// lengths are the caller's to refuse (this only checks the range of positive ones).
void check_length_range(double length, const std::string& where, std::string_view what, std::string_view reference);

}  // namespace volspline
