#pragma once
// Volume data to be fitted (Hua–He–Qin §5.1): points p_i = (x_i, y_i, z_i, d_1, ..., d_k), from
// scattered samples, unstructured grids or images. Formats and decisions: docs/fitting.md,
// "Volume data input".
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// Points and their named attribute columns: attributes(i, a) is attribute a at points[i].
struct VolumeData {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::string> attribute_names;
  /// points.size() rows, attribute_names.size() columns.
  Eigen::MatrixXd attributes;

  std::size_t size() const { return points.size(); }
  /// The column of an attribute. \throw InvalidInput naming the attributes the data has.
  int attribute_column(const std::string& name) const;
};

/// The data with only the named attribute columns, in the order given (all of them if `names`
/// is empty). \throw InvalidInput for a name the data lacks (naming those it has), or repeated.
VolumeData select_attributes(const VolumeData& data, const std::vector<std::string>& names);

/// The points i with (i % every == which) == keep, in their order, with their attributes: a
/// deterministic split into held-in and held-out data (knot placement and the local knot step
/// judge on every 8th point).
VolumeData every_nth_point(const VolumeData& data, std::size_t every, std::size_t which, bool keep);

/// Checks that every coordinate and attribute is finite, the sizes agree and attribute names are
/// distinct, non-empty and not x, y or z. \throw InvalidInput "SOURCE: point i: ..." (or the
/// attribute's name) saying what was found.
void validate_volume_data(const VolumeData& data, const std::string& source);

/// CSV: a header line naming the columns (x, y, z required, in any order; every other column is
/// an attribute), then one line per point; separators are commas (spaces and tabs around fields
/// are ignored); empty lines and lines starting with '#' are skipped.
/// \throw InvalidInput "SOURCE: line L: ..." for a missing x/y/z column, a repeated or empty
/// name, a line with the wrong number of fields, or a field that is not a finite number (the
/// column named).
VolumeData parse_volume_csv(std::string_view text, const std::string& source);

/// PLY (ascii, binary_little_endian, binary_big_endian): the properties of the `vertex` element;
/// x, y, z are the point, every other scalar property an attribute. List properties of the
/// vertex element and other elements (faces) are skipped.
/// \throw InvalidInput "SOURCE: line L" for header errors, "SOURCE: vertex i" for a bad or
/// missing (truncated) value.
VolumeData parse_volume_ply(std::string_view bytes, const std::string& source);

/// INRIMAGE-4: a text header of 256-byte blocks ("#INRIMAGE-4#{", KEY=VALUE lines with XDIM,
/// YDIM, ZDIM, VDIM, TYPE, PIXSIZE, CPU, VX, VY, VZ and optionally the origin TX, TY, TZ, then
/// "##}"), then XDIM·YDIM·ZDIM·VDIM values, x fastest. Voxel (i, j, k) becomes the point
/// origin + (i VX, j VY, k VZ) (its centre), with one attribute `value` (VDIM = 1) or `value_0`,
/// `value_1`, ... \throw InvalidInput "SOURCE: header line L" or "SOURCE: data" (truncated).
VolumeData parse_inrimage(std::string_view bytes, const std::string& source);

/// Reads a volume data file by its extension: .csv, .ply, .inr, .vtu (VTK XML unstructured
/// grid), .vti (VTK XML image data), .vtk (legacy VTK: any dataset with points; values missing
/// or not numbers are refused, not read as zeros), .nii or .nii.gz (NIfTI-1: the voxel-to-world
/// map of the sform, else the qform; values scaled by scl_slope and scl_inter where set).
/// VTK point data arrays become attributes (one per component: NAME, or NAME_0, NAME_1, ... for
/// vectors); images give their voxel centres, origin and spacing respected.
/// \throw IoError if the file cannot be opened; InvalidInput naming the file and the place.
VolumeData read_volume_data(const std::filesystem::path& path);

}  // namespace volspline
