#pragma once
// The VTK readers behind read_volume_data (io/volume_data.h); VTK stays private to the library.
#include <filesystem>
#include <string>

#include "volspline/io/volume_data.h"

namespace volspline::detail {

/// `extension` is one of .vtu, .vti, .vtk, .nii (lower case).
VolumeData read_vtk_volume_data(const std::filesystem::path& path, const std::string& extension);

}  // namespace volspline::detail
