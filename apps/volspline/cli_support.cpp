#include "cli_support.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "volspline/core/error.h"
#include "volspline/core/format.h"

namespace volspline::cli {

namespace {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) parts.push_back(item);
  if (!text.empty() && text.back() == ',') parts.emplace_back();
  return parts;
}

}  // namespace

std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option) {
  const auto parts = split_commas(text);
  if (parts.size() != count)
    throw InvalidInput("expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'", option);
  std::vector<double> values;
  for (const auto& part : parts) {
    double x = 0.0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
    if (ec != std::errc() || end != part.data() + part.size() || !std::isfinite(x))
      throw InvalidInput("expected a finite number, got '" + part + "' in '" + text + "'", option);
    values.push_back(x);
  }
  return values;
}

std::vector<int> parse_integers(const std::string& text, std::size_t count, int minimum, const std::string& option) {
  const auto parts = split_commas(text);
  if (parts.size() != count)
    throw InvalidInput("expected " + std::to_string(count) + " comma-separated integers, got '" + text + "'", option);
  std::vector<int> values;
  for (const auto& part : parts) {
    int x = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
    if (ec != std::errc() || end != part.data() + part.size() || x < minimum)
      throw InvalidInput("expected an integer >= " + std::to_string(minimum) + ", got '" + part + "'", option);
    values.push_back(x);
  }
  return values;
}

int parse_direction(const std::string& text, const std::string& option) {
  static const char* names[] = {"u", "v", "w", "s"};
  for (int d = 0; d < 4; ++d)
    if (text == names[d] || text == std::to_string(d)) return d;
  throw InvalidInput("expected a direction u, v or w, got '" + text + "'", option);
}

int parameter_count(const ModelObject& object) { return static_cast<int>(object.spline.index()) + 1; }

std::string join_numbers(const double* values, std::size_t count) {
  std::string s;
  for (std::size_t i = 0; i < count; ++i) {
    if (i) s += ' ';
    s += format_double(values[i]);
  }
  return s;
}

}  // namespace volspline::cli
