#include "volspline/render/text.h"

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace volspline {
namespace {

std::string printable(const std::string& text) {
  std::string s;
  for (char c : text) s.push_back(c >= 32 && c < 127 ? c : '?');
  return s;
}

}  // namespace

std::array<int, 2> text_size(const std::string& text, int scale) {
  std::string s = printable(text);
  return {scale * stb_easy_font_width(s.data()), scale * stb_easy_font_height(s.data())};
}

void draw_text(Image& image, int x, int y, const std::string& text, int scale, const std::array<std::uint8_t, 3>& rgb) {
  std::string s = printable(text);
  if (s.empty()) return;
  // 64 bytes per quad and up to about a dozen quads for the busiest glyphs ('8', '@'): the
  // library's estimate of 270 bytes per character is an average and cut off a final '8'.
  std::vector<char> buffer(1024 * (s.size() + 1));
  unsigned char color[4] = {rgb[0], rgb[1], rgb[2], 255};
  const int quads = stb_easy_font_print(0, 0, s.data(), color, buffer.data(), static_cast<int>(buffer.size()));
  struct Vertex {
    float x, y, z;
    unsigned char c[4];
  };
  const auto* v = reinterpret_cast<const Vertex*>(buffer.data());
  for (int q = 0; q < quads; ++q) {
    const Vertex* quad = v + 4 * q;
    float x0 = quad[0].x, x1 = quad[0].x, y0 = quad[0].y, y1 = quad[0].y;
    for (int k = 1; k < 4; ++k) {
      x0 = std::min(x0, quad[k].x);
      x1 = std::max(x1, quad[k].x);
      y0 = std::min(y0, quad[k].y);
      y1 = std::max(y1, quad[k].y);
    }
    const int px0 = std::max(0, x + scale * static_cast<int>(std::lround(x0)));
    const int px1 = std::min(image.width, x + scale * static_cast<int>(std::lround(x1)));
    const int py0 = std::max(0, y + scale * static_cast<int>(std::lround(y0)));
    const int py1 = std::min(image.height, y + scale * static_cast<int>(std::lround(y1)));
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) {
        std::uint8_t* p = image.pixel(px, py);
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
        p[3] = 255;
      }
  }
}

}  // namespace volspline
