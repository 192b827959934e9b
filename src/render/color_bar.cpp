#include "volspline/render/color_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "volspline/render/text.h"

namespace volspline {

namespace {

// Font pixels per font unit: labels stay legible from small pictures to large ones.
int text_scale(int width, int height) { return std::max(1, static_cast<int>(std::lround(std::min(width, height) / 260.0))); }

}  // namespace

int color_bar_width(int width, int height) { return std::min(width / 3, 64 * text_scale(width, height)); }

std::string color_bar_label(double value) {
  if (value == 0) return "0";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

void draw_color_bar(Image& image, const ColorBar& bar) {
  const int scale = text_scale(image.width, image.height);
  const int width = color_bar_width(image.width, image.height);
  const int left = image.width - width;
  const int strip_left = left + 4 * scale, strip_right = strip_left + 12 * scale;
  const int top = image.height / 8, bottom = image.height - image.height / 8;
  if (bottom - top < 8 || strip_right >= image.width) return;  // too small a picture for a key
  const std::array<std::uint8_t, 3> ink{40, 40, 48};
  for (int y = top; y <= bottom; ++y) {
    const double t = double(bottom - y) / (bottom - top);
    const Eigen::Vector3d c = colormap_color(bar.map, t);
    for (int x = strip_left; x < strip_right; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      for (int i = 0; i < 3; ++i) p[i] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(c[i], 0.0, 1.0)));
      p[3] = 255;
    }
  }
  // A frame and three ticks with labels.
  for (int x = strip_left - 1; x <= strip_right; ++x)
    for (int y : {top - 1, bottom + 1}) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = ink[0], p[1] = ink[1], p[2] = ink[2], p[3] = 255;
    }
  for (int y = top - 1; y <= bottom + 1; ++y)
    for (int x : {strip_left - 1, strip_right}) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = ink[0], p[1] = ink[1], p[2] = ink[2], p[3] = 255;
    }
  const double values[3] = {bar.max, 0.5 * (bar.min + bar.max), bar.min};
  const int rows[3] = {top, (top + bottom) / 2, bottom};
  for (int k = 0; k < 3; ++k) {
    for (int x = strip_right; x < strip_right + 3 * scale && x < image.width; ++x) {
      std::uint8_t* p = image.pixel(x, rows[k]);
      p[0] = ink[0], p[1] = ink[1], p[2] = ink[2], p[3] = 255;
    }
    const std::string label = color_bar_label(values[k]);
    const auto size = text_size(label, scale);
    draw_text(image, strip_right + 5 * scale, rows[k] - size[1] / 2, label, scale, ink);
  }
  const auto size = text_size(bar.title, scale);
  draw_text(image, std::max(left, (strip_left + strip_right) / 2 - size[0] / 2), top - size[1] - 4 * scale, bar.title, scale, ink);
}

}  // namespace volspline
