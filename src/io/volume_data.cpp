#include "volspline/io/volume_data.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <optional>

#include "text_numbers.h"
#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> csv_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string names_of(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

int VolumeData::attribute_column(const std::string& name) const {
  const auto it = std::find(attribute_names.begin(), attribute_names.end(), name);
  if (it == attribute_names.end())
    throw InvalidInput("no attribute '" + name + "' (the data has: " + names_of(attribute_names) + ")");
  return static_cast<int>(it - attribute_names.begin());
}

VolumeData every_nth_point(const VolumeData& data, std::size_t every, std::size_t which, bool keep) {
  if (every == 0) throw InvalidInput("every_nth_point: expected every >= 1, got 0");
  VolumeData out;
  out.attribute_names = data.attribute_names;
  std::vector<Eigen::Index> rows;
  for (std::size_t i = 0; i < data.size(); ++i)
    if ((i % every == which) == keep) rows.push_back(static_cast<Eigen::Index>(i));
  out.attributes.resize(static_cast<Eigen::Index>(rows.size()), data.attributes.cols());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out.points.push_back(data.points[static_cast<std::size_t>(rows[r])]);
    out.attributes.row(static_cast<Eigen::Index>(r)) = data.attributes.row(rows[r]);
  }
  return out;
}

VolumeData select_attributes(const VolumeData& data, const std::vector<std::string>& names) {
  if (names.empty()) return data;
  VolumeData selected;
  selected.points = data.points;
  selected.attributes.resize(static_cast<Eigen::Index>(data.size()), static_cast<Eigen::Index>(names.size()));
  for (std::size_t a = 0; a < names.size(); ++a) {
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(a), names[a]) != names.begin() + static_cast<std::ptrdiff_t>(a))
      throw InvalidInput("attribute '" + names[a] + "' is named twice");
    selected.attributes.col(static_cast<Eigen::Index>(a)) = data.attributes.col(data.attribute_column(names[a]));
    selected.attribute_names.push_back(names[a]);
  }
  return selected;
}

void validate_volume_data(const VolumeData& data, const std::string& source) {
  if (data.attributes.rows() != static_cast<Eigen::Index>(data.size()) ||
      data.attributes.cols() != static_cast<Eigen::Index>(data.attribute_names.size()))
    throw InvalidInput("the attribute matrix is " + std::to_string(data.attributes.rows()) + " x " +
                           std::to_string(data.attributes.cols()) + ", expected " + std::to_string(data.size()) + " x " +
                           std::to_string(data.attribute_names.size()) + " (points x attributes)",
                       source);
  for (std::size_t a = 0; a < data.attribute_names.size(); ++a) {
    const std::string& name = data.attribute_names[a];
    if (name.empty() || name == "x" || name == "y" || name == "z")
      throw InvalidInput("attribute " + std::to_string(a) + " is named '" + name + "' (expected a non-empty name other than x, y, z)", source);
    for (std::size_t b = 0; b < a; ++b)
      if (data.attribute_names[b] == name) throw InvalidInput("attribute '" + name + "' appears twice", source);
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (!data.points[i].allFinite()) throw InvalidInput("coordinates are not finite numbers", source + ": point " + std::to_string(i));
    for (Eigen::Index a = 0; a < data.attributes.cols(); ++a)
      if (!std::isfinite(data.attributes(static_cast<Eigen::Index>(i), a)))
        throw InvalidInput("attribute '" + data.attribute_names[static_cast<std::size_t>(a)] + "' is not a finite number",
                           source + ": point " + std::to_string(i));
  }
  // The range of coordinates (core/coordinate_range.h); attributes are any finite numbers.
  if (!data.points.empty()) {
    check_point_coordinate_range(
        data.points.front().data(), data.size(), 3, 3,
        [&](std::size_t i, std::size_t c) { return source + ": point " + std::to_string(i) + ", " + std::string(1, "xyz"[c]); }, source,
        "points", "docs/formats.md");
  }
}

VolumeData parse_volume_csv(std::string_view text, const std::string& source) {
  // A UTF-8 byte order mark, as spreadsheets write before the header, is not part of a name.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string> header;
  std::array<int, 3> xyz{-1, -1, -1};
  std::vector<int> attribute_fields;
  std::vector<double> values;  // row-major: x y z then attributes, per point
  std::size_t line_number = 0, start = 0;
  VolumeData data;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_number;
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    const std::string where = source + ": line " + std::to_string(line_number);
    const std::vector<std::string_view> fields = csv_fields(content);
    if (header.empty()) {
      for (std::size_t f = 0; f < fields.size(); ++f) {
        std::string name(fields[f]);
        if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
        if (name.empty()) throw InvalidInput("column " + std::to_string(f + 1) + " of the header has no name", where);
        if (std::find(header.begin(), header.end(), name) != header.end())
          throw InvalidInput("column '" + name + "' is named twice in the header", where);
        if (detail::parse_double(name))
          throw InvalidInput("expected a header naming the columns (x, y, z and attributes), got the number " +
                                 detail::quoted_token(name) + " in column " + std::to_string(f + 1),
                             where);
        const std::string key = lower(name);
        if (key == "x" || key == "y" || key == "z") {
          int& column = xyz[static_cast<std::size_t>(key[0] - 'x')];
          if (column >= 0) throw InvalidInput("column " + key + " is named twice in the header (x, y, z are case-insensitive)", where);
          column = static_cast<int>(f);
        }
        else attribute_fields.push_back(static_cast<int>(f));
        header.push_back(name);
      }
      for (int c = 0; c < 3; ++c)
        if (xyz[static_cast<std::size_t>(c)] < 0)
          throw InvalidInput(std::string("the header has no column ") + static_cast<char>('x' + c) +
                                 " (expected columns x, y, z and any attributes)",
                             where);
      for (int f : attribute_fields) data.attribute_names.push_back(header[static_cast<std::size_t>(f)]);
      continue;
    }
    if (fields.size() != header.size())
      throw InvalidInput("expected " + std::to_string(header.size()) + " fields (" + names_of(header) + "), got " +
                             std::to_string(fields.size()),
                         where);
    std::vector<double> row(fields.size());
    for (std::size_t f = 0; f < fields.size(); ++f) {
      // A number in quotes (spreadsheets quote fields) is the number.
      std::string_view field = fields[f];
      if (field.size() >= 2 && field.front() == '"' && field.back() == '"') field = trim(field.substr(1, field.size() - 2));
      const std::optional<double> v = detail::parse_double(field);
      if (!v)
        throw InvalidInput("column '" + header[f] + "': expected a finite number, got " + detail::quoted_token(fields[f]), where);
      row[f] = *v;
    }
    for (int c = 0; c < 3; ++c) values.push_back(row[static_cast<std::size_t>(xyz[static_cast<std::size_t>(c)])]);
    for (int f : attribute_fields) values.push_back(row[static_cast<std::size_t>(f)]);
  }
  if (header.empty()) throw InvalidInput("expected a header line naming the columns x, y, z (and attributes), got no lines", source);
  const std::size_t width = 3 + attribute_fields.size();
  const std::size_t n = values.size() / width;
  if (n == 0) throw InvalidInput("expected at least one point after the header, got none", source);
  data.points.resize(n);
  data.attributes.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(attribute_fields.size()));
  for (std::size_t i = 0; i < n; ++i) {
    data.points[i] = Eigen::Vector3d(values[i * width], values[i * width + 1], values[i * width + 2]);
    for (std::size_t a = 0; a < attribute_fields.size(); ++a)
      data.attributes(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a)) = values[i * width + 3 + a];
  }
  validate_volume_data(data, source);
  return data;
}

}  // namespace volspline
