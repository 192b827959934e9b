#include "volspline/mesh/mesh_reader.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <unordered_map>
#include <vector>

#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/mesh/parts.h"

namespace volspline {

namespace {

[[noreturn]] void fail(const std::string& source, const std::string& where, const std::string& message) {
  throw InvalidInput(message, where.empty() ? source : source + ": " + where);
}

std::string line_at(std::size_t line) { return "line " + std::to_string(line); }

std::string quoted(std::string_view token) {
  // Hostile files may hold anything; keep messages short and printable.
  std::string out = "'";
  for (const char c : token.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (token.size() > 40) out += "...";
  return out + "'";
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// std::from_chars ignores the locale (a comma decimal point can never sneak in) and reports
// overflow; it does not take a leading '+', which some writers emit.
bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), out);
  return result.ec == std::errc() && result.ptr == s.data() + s.size();
}

bool parse_integer(std::string_view s, long long& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto result = std::from_chars(s.data(), s.data() + s.size(), out);
  return result.ec == std::errc() && result.ptr == s.data() + s.size();
}

// Whitespace-separated words of one line.
std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// Tokens over a whole text, with the line each one is on; newlines are whitespace.
class Tokens {
 public:
  Tokens(std::string_view text, std::size_t start, std::size_t first_line)
      : text_(text), position_(start), line_(first_line) {}

  /// Moves to the start of the next token, so that current_line() is its line.
  void skip_space() {
    while (position_ < text_.size() && (is_space(text_[position_]) || text_[position_] == '\n')) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
  }
  std::optional<std::string_view> next() {
    skip_space();
    if (position_ >= text_.size()) return std::nullopt;
    token_line_ = line_;
    const std::size_t start = position_;
    while (position_ < text_.size() && !is_space(text_[position_]) && text_[position_] != '\n') ++position_;
    return text_.substr(start, position_ - start);
  }
  /// Skips the rest of the current line (the name after "solid", for instance).
  void skip_line() {
    while (position_ < text_.size() && text_[position_] != '\n') ++position_;
  }
  std::size_t line() const { return token_line_; }
  /// The line of the last token, or the current line before any: where a text that ends too
  /// early stops.
  std::size_t last_line() const { return token_line_ > 0 ? token_line_ : line_; }
  /// The line the cursor is on now (for "unexpected end of file" messages).
  std::size_t current_line() const { return line_; }
  std::size_t remaining() const { return text_.size() - position_; }

 private:
  std::string_view text_;
  std::size_t position_;
  std::size_t line_;
  std::size_t token_line_ = 0;
};

int checked_vertex_count(std::size_t count, const std::string& source, const std::string& where) {
  if (count >= static_cast<std::size_t>(INT_MAX)) {
    fail(source, where, "more than " + std::to_string(INT_MAX - 1) + " vertices, which a mesh cannot index");
  }
  return static_cast<int>(count);
}

// ---------------------------------------------------------------------------------------------
// OBJ

TriangleMesh parse_obj_text(std::string_view text, const std::string& source) {
  TriangleMesh mesh;
  struct ForwardReference {
    long long index;  // as written, 1-based
    std::size_t line;
  };
  std::vector<ForwardReference> forward;  // positive indices beyond the vertices read so far
  int part = kUnnamedPartNumber;
  std::size_t line_number = 0;
  std::size_t position = 0;
  std::vector<int> face;
  while (position < text.size()) {
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(position, end - position);
    position = end + 1;
    ++line_number;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto words = split_words(line);
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    if (keyword == "v") {
      if (words.size() < 4) fail(source, line_at(line_number), "expected three coordinates after 'v'");
      Eigen::Vector3d p;
      for (int i = 0; i < 3; ++i) {
        if (!parse_double(words[static_cast<std::size_t>(i + 1)], p[i]) || !std::isfinite(p[i])) {
          fail(source, line_at(line_number), "expected a finite number, got " + quoted(words[static_cast<std::size_t>(i + 1)]));
        }
      }
      checked_vertex_count(mesh.positions.size() + 1, source, line_at(line_number));
      mesh.add_vertex(p, Eigen::Vector3d::Zero());
    } else if (keyword == "f") {
      if (words.size() < 4) {
        fail(source, line_at(line_number), "a face needs at least 3 vertices, got " + std::to_string(words.size() - 1));
      }
      face.clear();
      const long long count = static_cast<long long>(mesh.positions.size());
      for (std::size_t i = 1; i < words.size(); ++i) {
        // v, v/vt, v//vn, v/vt/vn: the position index is before the first slash.
        const std::string_view word = words[i].substr(0, words[i].find('/'));
        long long index = 0;
        if (!parse_integer(word, index)) fail(source, line_at(line_number), "expected a vertex index, got " + quoted(words[i]));
        if (index == 0) fail(source, line_at(line_number), "face index 0 (OBJ indices start at 1)");
        if (index < 0) {
          // Relative: -1 is the last vertex read so far.
          if (-index > count) {
            fail(source, line_at(line_number), "relative face index " + std::to_string(index) + " reaches before the first vertex (" +
                                                   std::to_string(count) + " vertices so far)");
          }
          index = count + index;
        } else {
          if (index > count) {
            if (index > INT_MAX) {
              fail(source, line_at(line_number), "face index " + std::to_string(index) + " out of range");
            }
            forward.push_back({index, line_number});
          }
          index -= 1;
        }
        face.push_back(static_cast<int>(index));
      }
      // A convex polygon is exactly the fan of triangles from its first vertex; other polygons
      // would need a real triangulation, which OBJ exporters of quads and n-gons rarely need.
      for (std::size_t i = 1; i + 1 < face.size(); ++i) mesh.add_triangle(face[0], face[i], face[i + 1], part);
    } else if (keyword == "g") {
      part = kUnnamedPartNumber;
      long long n = 0;
      if (words.size() == 2 && words[1].starts_with("part_") && parse_integer(words[1].substr(5), n) && n >= INT_MIN &&
          n <= INT_MAX) {
        part = static_cast<int>(n);
      }
    }
    // Anything else (vt, vn, o, s, usemtl, mtllib, l, p, curves) carries nothing a triangle
    // mesh holds.
  }
  const long long count = static_cast<long long>(mesh.positions.size());
  for (const auto& reference : forward) {
    if (reference.index > count) {
      fail(source, line_at(reference.line), "face index " + std::to_string(reference.index) + " out of range (the file has " +
                                                std::to_string(count) + " vertices)");
    }
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// PLY

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<ScalarType> scalar_type(std::string_view name) {
  if (name == "char" || name == "int8") return ScalarType::Int8;
  if (name == "uchar" || name == "uint8") return ScalarType::UInt8;
  if (name == "short" || name == "int16") return ScalarType::Int16;
  if (name == "ushort" || name == "uint16") return ScalarType::UInt16;
  if (name == "int" || name == "int32") return ScalarType::Int32;
  if (name == "uint" || name == "uint32") return ScalarType::UInt32;
  if (name == "float" || name == "float32") return ScalarType::Float32;
  if (name == "double" || name == "float64") return ScalarType::Float64;
  return std::nullopt;
}

std::size_t scalar_size(ScalarType type) {
  switch (type) {
    case ScalarType::Int8:
    case ScalarType::UInt8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Float64:
      return 8;
  }
  return 8;
}

bool is_integer_type(ScalarType type) { return type != ScalarType::Float32 && type != ScalarType::Float64; }

template <class T>
T load(const char* bytes, bool big_endian) {
  char buffer[sizeof(T)];
  std::memcpy(buffer, bytes, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(buffer, buffer + sizeof(T));
  T value;
  std::memcpy(&value, buffer, sizeof(T));
  return value;
}

// Every scalar PLY type converts to double exactly (integers have at most 32 bits).
double load_scalar(ScalarType type, const char* bytes, bool big_endian) {
  switch (type) {
    case ScalarType::Int8:
      return load<std::int8_t>(bytes, big_endian);
    case ScalarType::UInt8:
      return load<std::uint8_t>(bytes, big_endian);
    case ScalarType::Int16:
      return load<std::int16_t>(bytes, big_endian);
    case ScalarType::UInt16:
      return load<std::uint16_t>(bytes, big_endian);
    case ScalarType::Int32:
      return load<std::int32_t>(bytes, big_endian);
    case ScalarType::UInt32:
      return load<std::uint32_t>(bytes, big_endian);
    case ScalarType::Float32:
      return load<float>(bytes, big_endian);
    case ScalarType::Float64:
      return load<double>(bytes, big_endian);
  }
  return 0;
}

struct PlyProperty {
  std::string name;
  bool list = false;
  ScalarType count_type = ScalarType::UInt8;
  ScalarType type = ScalarType::Float32;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t header_line = 0;

  int find(std::string_view property) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == property) return static_cast<int>(i);
    return -1;
  }
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

// Reads the property values of one element item, from text tokens or binary bytes, and says
// where the item starts for messages.
class PlyData {
 public:
  PlyData(std::string_view bytes, std::size_t start, std::size_t first_line, PlyFormat format, const std::string& source)
      : bytes_(bytes), position_(start), tokens_(bytes, start, first_line), format_(format), source_(source) {}

  std::size_t remaining() const { return format_ == PlyFormat::Ascii ? tokens_.remaining() : bytes_.size() - position_; }
  bool ascii() const { return format_ == PlyFormat::Ascii; }

  /// Location of the next value, e.g. "line 12" or "byte 345".
  std::string here() {
    if (!ascii()) return "byte " + std::to_string(position_);
    tokens_.skip_space();
    return line_at(tokens_.current_line());
  }

  double scalar(ScalarType type, const std::string& item) {
    if (ascii()) {
      const auto token = tokens_.next();
      if (!token) fail(source_, line_at(last_line()) + " (" + item + ")", "unexpected end of file");
      double value = 0;
      if (!parse_double(*token, value) || !std::isfinite(value) || (is_integer_type(type) && value != std::floor(value))) {
        fail(source_, line_at(tokens_.line()) + " (" + item + ")",
             std::string("expected ") + (is_integer_type(type) ? "an integer" : "a finite number") + ", got " + quoted(*token));
      }
      return value;
    }
    const std::size_t size = scalar_size(type);
    if (bytes_.size() - position_ < size) fail(source_, "byte " + std::to_string(position_) + " (" + item + ")", "unexpected end of file");
    const double value = load_scalar(type, bytes_.data() + position_, format_ == PlyFormat::BinaryBigEndian);
    if (!std::isfinite(value)) fail(source_, "byte " + std::to_string(position_) + " (" + item + ")", "a value is not finite");
    position_ += size;
    return value;
  }

  /// Checks that `count` values of `size` bytes can still be there before reading them.
  void require(std::size_t count, std::size_t size, const std::string& item) {
    if (ascii()) {
      // Every value takes at least one character and one separator.
      if (count > tokens_.remaining()) fail(source_, line_at(last_line()) + " (" + item + ")", "unexpected end of file");
    } else if (size > 0 && count > (bytes_.size() - position_) / size) {
      fail(source_, "byte " + std::to_string(position_) + " (" + item + ")", "unexpected end of file: a list of " +
                                                                               std::to_string(count) + " values does not fit");
    }
  }

 private:
  // The line of the last value read: where a file that ends too early stops.
  std::size_t last_line() const { return tokens_.last_line(); }
  std::string_view bytes_;
  std::size_t position_;
  Tokens tokens_;
  PlyFormat format_;
  const std::string& source_;
};

// The header: the format and the declared elements, and where the data starts.
struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_start = 0;  // byte after "end_header\n"
  std::size_t last_line = 0;   // the line number of "end_header"
};

// One "property ..." line of the header.
PlyProperty read_property_line(const std::vector<std::string_view>& words, const std::string& source, const std::string& where) {
  if (words.size() == 5 && words[1] == "list") {
    const auto count_type = scalar_type(words[2]);
    const auto type = scalar_type(words[3]);
    if (!count_type || !type || !is_integer_type(*count_type)) {
      fail(source, where, "expected 'property list COUNT_TYPE TYPE NAME' with an integer count type");
    }
    return {std::string(words[4]), true, *count_type, *type};
  }
  if (words.size() == 3) {
    const auto type = scalar_type(words[1]);
    if (!type) fail(source, where, "unknown property type " + quoted(words[1]));
    return {std::string(words[2]), false, ScalarType::UInt8, *type};
  }
  fail(source, where, "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
}

// Header: text lines up to "end_header".
PlyHeader read_ply_header(std::string_view bytes, const std::string& source) {
  PlyHeader header;
  std::size_t position = 0, line_number = 0;
  std::optional<PlyFormat> format;
  bool ended = false;
  while (!ended) {
    if (position >= bytes.size()) fail(source, line_at(line_number + 1), "unexpected end of file in the header (no end_header)");
    std::size_t end = bytes.find('\n', position);
    if (end == std::string_view::npos) end = bytes.size();
    const std::string_view line = bytes.substr(position, end - position);
    position = std::min(end + 1, bytes.size());
    ++line_number;
    const std::string where = line_at(line_number);
    const auto words = split_words(line);
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply") fail(source, where, "not a PLY file (the first line must be 'ply')");
      continue;
    }
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (words.size() != 3 || words[2] != "1.0") fail(source, where, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (words[1] == "ascii") format = PlyFormat::Ascii;
      else if (words[1] == "binary_little_endian") format = PlyFormat::BinaryLittleEndian;
      else if (words[1] == "binary_big_endian") format = PlyFormat::BinaryBigEndian;
      else fail(source, where, "unknown PLY format " + quoted(words[1]));
    } else if (keyword == "element") {
      long long count = 0;
      if (words.size() != 3 || !parse_integer(words[2], count) || count < 0) {
        fail(source, where, "expected 'element NAME COUNT' with a count >= 0");
      }
      header.elements.push_back({std::string(words[1]), static_cast<std::size_t>(count), {}, line_number});
    } else if (keyword == "property") {
      if (header.elements.empty()) fail(source, where, "a property before any element");
      header.elements.back().properties.push_back(read_property_line(words, source, where));
    } else if (keyword == "end_header") {
      ended = true;
    } else {
      fail(source, where, "unknown header line starting with " + quoted(keyword));
    }
  }
  if (!format) fail(source, "header", "no 'format' line");
  header.format = *format;
  header.data_start = position;
  header.last_line = line_number;
  return header;
}

// The element named "vertex" (the last of that name).
const PlyElement& vertex_element_of(const PlyHeader& header, const std::string& source) {
  const PlyElement* vertex_element = nullptr;
  for (const auto& e : header.elements) if (e.name == "vertex") vertex_element = &e;
  if (vertex_element == nullptr) fail(source, "header", "no 'element vertex'");
  return *vertex_element;
}

void check_vertex_coordinates(const PlyElement& vertex_element, const std::string& source) {
  for (const char* name : {"x", "y", "z"}) {
    const int i = vertex_element.find(name);
    if (i < 0 || vertex_element.properties[static_cast<std::size_t>(i)].list) {
      fail(source, line_at(vertex_element.header_line), std::string("element vertex has no scalar property ") + name);
    }
  }
}

// Reads the elements' data into a mesh: vertices (x y z and, where present, u v w), faces
// (vertex_indices fanned into triangles, an optional integer part); other elements are read
// and dropped. Face indices are checked against the vertex count at the end, since the vertex
// element may come after the faces.
class PlyMeshReader {
 public:
  PlyMeshReader(std::string_view bytes, const PlyHeader& header, const PlyElement& vertex_element, const std::string& source)
      : data_(bytes, header.data_start, header.last_line + 1, header.format, source), vertex_element_(vertex_element), source_(source) {}

  TriangleMesh read(const std::vector<PlyElement>& elements, int vertex_count) {
    for (const auto& element : elements) {
      if (element.properties.empty()) continue;  // items without properties occupy no bytes
      check_count_fits(element);
      read_element(element);
    }
    check_face_indices(vertex_count);
    return std::move(mesh_);
  }

 private:
  // Which properties of an element the mesh takes.
  struct Roles {
    bool vertex = false, face = false;
    int indices = -1, part = -1;
    std::array<int, 6> coordinate{-1, -1, -1, -1, -1, -1};  // x y z u v w
  };

  // A declared count is only believed as far as the remaining bytes can back it: every item
  // takes at least this many bytes (binary) or tokens (ascii).
  void check_count_fits(const PlyElement& element) {
    std::size_t minimum = 0;
    for (const auto& p : element.properties) minimum += data_.ascii() ? 1 : scalar_size(p.list ? p.count_type : p.type);
    if (element.count > data_.remaining() / minimum) {
      fail(source_, line_at(element.header_line), "element " + element.name + " declares " + std::to_string(element.count) +
                                                      " items, more than the remaining " + std::to_string(data_.remaining()) +
                                                      " bytes can hold");
    }
  }

  Roles roles_of(const PlyElement& element) {
    Roles roles;
    roles.vertex = &element == &vertex_element_;
    roles.face = element.name == "face";
    if (roles.vertex) {
      const char* names[6] = {"x", "y", "z", "u", "v", "w"};
      for (int i = 0; i < 6; ++i) {
        const int p = element.find(names[i]);
        if (p >= 0 && !element.properties[static_cast<std::size_t>(p)].list) roles.coordinate[static_cast<std::size_t>(i)] = p;
      }
      mesh_.positions.reserve(element.count);
      mesh_.parameters.reserve(element.count);
    }
    if (roles.face) {
      roles.indices = element.find("vertex_indices");
      if (roles.indices < 0) roles.indices = element.find("vertex_index");
      if (roles.indices < 0 || !element.properties[static_cast<std::size_t>(roles.indices)].list) {
        fail(source_, line_at(element.header_line), "element face has no list property vertex_indices");
      }
      roles.part = element.find("part");
      if (roles.part >= 0) {
        const auto& p = element.properties[static_cast<std::size_t>(roles.part)];
        if (p.list || !is_integer_type(p.type)) fail(source_, line_at(element.header_line), "property part must be a scalar integer");
      }
    }
    return roles;
  }

  void read_element(const PlyElement& element) {
    const Roles roles = roles_of(element);
    std::vector<double> values(element.properties.size());
    for (std::size_t item = 0; item < element.count; ++item) {
      const std::string name = element.name + " " + std::to_string(item);
      const std::string start = data_.here();
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const auto& property = element.properties[p];
        if (property.list) {
          read_list(property, roles.face && static_cast<int>(p) == roles.indices, name, start);
        } else {
          values[p] = data_.scalar(property.type, name);
        }
      }
      if (roles.vertex) add_vertex(roles, values);
      if (roles.face) add_face(roles, values, item, name, start);
    }
  }

  // A list property; the face's vertex indices are kept in face_, any other list is dropped.
  void read_list(const PlyProperty& property, bool indices, const std::string& name, const std::string& start) {
    const double n = data_.scalar(property.count_type, name);
    if (n < 0) fail(source_, start + " (" + name + ")", "a negative list length");
    const auto length = static_cast<std::size_t>(n);
    data_.require(length, scalar_size(property.type), name);
    if (indices) {
      if (length < 3) fail(source_, start + " (" + name + ")", "a face needs at least 3 vertices, got " + std::to_string(length));
      face_.clear();
    }
    for (std::size_t i = 0; i < length; ++i) {
      const double value = data_.scalar(property.type, name);
      if (!indices) continue;
      if (!is_integer_type(property.type) && value != std::floor(value)) {
        fail(source_, start + " (" + name + ")", "vertex index " + format_double(value) + " is not an integer");
      }
      if (value < 0 || value >= static_cast<double>(INT_MAX)) {
        fail(source_, start + " (" + name + ")", "vertex index " + format_double(value) + " out of range");
      }
      face_.push_back(static_cast<int>(value));
    }
  }

  void add_vertex(const Roles& roles, const std::vector<double>& values) {
    Eigen::Vector3d position, parameter = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) position[i] = values[static_cast<std::size_t>(roles.coordinate[static_cast<std::size_t>(i)])];
    for (int i = 0; i < 3; ++i) {
      const int p = roles.coordinate[static_cast<std::size_t>(i + 3)];
      if (p >= 0) parameter[i] = values[static_cast<std::size_t>(p)];
    }
    mesh_.add_vertex(position, parameter);
  }

  void add_face(const Roles& roles, const std::vector<double>& values, std::size_t item, const std::string& name,
                const std::string& start) {
    int part = kUnnamedPartNumber;
    if (roles.part >= 0) {
      const double value = values[static_cast<std::size_t>(roles.part)];
      if (value < INT_MIN || value > INT_MAX) fail(source_, start + " (" + name + ")", "part out of range");
      part = static_cast<int>(value);
    }
    face_origins_.push_back({start, item});
    for (std::size_t i = 1; i + 1 < face_.size(); ++i) {
      mesh_.add_triangle(face_[0], face_[i], face_[i + 1], part);
      triangle_face_.push_back(face_origins_.size() - 1);
    }
  }

  void check_face_indices(int vertex_count) const {
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (const int index : mesh_.triangles[t]) {
        if (index >= vertex_count) {
          const auto& origin = face_origins_[triangle_face_[t]];
          fail(source_, origin.where + " (face " + std::to_string(origin.face) + ")",
               "vertex index " + std::to_string(index) + " out of range (the file has " + std::to_string(vertex_count) + " vertices)");
        }
      }
    }
  }

  // Where each triangle's face item began, to name it if an index turns out to be out of range.
  struct FaceOrigin {
    std::string where;
    std::size_t face;
  };

  PlyData data_;
  const PlyElement& vertex_element_;
  const std::string& source_;
  TriangleMesh mesh_;
  std::vector<int> face_;
  std::vector<FaceOrigin> face_origins_;
  std::vector<std::size_t> triangle_face_;  // index into face_origins_ per triangle
};

TriangleMesh parse_ply_bytes(std::string_view bytes, const std::string& source) {
  const PlyHeader header = read_ply_header(bytes, source);
  const PlyElement& vertex_element = vertex_element_of(header, source);
  const int vertex_count = checked_vertex_count(vertex_element.count, source, line_at(vertex_element.header_line));
  check_vertex_coordinates(vertex_element, source);
  return PlyMeshReader(bytes, header, vertex_element, source).read(header.elements, vertex_count);
}

// ---------------------------------------------------------------------------------------------
// STL

// STL repeats every shared corner once per triangle; welding exactly equal positions restores
// the connectivity without moving anything. -0 and +0 are the same position.
class Welder {
 public:
  explicit Welder(TriangleMesh& mesh) : mesh_(mesh) {}
  int add(Eigen::Vector3d p, const std::string& source, const std::string& where) {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(p[i])) fail(source, where, "a vertex coordinate is not finite");
      p[i] += 0.0;
    }
    const Key key{p.x(), p.y(), p.z()};
    const auto [it, added] = index_.try_emplace(key, static_cast<int>(mesh_.positions.size()));
    if (added) {
      checked_vertex_count(mesh_.positions.size() + 1, source, where);
      mesh_.add_vertex(p, Eigen::Vector3d::Zero());
    }
    return it->second;
  }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 0;
      for (const double x : k) h = h * 1000003u ^ std::hash<std::uint64_t>{}(std::bit_cast<std::uint64_t>(x));
      return h;
    }
  };
  TriangleMesh& mesh_;
  std::unordered_map<Key, int, Hash> index_;
};

TriangleMesh parse_binary_stl(std::string_view bytes, const std::string& source) {
  if (bytes.size() < 84) {
    fail(source, "byte " + std::to_string(bytes.size()), "a binary STL file needs an 84-byte header, the file has " + std::to_string(bytes.size()) + " bytes");
  }
  const std::uint32_t count = load<std::uint32_t>(bytes.data() + 80, false);
  if (count > (bytes.size() - 84) / 50) {
    fail(source, "byte 80", "the header declares " + std::to_string(count) + " triangles (" + std::to_string(84 + 50ull * count) +
                                " bytes), the file has only " + std::to_string(bytes.size()) + " bytes");
  }
  TriangleMesh mesh;
  Welder welder(mesh);
  mesh.triangles.reserve(count);
  mesh.parts.reserve(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::size_t offset = 84 + 50 * static_cast<std::size_t>(t);
    const std::string where = "byte " + std::to_string(offset) + " (triangle " + std::to_string(t) + ")";
    std::array<int, 3> corner{};
    for (int v = 0; v < 3; ++v) {
      Eigen::Vector3d p;
      for (int i = 0; i < 3; ++i) p[i] = load<float>(bytes.data() + offset + 12 + 12 * v + 4 * i, false);
      corner[static_cast<std::size_t>(v)] = welder.add(p, source, where);
    }
    mesh.add_triangle(corner[0], corner[1], corner[2], kUnnamedPartNumber);
  }
  return mesh;
}

TriangleMesh parse_ascii_stl(std::string_view text, const std::string& source) {
  TriangleMesh mesh;
  Welder welder(mesh);
  Tokens tokens(text, 0, 1);
  const auto expect = [&](std::string_view word) {
    const auto token = tokens.next();
    if (!token) fail(source, line_at(tokens.last_line()), "unexpected end of file, expected '" + std::string(word) + "'");
    if (*token != word) fail(source, line_at(tokens.line()), "expected '" + std::string(word) + "', got " + quoted(*token));
  };
  const auto number = [&] {
    const auto token = tokens.next();
    if (!token) fail(source, line_at(tokens.last_line()), "unexpected end of file, expected a number");
    double value = 0;
    if (!parse_double(*token, value) || !std::isfinite(value)) fail(source, line_at(tokens.line()), "expected a finite number, got " + quoted(*token));
    return value;
  };
  expect("solid");
  tokens.skip_line();  // the solid's name
  while (true) {
    const auto token = tokens.next();
    if (!token) fail(source, line_at(tokens.last_line()), "unexpected end of file, expected 'facet' or 'endsolid'");
    if (*token == "endsolid") {
      tokens.skip_line();
      // Some files hold several solids one after another.
      const auto more = tokens.next();
      if (!more) break;
      if (*more != "solid") fail(source, line_at(tokens.line()), "expected 'solid' or the end of the file, got " + quoted(*more));
      tokens.skip_line();
      continue;
    }
    if (*token != "facet") fail(source, line_at(tokens.line()), "expected 'facet' or 'endsolid', got " + quoted(*token));
    expect("normal");
    for (int i = 0; i < 3; ++i) number();  // recomputed from the corners by whoever needs it
    expect("outer");
    expect("loop");
    std::vector<int> corners;
    while (true) {
      const auto word = tokens.next();
      if (!word) fail(source, line_at(tokens.last_line()), "unexpected end of file, expected 'vertex' or 'endloop'");
      if (*word == "endloop") break;
      if (*word != "vertex") fail(source, line_at(tokens.line()), "expected 'vertex' or 'endloop', got " + quoted(*word));
      const std::size_t line = tokens.line();
      Eigen::Vector3d p;
      for (int i = 0; i < 3; ++i) p[i] = number();
      corners.push_back(welder.add(p, source, line_at(line)));
    }
    if (corners.size() < 3) fail(source, line_at(tokens.line()), "a facet needs at least 3 vertices, got " + std::to_string(corners.size()));
    expect("endfacet");
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) mesh.add_triangle(corners[0], corners[i], corners[i + 1], kUnnamedPartNumber);
  }
  return mesh;
}

// The range of coordinates (core/coordinate_range.h), checked on the mesh a parser made, at the
// vertex (numbered from 1, as OBJ numbers them) and its coordinate.
TriangleMesh mesh_in_coordinate_range(TriangleMesh mesh, const std::string& source) {
  const std::size_t n = mesh.positions.size();
  if (n == 0) return mesh;
  check_point_coordinate_range(
      mesh.positions.front().data(), n, 3, 3,
      [&](std::size_t i, std::size_t c) {
        return source + ": vertex " + std::to_string(i + 1) + " of " + std::to_string(n) + ", " + std::string(1, "xyz"[c]);
      },
      source, "vertices", "docs/formats.md");
  return mesh;
}

}  // namespace

TriangleMesh parse_obj(std::string_view bytes, const std::string& source) { return mesh_in_coordinate_range(parse_obj_text(bytes, source), source); }

TriangleMesh parse_ply(std::string_view bytes, const std::string& source) { return mesh_in_coordinate_range(parse_ply_bytes(bytes, source), source); }

TriangleMesh parse_stl(std::string_view bytes, const std::string& source) {
  std::size_t first = 0;
  while (first < bytes.size() && (is_space(bytes[first]) || bytes[first] == '\n')) ++first;
  const bool says_solid = bytes.substr(first, 5) == "solid";
  const bool binary_size = bytes.size() >= 84 && bytes.size() == 84 + 50ull * load<std::uint32_t>(bytes.data() + 80, false);
  if (says_solid && !binary_size) return mesh_in_coordinate_range(parse_ascii_stl(bytes, source), source);
  return mesh_in_coordinate_range(parse_binary_stl(bytes, source), source);
}

TriangleMesh parse_mesh(std::string_view bytes, MeshFormat format, const std::string& source) {
  switch (format) {
    case MeshFormat::Ply:
      return parse_ply(bytes, source);
    case MeshFormat::Obj:
      return parse_obj(bytes, source);
    case MeshFormat::Stl:
      return parse_stl(bytes, source);
    case MeshFormat::Glb:
      throw InvalidInput("glTF (.glb) meshes are written, not read: give a .ply, .obj or .stl file", source);
  }
  throw InvalidInput("unknown mesh format", source);
}

TriangleMesh parse_off(std::string_view bytes, const std::string& source) {
  // Tokens with their line numbers; '#' starts a comment.
  std::vector<std::pair<std::string_view, int>> tokens;
  int line = 1;
  for (std::size_t i = 0; i < bytes.size();) {
    const char c = bytes[i];
    if (c == '\n') {
      ++line, ++i;
    } else if (c == '#') {
      while (i < bytes.size() && bytes[i] != '\n') ++i;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else {
      const std::size_t start = i;
      while (i < bytes.size() && bytes[i] != ' ' && bytes[i] != '\t' && bytes[i] != '\r' && bytes[i] != '\n' && bytes[i] != '#') ++i;
      tokens.emplace_back(bytes.substr(start, i - start), line);
    }
  }
  std::size_t at = 0;
  auto where = [&](std::size_t t) { return source + ": line " + std::to_string(t < tokens.size() ? tokens[t].second : line); };
  auto number = [&](const char* what) {
    if (at >= tokens.size()) throw InvalidInput(std::string("expected ") + what + ", got the end of the file", where(at));
    const std::string text(tokens[at].first);
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !std::isfinite(x))
      throw InvalidInput(std::string("expected ") + what + ", got '" + text.substr(0, 40) + "'", where(at));
    ++at;
    return x;
  };
  auto count = [&](const char* what, double limit) {
    const std::size_t t = at;
    const double x = number(what);
    if (x < 0 || x != std::floor(x) || x > limit)
      throw InvalidInput(std::string("expected ") + what + " (an integer from 0 to " + std::to_string(static_cast<long long>(limit)) + ")", where(t));
    return static_cast<long long>(x);
  };
  if (tokens.empty() || tokens[0].first != "OFF") throw InvalidInput("expected the header OFF", where(0));
  at = 1;
  // Every vertex takes at least 6 bytes and every face 8: counts beyond that are not backed by
  // the file, so nothing is reserved for them.
  const long long vertices = count("the vertex count", static_cast<double>(bytes.size() / 6));
  const long long faces = count("the face count", static_cast<double>(bytes.size() / 8));
  count("the edge count", 1e18);
  TriangleMesh mesh;
  for (long long v = 0; v < vertices; ++v) {
    const double x = number("a vertex coordinate"), y = number("a vertex coordinate"), z = number("a vertex coordinate");
    mesh.add_vertex(Eigen::Vector3d(x, y, z), Eigen::Vector3d::Zero());
  }
  for (long long f = 0; f < faces; ++f) {
    const std::size_t face_token = at;
    const long long corners = count("a face's vertex count", 1e6);
    if (corners < 3) throw InvalidInput("expected a face of 3 or more vertices, got " + std::to_string(corners), where(face_token));
    const int face_line = tokens[face_token].second;
    std::vector<int> index;
    for (long long k = 0; k < corners; ++k) index.push_back(static_cast<int>(count("a vertex index", static_cast<double>(vertices - 1))));
    // Colour values may follow on the face's line; skip them.
    while (at < tokens.size() && tokens[at].second == face_line) ++at;
    for (long long k = 1; k + 1 < corners; ++k)
      mesh.add_triangle(index[0], index[static_cast<std::size_t>(k)], index[static_cast<std::size_t>(k + 1)], kUnnamedPartNumber);
  }
  return mesh_in_coordinate_range(std::move(mesh), source);
}

TriangleMesh read_mesh(const std::filesystem::path& path) {
  if (path.extension() == ".off" || path.extension() == ".OFF") return parse_off(read_file(path), path.string());
  const MeshFormat format = mesh_format_from_path(path);
  const std::string bytes = read_file(path);
  return parse_mesh(bytes, format, path.string());
}

}  // namespace volspline
