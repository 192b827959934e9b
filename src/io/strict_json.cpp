#include "volspline/io/strict_json.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "volspline/core/error.h"

namespace volspline {

namespace {

using nlohmann::json;

// ------------------------------------------------------------------------------------------
// Parsing JSON text into a DOM: a SAX handler that rejects duplicate keys, limits the nesting
// depth, reports numbers beyond the range of a double at their JSON path, and converts
// syntax errors into "line L, column C" messages.

class DomBuilder {
 public:
  DomBuilder(std::string_view text, json& root) : text_(text), root_(root) {}

  bool null() { return add(json(nullptr)); }
  bool boolean(bool value) { return add(json(value)); }
  bool number_integer(json::number_integer_t value) { return add(json(value)); }
  bool number_unsigned(json::number_unsigned_t value) { return add(json(value)); }
  bool number_float(json::number_float_t value, const json::string_t& /*text*/) { return add(json(value)); }
  bool string(json::string_t& value) { return add(json(std::move(value))); }
  bool binary(json::binary_t& value) { return add(json::binary(std::move(value))); }

  bool start_object(std::size_t /*elements*/) { return open(json::object(), true); }
  bool start_array(std::size_t /*elements*/) { return open(json::array(), false); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& key) {
    Frame& top = frames_.back();
    top.key = key;
    if (top.value->contains(key)) {
      throw InvalidInput("duplicate key " + json_quoted(key) + ": every key may appear only once in an object",
                         current_path());
    }
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token, const json::exception& error) {
    if (error.id == 406) {
      // nlohmann rejects numbers such as 1e999 that overflow a double: say where.
      throw InvalidInput("expected a finite number, got " + last_token + " (beyond the range of a double)",
                         current_path());
    }
    throw InvalidInput("invalid JSON: " + reason(error.what()), line_and_column(position));
  }

 private:
  struct Frame {
    json* value;
    bool object;
    std::string key;
  };

  /// The JSON path of the value that is parsed next (or is being parsed).
  std::string current_path() const {
    std::string path;
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.object) {
        path = json_key_path(path, f.key);
      } else {
        // An enclosing array's current element is its last; the innermost one's is the next.
        const std::size_t size = f.value->size();
        path = json_index_path(path, i + 1 < frames_.size() ? size - 1 : size);
      }
    }
    return path;
  }

  /// Where nlohmann stopped: `position` counts the bytes read, the offending one included.
  std::string line_and_column(std::size_t position) const {
    const std::size_t at = std::min(position > 0 ? position - 1 : 0, text_.size());
    std::size_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < at; ++i) {
      if (text_[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
  }

  /// nlohmann's message without its "[json.exception...] parse error at line L, column C: ".
  static std::string reason(const std::string& what) {
    std::string text = what;
    if (const auto bracket = text.find("] "); text.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
      text = text.substr(bracket + 2);
    }
    if (text.rfind("parse error", 0) == 0) {
      if (const auto colon = text.find(": "); colon != std::string::npos) text = text.substr(colon + 2);
    }
    return text;
  }

  bool add(json value) {
    if (frames_.empty()) {
      root_ = std::move(value);
      return true;
    }
    Frame& top = frames_.back();
    if (top.object) {
      (*top.value)[top.key] = std::move(value);
    } else {
      top.value->push_back(std::move(value));
    }
    return true;
  }

  bool open(json container, bool object) {
    if (frames_.size() >= kMaxJsonDepth) {
      throw InvalidInput("expected at most " + std::to_string(kMaxJsonDepth) +
                             " levels of nested arrays and objects, got more",
                         current_path());
    }
    json* slot = nullptr;
    if (frames_.empty()) {
      root_ = std::move(container);
      slot = &root_;
    } else {
      Frame& top = frames_.back();
      if (top.object) {
        slot = &((*top.value)[top.key] = std::move(container));
      } else {
        top.value->push_back(std::move(container));
        slot = &top.value->back();
      }
    }
    frames_.push_back(Frame{slot, object, {}});
    return true;
  }

  bool close() {
    frames_.pop_back();
    return true;
  }

  std::string_view text_;
  json& root_;
  std::vector<Frame> frames_;
};

}  // namespace

json parse_json_document(std::string_view text) {
  json root;
  DomBuilder builder(text, root);
  json::sax_parse(text.data(), text.data() + text.size(), &builder);
  return root;
}


bool is_json_identifier(const std::string& key) {
  if (key.empty()) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!alpha(key[0])) return false;
  return std::all_of(key.begin(), key.end(), [&](char c) { return alpha(c) || (c >= '0' && c <= '9'); });
}

std::string json_quoted(const std::string& text, std::size_t limit) {
  std::string shown = text.size() > limit ? text.substr(0, limit) : text;
  std::string literal = json(shown).dump(-1, ' ', false, json::error_handler_t::replace);
  if (shown.size() < text.size()) literal.insert(literal.size() - 1, "...");
  return literal;
}

std::string json_key_path(const std::string& parent, const std::string& key) {
  if (!is_json_identifier(key)) return parent + "[" + json_quoted(key, 1000) + "]";
  return parent.empty() ? key : parent + "." + key;
}

std::string json_index_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

InvalidInput located_in_source(const InvalidInput& error, const std::string& source_name) {
  std::string where = source_name;
  if (!where.empty() && !error.where().empty()) where += ": ";
  where += error.where();
  return InvalidInput(error.message(), where);
}

std::string describe_json_value(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return value.dump();
    case json::value_t::string:
      return "the string " + json_quoted(value.get_ref<const std::string&>());
    case json::value_t::array:
      if (value.empty()) return "an empty array";
      return value.size() == 1 ? "an array of 1 element" : "an array of " + std::to_string(value.size()) + " elements";
    case json::value_t::object:
      return value.empty() ? "an empty object" : "an object";
    default:
      return "a value of an unsupported kind";
  }
}

}  // namespace volspline
