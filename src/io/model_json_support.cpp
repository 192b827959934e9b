#include "model_json_support.h"

#include <algorithm>
#include <cmath>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/strict_json.h"

namespace volspline::model_json {

using nlohmann::json;

[[noreturn]] void fail(const std::string& expected, const json& got, const std::string& path) {
  throw InvalidInput("expected " + expected + ", got " + describe_json_value(got), path);
}

void check_keys(const json& object, const std::string& path, std::initializer_list<const char*> allowed) {
  for (const auto& item : object.items()) {
    const std::string& key = item.key();
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InvalidInput("unknown key " + json_quoted(key) + ": expected one of " + list +
                             " (free-form data belongs under \"metadata\")",
                         json_key_path(path, key));
    }
  }
}

const json& required(const json& object, const char* key, const std::string& path, const std::string& what) {
  const auto it = object.find(key);
  if (it == object.end()) {
    throw InvalidInput("missing key \"" + std::string(key) + "\" (" + what + ")", path);
  }
  return *it;
}

double number(const json& value, const std::string& path) {
  if (!value.is_number()) fail("a number", value, path);
  const double x = value.get<double>();
  // The parser rejects overflowing literals already; this guards every other route.
  if (!std::isfinite(x)) fail("a finite number", value, path);
  return x;
}

std::vector<double> numbers(const json& value, const std::string& path, const std::string& what) {
  if (!value.is_array()) fail(what, value, path);
  std::vector<double> out;
  out.reserve(value.size());
  for (std::size_t i = 0; i < value.size(); ++i) out.push_back(number(value[i], json_index_path(path, i)));
  return out;
}

/// A number as written: 17 significant digits, and "-0.0" for negative zero (a JSON reader
/// takes "-0" for the integer 0).
std::string number_text(double value) {
  std::string text = format_double(value);
  if (value == 0.0 && std::signbit(value)) text = "-0.0";
  return text;
}

/// "[a, b, c]" on one line if it fits in kLineWidth characters, else wrapped at that width.
void write_numbers(std::ostringstream& out, const double* values, std::size_t count, const std::string& indent) {
  constexpr std::size_t kLineWidth = 100;
  std::vector<std::string> texts;
  std::size_t total = indent.size() + 2;
  for (std::size_t i = 0; i < count; ++i) {
    texts.push_back(number_text(values[i]));
    total += texts.back().size() + 2;
  }
  if (total <= kLineWidth) {
    out << '[';
    for (std::size_t i = 0; i < count; ++i) out << (i ? ", " : "") << texts[i];
    out << ']';
    return;
  }
  out << "[\n" << indent << "  ";
  std::size_t column = indent.size() + 2;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) {
      if (column + 2 + texts[i].size() + 1 > kLineWidth) {
        out << ",\n" << indent << "  ";
        column = indent.size() + 2;
      } else {
        out << ", ";
        column += 2;
      }
    }
    out << texts[i];
    column += texts[i].size();
  }
  out << '\n' << indent << ']';
}

std::string json_text(const json& value, const std::string& path, const std::string& indent, bool pretty) {
  std::string text;
  try {
    text = value.dump(pretty ? 2 : -1, ' ', false, json::error_handler_t::strict);
  } catch (const json::exception&) {
    throw InvalidInput("expected text in UTF-8, got invalid UTF-8", path);
  }
  std::string indented;
  for (char c : text) {
    indented += c;
    if (c == '\n') indented += indent;
  }
  return indented;
}

}  // namespace volspline::model_json
