#include "cli_support.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <filesystem>
#include <iostream>
#include <optional>
#include <cmath>
#include <sstream>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_formats.h"
#include "volspline/render/image.h"

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

namespace {

// "A,B,C" into exactly `count` values accepted by `valid`; `what` names the expected kind.
template <class T, class Valid>
std::vector<T> parse_list(const std::string& text, std::size_t count, const std::string& option, const std::string& what,
                          Valid valid) {
  const auto parts = split_commas(text);
  if (parts.size() != count)
    throw InvalidInput("expected " + std::to_string(count) + " comma-separated values, got '" + text + "'", option);
  std::vector<T> values;
  for (const auto& raw : parts) {
    // from_chars accepts neither spaces nor a leading '+', which people type.
    const auto first = raw.find_first_not_of(" \t");
    const auto last = raw.find_last_not_of(" \t");
    std::string part = first == std::string::npos ? std::string() : raw.substr(first, last - first + 1);
    if (part.size() > 1 && part[0] == '+') part.erase(0, 1);
    T x{};
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), x);
    if (ec == std::errc::result_out_of_range)
      throw InvalidInput("'" + raw + "' is out of the range of a double", option);
    if (ec != std::errc() || end != part.data() + part.size() || !valid(x))
      throw InvalidInput("expected " + what + ", got '" + raw + "' in '" + text + "'", option);
    values.push_back(x);
  }
  return values;
}

}  // namespace

std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& option) {
  return parse_list<double>(text, count, option, "a finite number", [](double x) { return std::isfinite(x); });
}

std::vector<int> parse_integers(const std::string& text, std::size_t count, int minimum, const std::string& option) {
  return parse_list<int>(text, count, option, "an integer >= " + std::to_string(minimum), [&](int x) { return x >= minimum; });
}

void write_mesh_and_picture(const TriangleMesh& mesh, const std::string& out, MeshFormat format, bool ascii,
                            const std::string& png, const RenderOptions& options, const TriangleMesh* shown,
                            const std::vector<PlyVertexProperty>& properties) {
  AtomicFile mesh_file(out);
  mesh_file.stream() << mesh_bytes(mesh, format, {.ascii = ascii, .vertex_properties = properties});
  std::optional<AtomicFile> png_file;
  if (!png.empty()) {
    const std::string bytes = png_bytes(render_mesh(shown != nullptr ? *shown : mesh, options));
    png_file.emplace(png);
    png_file->stream() << bytes;
  }
  mesh_file.commit();
  if (png_file) png_file->commit();
}

void write_mesh_picture_and_stats(const TriangleMesh& mesh, const std::string& out, MeshFormat format, const std::string& png,
                                  const RenderOptions& options, const std::string& stats_text, const std::string& stats_path,
                                  Progress* progress, const TriangleMesh* shown, const std::vector<PlyVertexProperty>& properties) {
  std::optional<AtomicFile> stats_file;
  if (!stats_path.empty()) {
    stats_file.emplace(stats_path, false);
    stats_file->stream() << stats_text << "\n";
  }
  {
    const ProgressPhase phase(progress, "writing");
    write_mesh_and_picture(mesh, out, format, false, png, options, shown, properties);
    if (stats_file) stats_file->commit();
  }
  std::cout << "wrote " << out << ": " << mesh.num_vertices() << " vertices, " << mesh.num_triangles() << " triangles\n";
  if (!png.empty()) std::cout << "wrote " << png << "\n";
  if (stats_file) std::cout << "wrote " << stats_path << "\n";
}

int parse_direction(const std::string& text, const std::string& option) {
  static const char* names[] = {"u", "v", "w", "s"};
  for (int d = 0; d < 4; ++d)
    if (text == names[d] || text == std::to_string(d)) return d;
  throw InvalidInput("expected a direction u, v or w, got '" + text + "'", option);
}

int parameter_count(const ModelObject& object) {
  // A swept solid has the four parameters of its patches; a simplex spline volume is evaluated
  // at points x, y, z of its domain.
  if (is_swept_solid(object)) return 4;
  if (is_simplex_spline_volume(object)) return 3;
  return static_cast<int>(object.spline.index()) + 1;
}

std::string json_text(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::size_t object_index(long long index, std::size_t count, const std::string& option) {
  if (index < 0) throw InvalidInput("expected an object index >= 0, got " + std::to_string(index), option);
  if (static_cast<unsigned long long>(index) >= count)
    throw InvalidInput("object " + std::to_string(index) + " does not exist; the model has " + std::to_string(count) + " object(s)", option);
  return static_cast<std::size_t>(index);
}

std::string join_numbers(const double* values, std::size_t count) {
  std::string s;
  for (std::size_t i = 0; i < count; ++i) {
    if (i) s += ' ';
    s += format_double(values[i]);
  }
  return s;
}

Model ModelInput::read() const { return read_model_file(path, format); }

std::shared_ptr<ModelInput> add_model_input(CLI::App* cmd) {
  auto input = std::make_shared<ModelInput>();
  cmd->add_option("MODEL", input->path, "model file: .json, G+Smo .xml, IRIT .itd or .vtu (docs/formats.md)")->required();
  cmd->add_option("--input-format", input->format, "json, gismo, irit or vtu, overriding the extension");
  return input;
}

namespace {

std::string& command_line_storage() {
  static std::string line;
  return line;
}

}  // namespace

void remember_command_line(int argc, const char* const* argv) {
  std::string line = "volspline";
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const bool plain = !arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.,:/=+@%") ==
                                           std::string_view::npos;
    if (plain) {
      line += " " + std::string(arg);
      continue;
    }
    line += " '";
    for (const char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += "'";
  }
  command_line_storage() = line;
}

const std::string& remembered_command_line() { return command_line_storage(); }

Eigen::Vector3d parse_view_direction(const std::string& text, const std::string& option) {
  const auto d = parse_numbers(text, 3, option);
  const Eigen::Vector3d direction(d[0], d[1], d[2]);
  if (direction.norm() == 0.0) throw InvalidInput("the view direction must not be zero, got '" + text + "'", option);
  return direction;
}

Plane parse_plane(const std::string& text, const std::string& option) {
  const auto p = parse_numbers(text, 4, option);
  const Plane plane{Eigen::Vector3d(p[0], p[1], p[2]), p[3]};
  if (plane.normal.norm() == 0.0) throw InvalidInput("the plane normal NX,NY,NZ must not be zero, got '" + text + "'", option);
  return plane;
}

std::shared_ptr<std::string> add_html_option(CLI::App* cmd) {
  auto html = std::make_shared<std::string>();
  cmd->add_option("--html", *html,
                  "also write an interactive page: the result in three.js with parts, probes, clipping and the model's "
                  "description, one self-contained file (docs/web-pages.md)");
  return html;
}

void check_html_option(const std::string& html) {
  if (html.empty()) return;
  if (std::filesystem::path(html).extension() != ".html")
    throw InvalidInput("expected a file name ending in .html, got '" + html + "'", "--html");
  if (!interactive_pages_available())
    throw InvalidInput("this volspline cannot write interactive pages: " + std::string(interactive_pages_unavailable_reason()), "--html");
}

void write_html_page(const std::string& html, InteractivePage page) {
  if (html.empty()) return;
  if (page.command.empty()) page.command = remembered_command_line();
  write_file_atomically(html, interactive_page_html(page));
  std::cout << "wrote " << html << "\n";
}

}  // namespace volspline::cli
