#pragma once
// An 8-bit RGBA picture and its PNG encoding; the renderer produces these, the command line
// saves them.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace volspline {

struct Image {
  int width = 0;
  int height = 0;
  /// width * height pixels, rows top to bottom, 4 bytes (R, G, B, A) each; alpha is straight
  /// (not premultiplied), as PNG expects.
  std::vector<std::uint8_t> rgba;

  Image() = default;
  /// A width x height image filled with one colour. \throw InvalidInput for a negative size.
  Image(int width, int height, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
        std::uint8_t a = 0);

  std::uint8_t* pixel(int x, int y) { return rgba.data() + 4 * (std::size_t(y) * width + x); }
  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + 4 * (std::size_t(y) * width + x);
  }
};

/// The PNG file contents of `image` (8-bit RGBA).
/// \throw InvalidInput if the image is empty or `rgba` does not hold width * height pixels,
/// Error if encoding fails.
std::string png_bytes(const Image& image);

/// Writes `image` as a PNG file, atomically. \throw as png_bytes, and IoError if the file cannot
/// be written.
void write_png(const Image& image, const std::filesystem::path& path);

}  // namespace volspline
