// PLY vertex properties as volume data (io/volume_data.h): x, y, z and every other scalar
// property of the `vertex` element. Only what volume data needs is read; triangle meshes are
// read by mesh/mesh_reader.h.
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "text_numbers.h"
#include "volspline/core/error.h"
#include "volspline/io/volume_data.h"

namespace volspline {
namespace {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyScalar {
  int bytes = 0;
  bool is_signed = false, is_float = false;
};

std::optional<PlyScalar> scalar_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyScalar{1, true, false};
  if (name == "uchar" || name == "uint8") return PlyScalar{1, false, false};
  if (name == "short" || name == "int16") return PlyScalar{2, true, false};
  if (name == "ushort" || name == "uint16") return PlyScalar{2, false, false};
  if (name == "int" || name == "int32") return PlyScalar{4, true, false};
  if (name == "uint" || name == "uint32") return PlyScalar{4, false, false};
  if (name == "float" || name == "float32") return PlyScalar{4, true, true};
  if (name == "double" || name == "float64") return PlyScalar{8, true, true};
  return std::nullopt;
}

struct PlyProperty {
  std::string name;
  PlyScalar type;
  bool list = false;
  PlyScalar count_type;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// Reads values in the file's order, text tokens or binary scalars.
class PlyValues {
 public:
  PlyValues(std::string_view bytes, std::size_t position, PlyFormat format) : bytes_(bytes), position_(position), format_(format) {}
  // The next value, or nothing at the end of the data or (ascii) for a token that is no number.
  std::optional<double> next(const PlyScalar& type) {
    if (format_ == PlyFormat::Ascii) {
      while (position_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[position_]))) ++position_;
      const std::size_t start = position_;
      while (position_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[position_]))) ++position_;
      if (position_ == start) return std::nullopt;
      return detail::parse_double(bytes_.substr(start, position_ - start));
    }
    if (bytes_.size() - position_ < static_cast<std::size_t>(type.bytes)) return std::nullopt;
    unsigned char b[8];
    const bool big = format_ == PlyFormat::BinaryBigEndian;
    for (int i = 0; i < type.bytes; ++i)
      b[i] = static_cast<unsigned char>(bytes_[position_ + static_cast<std::size_t>(big ? type.bytes - 1 - i : i)]);
    position_ += static_cast<std::size_t>(type.bytes);
    if (type.is_float) {
      if (type.bytes == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return static_cast<double>(f);
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    std::uint64_t u = 0;
    for (int i = type.bytes - 1; i >= 0; --i) u = (u << 8) | b[i];
    if (type.is_signed && type.bytes < 8 && ((u >> (8 * type.bytes - 1)) & 1u)) u |= ~std::uint64_t{0} << (8 * type.bytes);
    std::int64_t s;
    std::memcpy(&s, &u, 8);
    return type.is_signed ? static_cast<double>(s) : static_cast<double>(u);
  }

 private:
  std::string_view bytes_;
  std::size_t position_;
  PlyFormat format_;
};

}  // namespace

VolumeData parse_volume_ply(std::string_view bytes, const std::string& source) {
  std::size_t start = 0, line_number = 0;
  std::optional<PlyFormat> format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (start < bytes.size() && !ended) {
    const std::size_t end = std::min(bytes.find('\n', start), bytes.size());
    const std::string_view line = bytes.substr(start, end - start);
    start = end + 1;
    ++line_number;
    const std::string where = source + ": line " + std::to_string(line_number);
    const std::vector<std::string_view> words = words_of(line);
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") throw InvalidInput("not a PLY file (the first line must be 'ply')", where);
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "format") {
      if (words.size() != 3) throw InvalidInput("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'", where);
      if (words[1] == "ascii") format = PlyFormat::Ascii;
      else if (words[1] == "binary_little_endian") format = PlyFormat::BinaryLittleEndian;
      else if (words[1] == "binary_big_endian") format = PlyFormat::BinaryBigEndian;
      else throw InvalidInput("unknown PLY format " + detail::quoted_token(words[1]), where);
    } else if (words[0] == "element") {
      const auto count = words.size() == 3 ? detail::parse_integer(words[2], 0, 1LL << 31) : std::nullopt;
      if (!count) throw InvalidInput("expected 'element NAME COUNT' with a count in 0..2^31", where);
      elements.push_back({std::string(words[1]), *count, {}});
    } else if (words[0] == "property") {
      if (elements.empty()) throw InvalidInput("a property before any element", where);
      PlyProperty property;
      if (words.size() == 5 && words[1] == "list") {
        const auto count_type = scalar_type(words[2]), type = scalar_type(words[3]);
        if (!count_type || !type || count_type->is_float) throw InvalidInput("expected 'property list INTEGER_TYPE TYPE NAME'", where);
        property = {std::string(words[4]), *type, true, *count_type};
      } else {
        const auto type = words.size() == 3 ? scalar_type(words[1]) : std::nullopt;
        if (!type) throw InvalidInput("expected 'property TYPE NAME' with TYPE one of char, uchar, short, ushort, int, uint, float, double", where);
        property = {std::string(words[2]), *type, false, {}};
      }
      for (const auto& p : elements.back().properties)
        if (p.name == property.name) throw InvalidInput("property '" + property.name + "' appears twice", where);
      elements.back().properties.push_back(property);
    } else if (words[0] == "end_header") {
      ended = true;
    } else {
      throw InvalidInput("unknown header keyword " + detail::quoted_token(words[0]), where);
    }
  }
  if (!ended) throw InvalidInput("the header does not end (expected 'end_header')", source + ": line " + std::to_string(line_number));
  if (!format) throw InvalidInput("the header has no 'format' line", source + ": line " + std::to_string(line_number));

  VolumeData data;
  std::array<int, 3> xyz{-1, -1, -1};
  const PlyElement* vertex = nullptr;
  for (const auto& e : elements)
    if (e.name == "vertex") vertex = &e;
  if (!vertex) throw InvalidInput("no 'vertex' element in the header", source);
  std::vector<int> attribute_properties;
  for (std::size_t p = 0; p < vertex->properties.size(); ++p) {
    const auto& property = vertex->properties[p];
    if (property.list) continue;
    if (property.name == "x" || property.name == "y" || property.name == "z")
      xyz[static_cast<std::size_t>(property.name[0] - 'x')] = static_cast<int>(p);
    else {
      attribute_properties.push_back(static_cast<int>(p));
      data.attribute_names.push_back(property.name);
    }
  }
  for (int c = 0; c < 3; ++c)
    if (xyz[static_cast<std::size_t>(c)] < 0)
      throw InvalidInput(std::string("the vertex element has no property ") + static_cast<char>('x' + c), source);

  PlyValues values(bytes, start, *format);
  const auto skip_element = [&](const PlyElement& e, long long index, std::vector<double>* row) {
    const std::string where = source + ": " + e.name + " " + std::to_string(index);
    for (std::size_t p = 0; p < e.properties.size(); ++p) {
      const auto& property = e.properties[p];
      if (property.list) {
        const auto count = values.next(property.count_type);
        if (!count || *count < 0 || *count > 1e6 || *count != std::floor(*count))
          throw InvalidInput("property '" + property.name + "': expected a list count, got none or an invalid one (truncated?)", where);
        for (long long k = 0; k < static_cast<long long>(*count); ++k)
          if (!values.next(property.type)) throw InvalidInput("property '" + property.name + "': the list is truncated", where);
        continue;
      }
      const auto value = values.next(property.type);
      if (!value) throw InvalidInput("property '" + property.name + "': expected a finite number, got none or an invalid one (truncated?)", where);
      if (row) (*row)[p] = *value;
    }
  };
  std::vector<double> row(vertex->properties.size());
  data.points.reserve(static_cast<std::size_t>(std::min<long long>(vertex->count, 1 << 24)));
  std::vector<double> attribute_values;
  for (const auto& e : elements) {
    for (long long i = 0; i < e.count; ++i) {
      if (&e != vertex) {
        skip_element(e, i, nullptr);
        continue;
      }
      skip_element(e, i, &row);
      data.points.emplace_back(row[static_cast<std::size_t>(xyz[0])], row[static_cast<std::size_t>(xyz[1])], row[static_cast<std::size_t>(xyz[2])]);
      for (int p : attribute_properties) attribute_values.push_back(row[static_cast<std::size_t>(p)]);
    }
    if (&e == vertex) break;  // what follows the vertices is not needed
  }
  if (data.points.empty()) throw InvalidInput("the vertex element has no vertices", source);
  const std::size_t k = attribute_properties.size();
  data.attributes.resize(static_cast<Eigen::Index>(data.points.size()), static_cast<Eigen::Index>(k));
  for (std::size_t i = 0; i < data.points.size(); ++i)
    for (std::size_t a = 0; a < k; ++a) data.attributes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a)) = attribute_values[i * k + a];
  validate_volume_data(data, source);
  return data;
}

}  // namespace volspline
