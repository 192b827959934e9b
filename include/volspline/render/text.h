#pragma once
// Plain labels in pictures (colour-bar numbers and titles), drawn from stb_easy_font's quads:
// no font files to find, the same pixels on every machine.
#include <array>
#include <cstdint>
#include <string>

#include "volspline/render/image.h"

namespace volspline {

/// Size in pixels (width, height) of `text` drawn at `scale` (1 = the font's 6 x 7-pixel cells).
std::array<int, 2> text_size(const std::string& text, int scale);

/// Draws printable ASCII `text` with its top-left corner at (x, y), each font pixel a
/// scale x scale block in colour `rgb`; anything outside the image is clipped.
void draw_text(Image& image, int x, int y, const std::string& text, int scale, const std::array<std::uint8_t, 3>& rgb);

}  // namespace volspline
