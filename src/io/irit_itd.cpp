#include "volspline/io/irit_itd.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <utility>
#include <vector>

#include "text_numbers.h"
#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/coordinate_range.h"

namespace volspline {

namespace {

/// IRIT's point types end at 9 coordinates (CAGD_MAX_PT_COORD).
constexpr int kMaxIritCoordinates = 9;

struct Token {
  std::string_view text;
  std::size_t line;
  bool is(char c) const { return text.size() == 1 && text[0] == c; }
};

std::string upper(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

/// Brackets are tokens of their own; '#' starts a comment to the end of the line; a double-quoted
/// string (attribute values) is one token.
std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  std::size_t line = 1;
  std::size_t i = 0;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (space(c)) {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '[' || c == ']') {
      tokens.push_back({text.substr(i, 1), line});
      ++i;
    } else if (c == '"') {
      const std::size_t start = i;
      const std::size_t start_line = line;
      ++i;
      while (i < text.size() && text[i] != '"') {
        if (text[i] == '\n') ++line;
        ++i;
      }
      if (i >= text.size()) throw InvalidInput("unterminated string (a '\"' without its closing '\"')", "line " + std::to_string(start_line));
      ++i;
      tokens.push_back({text.substr(start, i - start), start_line});
    } else {
      const std::size_t start = i;
      while (i < text.size() && !space(text[i]) && text[i] != '[' && text[i] != ']' && text[i] != '"') ++i;
      tokens.push_back({text.substr(start, i - start), line});
    }
  }
  return tokens;
}

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::size_t last_line) : tokens_(std::move(tokens)), last_line_(last_line) {}

  Model model() {
    Model result;
    while (!at_end()) item(result, "");
    if (result.objects.empty()) {
      throw InvalidInput("expected at least one [CURVE ...], [SURFACE ...] or [TRIVAR ...], got none", "line " + std::to_string(last_line_));
    }
    return result;
  }

 private:
  bool at_end() const { return position_ >= tokens_.size(); }

  std::string where() const {
    return "line " + std::to_string(at_end() ? last_line_ : tokens_[position_].line);
  }

  std::string shown() const { return at_end() ? "the end of the file" : detail::quoted_token(tokens_[position_].text); }

  [[noreturn]] void fail(const std::string& expected) const {
    throw InvalidInput("expected " + expected + ", got " + shown(), where());
  }

  const Token& next(const std::string& expected) {
    if (at_end()) fail(expected);
    return tokens_[position_++];
  }

  void expect(char bracket, const std::string& context) {
    if (at_end() || !tokens_[position_].is(bracket)) fail(std::string("'") + bracket + "' " + context);
    ++position_;
  }

  bool peek(char bracket) const { return !at_end() && tokens_[position_].is(bracket); }

  /// Skips a bracketed group (an attribute such as [COLOR 4]) that starts at the current '['.
  void skip_group() {
    const std::size_t start = position_;
    int depth = 0;
    do {
      if (at_end()) {
        position_ = start;
        fail("']' closing the attribute that starts here");
      }
      if (tokens_[position_].is('[')) ++depth;
      if (tokens_[position_].is(']')) --depth;
      ++position_;
    } while (depth > 0);
  }

  bool next_is_geometry_or_object() const {
    if (position_ + 1 >= tokens_.size() || !tokens_[position_].is('[')) return false;
    const std::string word = upper(tokens_[position_ + 1].text);
    return word == "OBJECT" || word == "CURVE" || word == "SURFACE" || word == "TRIVAR";
  }

  /// `depth`: the OBJECTs around this item. Nested OBJECTs recurse, so their depth is bounded
  /// (kMaxIritObjectDepth) before a hostile file can exhaust the stack.
  void item(Model& model, const std::string& name, std::size_t depth = 0) {
    expect('[', "opening an [OBJECT ...], [CURVE ...], [SURFACE ...] or [TRIVAR ...]");
    const std::size_t keyword_at = position_;
    const std::string keyword = upper(next("OBJECT, CURVE, SURFACE or TRIVAR").text);
    if (keyword == "OBJECT") {
      if (depth >= kMaxIritObjectDepth) {
        position_ = keyword_at;
        fail("a CURVE, SURFACE or TRIVAR: OBJECTs may be nested at most " + std::to_string(kMaxIritObjectDepth) + " deep");
      }
      while (peek('[') && !next_is_geometry_or_object()) skip_group();  // [OBJECT [COLOR 4] NAME ...
      if (peek('[') || peek(']')) fail("the object's name");
      std::string object_name(next("the object's name").text);
      if (upper(object_name) == "NONE") object_name.clear();
      while (!peek(']')) {
        if (at_end()) fail("']' closing the OBJECT");
        item(model, object_name, depth + 1);
      }
      ++position_;
      return;
    }
    int parameters = 0;
    if (keyword == "CURVE") parameters = 1;
    if (keyword == "SURFACE") parameters = 2;
    if (keyword == "TRIVAR") parameters = 3;
    if (parameters == 0) {
      position_ = keyword_at;
      fail("OBJECT, CURVE, SURFACE or TRIVAR (only B-spline and Bezier curves, surfaces and trivariates are read)");
    }
    const std::string kind = upper(next("BSPLINE or BEZIER").text);
    if (kind != "BSPLINE" && kind != "BEZIER") {
      --position_;
      fail("BSPLINE or BEZIER after " + keyword);
    }
    const bool bezier = kind == "BEZIER";
    const auto read = [&]() -> SplineObject {
      switch (parameters) {
        case 1:
          return spline<1>(bezier);
        case 2:
          return spline<2>(bezier);
        default:
          return spline<3>(bezier);
      }
    };
    model.objects.push_back(ModelObject{name, bezier, read(), nullptr});
  }

  long long integer(long long lo, long long hi, const std::string& what) {
    if (at_end() || tokens_[position_].is('[') || tokens_[position_].is(']')) fail(what);
    const auto value = detail::parse_integer(tokens_[position_].text, lo, hi);
    if (!value) fail(what);
    ++position_;
    return *value;
  }

  double number(const std::string& what) {
    if (at_end()) fail(what);
    const auto value = detail::parse_double(tokens_[position_].text);
    if (!value) fail(what);
    ++position_;
    return *value;
  }

  template <int D>
  TensorSpline<D> spline(bool bezier) {
    const std::string header_line = where();
    while (peek('[')) skip_group();  // attributes of the geometry
    std::array<long long, D> counts{};
    std::array<int, D> orders{};
    static const char* const kDirections[] = {"u", "v", "w"};
    const long long max_order = kMaxModelDegree + 1;
    for (int d = 0; d < D; ++d) {
      counts[static_cast<std::size_t>(d)] =
          integer(2, INT32_MAX, std::string("the number of control points in ") + kDirections[d] + " (an integer >= 2)");
    }
    if (bezier) {
      for (int d = 0; d < D; ++d) {
        if (counts[static_cast<std::size_t>(d)] > max_order) {
          position_ -= static_cast<std::size_t>(D - d);
          fail("a Bezier count (order) of at most " + std::to_string(max_order));
        }
        orders[static_cast<std::size_t>(d)] = static_cast<int>(counts[static_cast<std::size_t>(d)]);
      }
    } else {
      for (int d = 0; d < D; ++d) {
        orders[static_cast<std::size_t>(d)] = static_cast<int>(
            integer(2, max_order,
                    std::string("the order (degree + 1, from 2 to ") + std::to_string(max_order) + ") in " + kDirections[d]));
        if (orders[static_cast<std::size_t>(d)] > counts[static_cast<std::size_t>(d)]) {
          --position_;
          fail("an order of at most the number of control points (" + std::to_string(counts[static_cast<std::size_t>(d)]) + ")");
        }
      }
    }
    const Token& type = next("the point type E1..E9 or P1..P9");
    const std::string type_text = upper(type.text);
    if (type_text.size() != 2 || (type_text[0] != 'E' && type_text[0] != 'P') || type_text[1] < '1' || type_text[1] > '9') {
      --position_;
      fail("the point type E1..E9 or P1..P9");
    }
    const bool rational = type_text[0] == 'P';
    const int k = type_text[1] - '0';

    std::vector<KnotVector> knots;
    for (int d = 0; d < D; ++d) {
      const std::size_t count = static_cast<std::size_t>(counts[static_cast<std::size_t>(d)]);
      const int degree = orders[static_cast<std::size_t>(d)] - 1;
      if (bezier) {
        knots.push_back(KnotVector::bezier(degree));
        continue;
      }
      const std::string kv_line = where();
      expect('[', std::string("opening the knot vector [KV ...] of ") + kDirections[d]);
      const std::string kv = upper(next("KV").text);
      if (kv == "KVP") {
        --position_;
        fail("KV (periodic knot vectors, KVP, are not supported)");
      }
      if (kv != "KV") {
        --position_;
        fail("KV");
      }
      const std::size_t expected = count + static_cast<std::size_t>(degree) + 1;
      std::vector<double> values;
      while (!peek(']')) {
        if (values.size() == expected) fail("']' after the " + std::to_string(expected) + " knots of " + kDirections[d] + " (count + order)");
        values.push_back(number(std::string("a knot (a finite number) or ']'")));
      }
      if (values.size() != expected) {
        fail("the " + std::to_string(expected) + " knots of " + kDirections[d] + " (count " + std::to_string(count) + " + order " +
             std::to_string(degree + 1) + "), not " + std::to_string(values.size()) + " then");
      }
      ++position_;
      try {
        knots.emplace_back(degree, std::move(values));
      } catch (const InvalidInput& e) {
        throw InvalidInput(e.message() + " (knot " + e.where() + " of " + kDirections[d] + ")", kv_line);
      }
    }

    std::uint64_t n = 1;
    for (long long c : counts) {
      const std::optional<std::uint64_t> product = multiply_exactly<std::uint64_t>(n, c);
      // More control points than tokens left cannot be there: stop before allocating for them
      // (and before a product of counts could wrap).
      if (!product || (n = *product) > tokens_.size() - std::min(position_, tokens_.size())) {
        throw InvalidInput("the header asks for more control points than the file holds", header_line);
      }
    }
    const std::size_t size = static_cast<std::size_t>(k) + (rational ? 1 : 0);
    std::vector<double> coefficients;
    std::vector<std::size_t> lines;
    coefficients.reserve(static_cast<std::size_t>(n) * size);
    for (std::uint64_t i = 0; i < n; ++i) {
      lines.push_back(at_end() ? last_line_ : tokens_[position_].line);
      expect('[', "opening control point " + std::to_string(i) + " of " + std::to_string(n));
      while (peek('[')) skip_group();  // attributes of the point
      const std::string what = "a coordinate (a finite number) of control point " + std::to_string(i) + " (" +
                               std::to_string(size) + " numbers for " + type_text + ")";
      double weight = 1.0;
      if (rational) weight = number(what);
      for (int c = 0; c < k; ++c) coefficients.push_back(number(what));
      if (rational) coefficients.push_back(weight);
      expect(']', "closing control point " + std::to_string(i) + " after its " + std::to_string(size) + " numbers (point type " + type_text + ")");
    }
    expect(']', "closing the " + std::string(D == 1 ? "CURVE" : D == 2 ? "SURFACE" : "TRIVAR") + " after its " + std::to_string(n) + " control points");

    std::array<KnotVector, D> knot_array = [&]<std::size_t... I>(std::index_sequence<I...>) {
      return std::array<KnotVector, D>{std::move(knots[I])...};
    }(std::make_index_sequence<D>{});
    try {
      return TensorSpline<D>::from_homogeneous(std::move(knot_array), k, rational, std::move(coefficients));
    } catch (const InvalidInput& e) {
      // "weights[i]" and "coefficients[j]" locate a control point; name its line.
      std::string line = header_line;
      for (const char* prefix : {"weights[", "coefficients["}) {
        if (e.where().rfind(prefix, 0) == 0) {
          const auto index = detail::parse_integer(
              std::string_view(e.where()).substr(std::string_view(prefix).size(), e.where().find(']') - std::string_view(prefix).size()), 0,
              INT64_MAX);
          if (index) {
            const std::size_t point = static_cast<std::size_t>(*index) / (std::string(prefix) == "weights[" ? 1 : size);
            if (point < lines.size()) line = "line " + std::to_string(lines[point]);
          }
        }
      }
      throw InvalidInput(e.message() + (e.where().empty() ? "" : " (" + e.where() + ")"), line);
    }
  }

  std::vector<Token> tokens_;
  std::size_t last_line_;
  std::size_t position_ = 0;
};

std::string irit_name(const std::string& name) {
  if (name.empty()) return "NONE";
  std::string out;
  for (unsigned char c : name) out += std::isalnum(c) || c == '_' ? static_cast<char>(c) : '_';
  if (upper(out) == "NONE") out += '_';
  return out;
}

template <int D>
void write_spline(std::string& out, const TensorSpline<D>& spline, const std::string& path) {
  const int k = spline.dimension();
  if (k > kMaxIritCoordinates) {
    throw InvalidInput("IRIT holds at most " + std::to_string(kMaxIritCoordinates) + " coordinates per point (E9/P9), the object has " +
                           std::to_string(k),
                       path);
  }
  const bool rational = spline.is_rational();
  out += std::string("    [") + (D == 1 ? "CURVE" : D == 2 ? "SURFACE" : "TRIVAR") + " BSPLINE";
  for (int d = 0; d < D; ++d) out += " " + std::to_string(spline.num_control_points()[static_cast<std::size_t>(d)]);
  for (int d = 0; d < D; ++d) out += " " + std::to_string(spline.knot_vector(d).degree() + 1);
  out += std::string(" ") + (rational ? 'P' : 'E') + std::to_string(k) + "\n";
  for (int d = 0; d < D; ++d) {
    out += "        [KV";
    for (double t : spline.knot_vector(d).knots()) {
      out += ' ';
      out += format_double(t);
    }
    out += "]\n";
  }
  const auto n = static_cast<std::size_t>(spline.num_control_points_total());
  const auto size = static_cast<std::size_t>(spline.coefficient_size());
  const std::vector<double>& h = spline.homogeneous();
  for (std::size_t i = 0; i < n; ++i) {
    out += "        [";
    // IRIT's rational points are (w, w x1, ..., w xk): the weight first, then premultiplied.
    if (rational) {
      out += format_double(h[i * size + static_cast<std::size_t>(k)]);
      out += ' ';
    }
    for (int c = 0; c < k; ++c) {
      if (c) out += ' ';
      out += format_double(h[i * size + static_cast<std::size_t>(c)]);
    }
    out += "]\n";
  }
  out += "    ]\n";
}

}  // namespace

Model parse_irit_itd(std::string_view text, const std::string& source_name) {
  try {
    const std::size_t last_line = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    Model model = Parser(tokenize(text), last_line).model();
    check_coordinate_range(model);
    return model;
  } catch (const InvalidInput& e) {
    std::string where = source_name;
    if (!where.empty() && !e.where().empty()) where += ": ";
    throw InvalidInput(e.message(), where + e.where());
  }
}

Model read_irit_itd(const std::filesystem::path& path) { return parse_irit_itd(read_file(path), path.string()); }

std::string irit_itd_text(const Model& model) {
  if (model.objects.empty()) throw InvalidInput("expected at least one object, got none", "objects");
  std::string out = "#\n# written by volspline: IRIT B-spline objects; orders = degree + 1; P points are (w, w x, ...)\n#\n";
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    const ModelObject& object = model.objects[i];
    out += "[OBJECT " + irit_name(object.name) + "\n";
    const std::string path = "objects[" + std::to_string(i) + "]";
    visit_classic_spline(object, "IRIT", path, [&](const auto& spline) { write_spline(out, spline, path); });
    out += "]\n";
  }
  return out;
}

void write_irit_itd(const Model& model, const std::filesystem::path& path) {
  write_file_atomically(path, irit_itd_text(model));
}

}  // namespace volspline
