#include "volspline/render/image.h"

#include <limits>

#if VOLSPLINE_WITH_STB
#include <stb_image_write.h>
#endif

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {

#if VOLSPLINE_WITH_STB
namespace {

void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<std::size_t>(size));
}

}  // namespace
#endif

Image::Image(int width_, int height_, std::uint8_t r, std::uint8_t g, std::uint8_t b,
             std::uint8_t a)
    : width(width_), height(height_) {
  if (width < 0 || height < 0) {
    throw InvalidInput("image size " + std::to_string(width) + " x " + std::to_string(height) +
                       " is negative");
  }
  rgba.resize(4 * std::size_t(width) * std::size_t(height));
  for (std::size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = a;
  }
}

std::string png_bytes(const Image& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw InvalidInput("cannot encode an empty image (" + std::to_string(image.width) + " x " +
                       std::to_string(image.height) + ") as PNG");
  }
  if (image.rgba.size() != 4 * std::size_t(image.width) * std::size_t(image.height)) {
    throw InvalidInput("image of " + std::to_string(image.width) + " x " +
                       std::to_string(image.height) + " pixels holds " +
                       std::to_string(image.rgba.size()) + " bytes, expected 4 per pixel");
  }
  // stb takes the row stride as an int.
  if (image.width > std::numeric_limits<int>::max() / 4) {
    throw InvalidInput("image is too wide to encode as PNG");
  }
#if !VOLSPLINE_WITH_STB
  // stb is optional in volspline::core (VOLSPLINE_WITH_STB, docs/using-volspline.md): pictures
  // are still drawn in memory, only their encoding is refused.
  throw InvalidInput("writing PNG needs stb: this volspline was built with VOLSPLINE_WITH_STB=OFF");
#else
  std::string bytes;
  if (stbi_write_png_to_func(append_to_string, &bytes, image.width, image.height, 4,
                             image.rgba.data(), 4 * image.width) == 0) {
    throw Error("PNG encoding of a " + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " image failed");
  }
  return bytes;
#endif
}

void write_png(const Image& image, const std::filesystem::path& path) {
  write_file_atomically(path, png_bytes(image));
}

}  // namespace volspline
