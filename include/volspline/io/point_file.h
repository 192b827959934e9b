#pragma once
// Point files: one point per line, its x, y and z separated by commas, spaces or tabs. Lines
// that are empty or start with '#' are skipped; a first line that is not numbers is a header
// and is skipped too. The domain of a simplex spline volume can be the Delaunay
// tetrahedralisation of such points (volspline make simplex-spline --points).
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// \throw InvalidInput "SOURCE: line L: expected 3 numbers x, y, z, got ..." for a line that is not
/// three finite numbers, or for a file without points.
std::vector<Eigen::Vector3d> parse_points(std::string_view text, const std::string& source_name);
/// \throw IoError if the file cannot be read; InvalidInput as parse_points.
std::vector<Eigen::Vector3d> read_points(const std::filesystem::path& path);

}  // namespace volspline
