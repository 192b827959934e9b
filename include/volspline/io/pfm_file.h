#pragma once
// Portable float maps (PFM): one 32-bit float per pixel, for results that are numbers rather
// than colours (the line integrals of an X-ray picture). Greyscale "Pf", little-endian (scale
// -1), rows bottom to top as the format has them.
#include <filesystem>
#include <string>
#include <vector>

namespace volspline {

/// The file's bytes for width x height values given top row first.
/// \throw InvalidInput if values has not width * height entries or a side is < 1.
std::string pfm_bytes(const std::vector<double>& values, int width, int height);
/// Writes pfm_bytes atomically. \throw IoError if the file cannot be written.
void write_pfm(const std::vector<double>& values, int width, int height, const std::filesystem::path& path);

}  // namespace volspline
