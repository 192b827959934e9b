#include "volspline/io/pfm_file.h"

#include <bit>
#include <cstdint>
#include <cstring>

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {

std::string pfm_bytes(const std::vector<double>& values, int width, int height) {
  if (width < 1 || height < 1 || values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw InvalidInput("expected " + std::to_string(width) + " x " + std::to_string(height) + " values for a PFM image, got " +
                       std::to_string(values.size()));
  std::string bytes = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  const std::size_t header = bytes.size();
  bytes.resize(header + 4 * values.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float f = static_cast<float>(values[static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]);
      std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
      if constexpr (std::endian::native == std::endian::big) bits = ((bits & 0xFFu) << 24) | ((bits & 0xFF00u) << 8) | ((bits >> 8) & 0xFF00u) | (bits >> 24);
      std::memcpy(bytes.data() + header + 4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)), &bits, 4);
    }
  return bytes;
}

void write_pfm(const std::vector<double>& values, int width, int height, const std::filesystem::path& path) {
  write_file_atomically(path, pfm_bytes(values, width, height));
}

}  // namespace volspline
