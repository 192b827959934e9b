#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace volspline::cli {

/// One picture of the inside of a solid made by `demo`, with the command (run in the demo
/// folder) that reproduces it.
struct ViewDemoEntry {
  std::string title, description, picture, command;
};

/// Writes Lasser 1994 §IV's ways of looking inside a solid (Figs. 8-13, paddlewheels, colouring
/// by the Jacobian and by a material attribute) into `dir`, where the models they view already
/// are (bent-tricubic.json, twisted-loft.json, half-torus.json written by demo) or are written
/// here (torus-temperature.json).
std::vector<ViewDemoEntry> write_view_demo(const std::filesystem::path& dir);

}  // namespace volspline::cli
