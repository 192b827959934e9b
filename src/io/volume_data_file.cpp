#include "volspline/io/volume_data.h"

// The file dispatcher of volume data, apart from the parsers in volume_data.cpp: those belong to
// volspline::core (the fitting of simplex splines uses them), this one to volspline::models,
// which knows whether the VTK readers (volspline::vtk) were built (docs/design.md "Components").
#include <algorithm>
#include <cctype>

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#if VOLSPLINE_WITH_VTK
#include "volume_data_vtk.h"
#endif

namespace volspline {

VolumeData read_volume_data(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  // NIfTI images are often gzip-compressed (name.nii.gz); VTK's reader inflates them itself.
  if (extension == ".gz") {
    std::string stem = path.stem().extension().string();
    std::transform(stem.begin(), stem.end(), stem.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (stem == ".nii") extension = ".nii";
  }
  const std::string source = path.string();
  VolumeData data;
  if (extension == ".csv") data = parse_volume_csv(read_file(path), source);
  else if (extension == ".ply") data = parse_volume_ply(read_file(path), source);
  else if (extension == ".inr") data = parse_inrimage(read_file(path), source);
  else if (extension == ".vtu" || extension == ".vti" || extension == ".vtk" || extension == ".nii")
#if VOLSPLINE_WITH_VTK
    data = detail::read_vtk_volume_data(path, extension);
#else
    throw InvalidInput("reading " + extension + " volume data needs VTK: this volspline was built with VOLSPLINE_WITH_VTK=OFF", source);
#endif
  else
    throw InvalidInput("unknown volume data format " + (extension.empty() ? std::string("(no extension)") : extension) +
                           " (.csv, .ply, .vtu, .vti, .vtk, .inr, .nii or .nii.gz expected)",
                       source);
  validate_volume_data(data, source);
  return data;
}

}  // namespace volspline
