// INRIMAGE-4 images as volume data (io/volume_data.h). The header is text in blocks of 256
// bytes; the format is the one CGAL's ImageIO writes (docs/fitting.md, "Volume data input").
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>

#include "text_numbers.h"
#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/io/volume_data.h"

namespace volspline {
namespace {

enum class InrType { Unsigned, Signed, Float };

double load_value(const unsigned char* p, InrType type, int bytes, bool big_endian) {
  unsigned char b[8];
  for (int i = 0; i < bytes; ++i) b[i] = big_endian ? p[bytes - 1 - i] : p[i];
  switch (type) {
    case InrType::Float:
      if (bytes == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      } else {
        double d;
        std::memcpy(&d, b, 8);
        return d;
      }
    case InrType::Unsigned: {
      std::uint64_t u = 0;
      for (int i = bytes - 1; i >= 0; --i) u = (u << 8) | b[i];
      return static_cast<double>(u);
    }
    case InrType::Signed: {
      std::uint64_t u = 0;
      for (int i = bytes - 1; i >= 0; --i) u = (u << 8) | b[i];
      if (bytes < 8 && (u >> (8 * bytes - 1)) & 1u) u |= ~std::uint64_t{0} << (8 * bytes);  // sign extension
      std::int64_t s;
      std::memcpy(&s, &u, 8);
      return static_cast<double>(s);
    }
  }
  return 0;
}

}  // namespace

VolumeData parse_inrimage(std::string_view bytes, const std::string& source) {
  const std::string_view magic = "#INRIMAGE-4#{";
  if (bytes.substr(0, magic.size()) != magic)
    throw InvalidInput("not an INRIMAGE-4 file (expected it to start with '#INRIMAGE-4#{')", source + ": header line 1");
  const std::size_t close = bytes.find("##}");
  if (close == std::string_view::npos)
    throw InvalidInput("the header does not end (expected a line '##}' within the file)", source + ": header");
  // The header is padded with newlines to a multiple of 256 bytes after "##}\n".
  const std::size_t header_size = (close + 4 + 255) / 256 * 256;
  std::map<std::string, std::pair<std::string, std::size_t>> fields;  // key -> (value, line)
  std::size_t line_number = 1, start = bytes.find('\n') + 1;
  while (start < close) {
    const std::size_t end = std::min(bytes.find('\n', start), close);
    const std::string_view line = bytes.substr(start, end - start);
    start = end + 1;
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    const std::size_t equals = line.find('=');
    if (equals == std::string_view::npos)
      throw InvalidInput("expected KEY=VALUE, got " + detail::quoted_token(line), source + ": header line " + std::to_string(line_number));
    fields[std::string(line.substr(0, equals))] = {std::string(line.substr(equals + 1)), line_number};
  }
  const auto where = [&](const std::string& key) {
    const auto it = fields.find(key);
    return source + (it == fields.end() ? std::string(": header") : ": header line " + std::to_string(it->second.second));
  };
  const auto integer = [&](const std::string& key, std::optional<long long> fallback) -> long long {
    const auto it = fields.find(key);
    if (it == fields.end()) {
      if (fallback) return *fallback;
      throw InvalidInput("missing " + key + " (expected " + key + "=N, N >= 1)", where(key));
    }
    const auto v = detail::parse_integer(it->second.first, 1, 1 << 20);
    if (!v) throw InvalidInput(key + ": expected an integer in 1..2^20, got " + detail::quoted_token(it->second.first), where(key));
    return *v;
  };
  const auto real = [&](const std::string& key, double fallback, bool positive) -> double {
    const auto it = fields.find(key);
    if (it == fields.end()) return fallback;
    const auto v = detail::parse_double(it->second.first);
    if (!v || (positive && *v <= 0))
      throw InvalidInput(key + ": expected a " + std::string(positive ? "positive " : "") + "finite number, got " +
                             detail::quoted_token(it->second.first),
                         where(key));
    return *v;
  };
  const long long nx = integer("XDIM", std::nullopt), ny = integer("YDIM", std::nullopt), nz = integer("ZDIM", std::nullopt);
  const long long nv = integer("VDIM", 1);
  const std::string type_name = fields.count("TYPE") ? fields["TYPE"].first : "";
  InrType type;
  if (type_name == "float") type = InrType::Float;
  else if (type_name == "unsigned fixed") type = InrType::Unsigned;
  else if (type_name == "signed fixed") type = InrType::Signed;
  else
    throw InvalidInput("TYPE: expected 'float', 'unsigned fixed' or 'signed fixed', got " + detail::quoted_token(type_name), where("TYPE"));
  std::string pixsize = fields.count("PIXSIZE") ? fields["PIXSIZE"].first : "";
  int bits = 0;
  if (pixsize == "8 bits") bits = 8;
  else if (pixsize == "16 bits") bits = 16;
  else if (pixsize == "32 bits") bits = 32;
  else if (pixsize == "64 bits") bits = 64;
  if (bits == 0 || (type == InrType::Float && bits < 32))
    throw InvalidInput("PIXSIZE: expected '8 bits', '16 bits', '32 bits' or '64 bits' (32 or 64 for float), got " +
                           detail::quoted_token(pixsize),
                       where("PIXSIZE"));
  const std::string cpu = fields.count("CPU") ? fields["CPU"].first : "decm";
  bool big_endian;
  if (cpu == "decm" || cpu == "alpha" || cpu == "pc") big_endian = false;
  else if (cpu == "sun" || cpu == "sgi" || cpu == "hp") big_endian = true;
  else throw InvalidInput("CPU: expected decm, alpha, pc (little-endian) or sun, sgi, hp (big-endian), got " + detail::quoted_token(cpu), where("CPU"));
  const Eigen::Vector3d spacing(real("VX", 1, true), real("VY", 1, true), real("VZ", 1, true));
  const Eigen::Vector3d origin(real("TX", 0, false), real("TY", 0, false), real("TZ", 0, false));

  const int value_bytes = bits / 8;
  const long long voxels = checked_product<long long>({nx, ny, nz}, "voxels: XDIM x YDIM x ZDIM", source + ": header", 1LL << 28);
  checked_product<long long>({nx, ny, nz, nv}, "values: XDIM x YDIM x ZDIM x VDIM", source + ": header", 1LL << 28);
  const std::size_t needed = checked_product<std::size_t>({voxels, nv, static_cast<long long>(value_bytes)}, "bytes of the image", source + ": header");
  if (bytes.size() < header_size || bytes.size() - header_size < needed)
    throw InvalidInput("truncated: the header declares " + std::to_string(nx) + " x " + std::to_string(ny) + " x " + std::to_string(nz) +
                           " x " + std::to_string(nv) + " values of " + std::to_string(value_bytes) + " bytes (" +
                           std::to_string(needed) + " bytes after the " + std::to_string(header_size) + "-byte header), the file has " +
                           std::to_string(bytes.size() < header_size ? 0 : bytes.size() - header_size),
                       source + ": data");

  VolumeData data;
  if (nv == 1) data.attribute_names.push_back("value");
  else
    for (long long v = 0; v < nv; ++v) data.attribute_names.push_back("value_" + std::to_string(v));
  data.points.reserve(static_cast<std::size_t>(voxels));
  data.attributes.resize(static_cast<Eigen::Index>(voxels), static_cast<Eigen::Index>(nv));
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + header_size;
  std::size_t i = 0;
  for (long long k = 0; k < nz; ++k)
    for (long long j = 0; j < ny; ++j)
      for (long long l = 0; l < nx; ++l, ++i) {
        data.points.push_back(origin + Eigen::Vector3d(static_cast<double>(l), static_cast<double>(j), static_cast<double>(k)).cwiseProduct(spacing));
        for (long long v = 0; v < nv; ++v) {
          data.attributes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(v)) = load_value(p, type, value_bytes, big_endian);
          p += value_bytes;
        }
      }
  validate_volume_data(data, source);
  return data;
}

}  // namespace volspline
