#pragma once
// JSON as volspline's formats read it (model files, scene files): stricter than the JSON
// grammar, so that a mistake in a hand-written file is an error at its JSON path instead of a
// silently different model, and with the helpers that name a place and a value in a message.
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "volspline/core/error.h"

namespace volspline {

/// Deepest nesting of arrays and objects accepted. A model needs 5 levels (top, objects,
/// object, knots, knot vector); the rest is room for metadata. The limit keeps recursive JSON
/// operations (copy, dump, comparison) far from the stack's end.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// The JSON text parsed strictly: duplicate keys, nesting deeper than kMaxJsonDepth and numbers
/// beyond the range of a double are errors.
/// \throw InvalidInput located at the JSON path, or at "line L, column C" for text that is not
/// JSON.
nlohmann::json parse_json_document(std::string_view text);

/// A JSON value described for an error message: "null", "3.5", "the string \"x\"", "an array
/// of 2 elements", "an object".
std::string describe_json_value(const nlohmann::json& value);

/// Whether `key` can be written after a dot in a JSON path ([A-Za-z_][A-Za-z0-9_]*).
bool is_json_identifier(const std::string& key);

/// A JSON string literal for `text`, shortened to about `limit` bytes (with "...") for messages.
std::string json_quoted(const std::string& text, std::size_t limit = 40);

/// The path of member `key` of the value at `parent`: parent.key, or parent["key"] when the key
/// is not an identifier; the key alone at the top ("" parent).
std::string json_key_path(const std::string& parent, const std::string& key);

/// The path of element `index` of the array at `parent`: parent[index].
std::string json_index_path(const std::string& parent, std::size_t index);

/// `error` with `source_name` (usually a file name) in front of its location, as the readers of
/// JSON formats report errors: "SOURCE: PATH: message", or "SOURCE: message" where it had no
/// location.
InvalidInput located_in_source(const InvalidInput& error, const std::string& source_name);

}  // namespace volspline
