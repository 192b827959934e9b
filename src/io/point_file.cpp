#include "volspline/io/point_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {
namespace {

// The numbers of a line, or false if some field is not a finite number.
bool line_numbers(std::string_view line, std::vector<double>& out) {
  out.clear();
  std::string field;
  auto flush = [&]() -> bool {
    if (field.empty()) return true;
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size() || errno == ERANGE || !std::isfinite(x)) return false;
    out.push_back(x);
    field.clear();
    return true;
  };
  for (char c : line) {
    if (c == ',' || c == ' ' || c == '\t' || c == '\r') {
      if (!flush()) return false;
    } else {
      field += c;
    }
  }
  return flush();
}

}  // namespace

std::vector<Eigen::Vector3d> parse_points(std::string_view text, const std::string& source_name) {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> lines;  // of each point, for the range check's message
  std::vector<double> numbers;
  std::size_t line_number = 0, start = 0;
  bool first_content = true;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') {
      if (end == text.size()) break;
      continue;
    }
    const bool numeric = line_numbers(line, numbers);
    if (!numeric && first_content) {
      first_content = false;  // a header
      continue;
    }
    first_content = false;
    if (!numeric || numbers.size() != 3) {
      std::string shown(line.substr(0, 60));
      throw InvalidInput("expected 3 numbers x, y, z, got \"" + shown + (line.size() > 60 ? "...\"" : "\""),
                         source_name + ": line " + std::to_string(line_number));
    }
    points.emplace_back(numbers[0], numbers[1], numbers[2]);
    lines.push_back(line_number);
    if (end == text.size()) break;
  }
  if (points.empty()) throw InvalidInput("expected at least one point (a line x, y, z), got none", source_name);
  // The range of coordinates (core/coordinate_range.h), located at the line.
  check_point_coordinate_range(
      points.front().data(), points.size(), 3, 3,
      [&](std::size_t i, std::size_t c) { return source_name + ": line " + std::to_string(lines[i]) + ", " + std::string(1, "xyz"[c]); },
      source_name, "points", "docs/formats.md");
  return points;
}

std::vector<Eigen::Vector3d> read_points(const std::filesystem::path& path) { return parse_points(read_file(path), path.string()); }

}  // namespace volspline
