#pragma once
// What the readers and writers of model-file objects share (io/model_file.cpp and the objects
// that have a file of their own, such as simplex_spline_json.cpp): located errors, key checks,
// finite numbers, and numbers written with 17 significant digits.
#include <initializer_list>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace volspline::model_json {

/// \throw InvalidInput "expected EXPECTED, got <description of got>" at `path`.
[[noreturn]] void fail(const std::string& expected, const nlohmann::json& got, const std::string& path);
/// \throw InvalidInput for a key of `object` that is not in `allowed`.
void check_keys(const nlohmann::json& object, const std::string& path, std::initializer_list<const char*> allowed);
/// object[key]. \throw InvalidInput "missing key" saying what it holds.
const nlohmann::json& required(const nlohmann::json& object, const char* key, const std::string& path, const std::string& what);
/// A finite number. \throw InvalidInput otherwise.
double number(const nlohmann::json& value, const std::string& path);
/// An array of finite numbers. \throw InvalidInput ("expected WHAT") otherwise.
std::vector<double> numbers(const nlohmann::json& value, const std::string& path, const std::string& what);
/// A number as written: 17 significant digits, "-0.0" for negative zero.
std::string number_text(double value);
/// "[a, b, c]" on one line if it fits in 100 characters, else wrapped.
void write_numbers(std::ostringstream& out, const double* values, std::size_t count, const std::string& indent);
/// A JSON value as text, each new line indented. \throw InvalidInput for text that is not UTF-8.
std::string json_text(const nlohmann::json& value, const std::string& path, const std::string& indent, bool pretty);

}  // namespace volspline::model_json
