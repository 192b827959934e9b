#pragma once
#include <filesystem>

namespace volspline::cli {

/// Writes the Peters-Wittman figures 1a .. 4c (mesh .ply and picture .png each) into `dir`.
void write_blend_demo(const std::filesystem::path& dir);

}  // namespace volspline::cli
