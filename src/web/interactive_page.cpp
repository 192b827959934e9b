#include "volspline/web/interactive_page.h"

#include <algorithm>
#include <map>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/mesh/vertex_clustering.h"
#include "volspline/render/colormap.h"
#include "viewer_script.h"

namespace volspline {

namespace {

// RFC 4648 base64 with padding: how the page carries each binary glTF (JSON has no bytes).
std::string base64_of(const std::string& bytes) {
  static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned n = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (const int shift : {18, 12, 6, 0}) out += alphabet[(n >> shift) & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned n = static_cast<unsigned char>(bytes[i]) << 16 | (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0u);
    out += alphabet[(n >> 18) & 63];
    out += alphabet[(n >> 12) & 63];
    out += two ? alphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

nlohmann::json srgb_json(const Eigen::Vector3d& c) { return {c.x(), c.y(), c.z()}; }

// The triangles of one part of `mesh` (and their colours) as a mesh of their own, vertices
// renumbered in order of first use.
struct PagePartMesh {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3d> colors;
};

std::map<int, PagePartMesh> page_meshes_by_part(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& colors) {
  std::map<int, PagePartMesh> by_part;
  std::map<int, std::vector<int>> renumbered;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const int part = mesh.parts[t];
    PagePartMesh& out = by_part[part];
    std::vector<int>& index = renumbered[part];
    if (index.empty()) index.assign(mesh.num_vertices(), -1);
    std::array<int, 3> corners{};
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.triangles[t][static_cast<std::size_t>(c)];
      int& mapped = index[static_cast<std::size_t>(v)];
      if (mapped < 0) {
        mapped = out.mesh.add_vertex(mesh.positions[static_cast<std::size_t>(v)], mesh.parameters[static_cast<std::size_t>(v)]);
        if (!colors.empty()) out.colors.push_back(colors[static_cast<std::size_t>(v)]);
      }
      corners[static_cast<std::size_t>(c)] = mapped;
    }
    out.mesh.add_triangle(corners[0], corners[1], corners[2], part);
  }
  return by_part;
}

// The script's text inside <script>...</script>: "</script" or "<!--" would end or confuse it.
// Every '<' of the JSON is inside a string, where \u003c means the same.
std::string script_safe_json(const nlohmann::json& value) {
  const std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

std::string page_html_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

bool interactive_pages_available() { return !web_viewer_script().empty(); }

std::string_view interactive_pages_unavailable_reason() {
  return interactive_pages_available() ? std::string_view{} : web_viewer_missing_reason();
}

std::string interactive_page_html(const InteractivePage& page) {
  if (!interactive_pages_available())
    throw InvalidInput("this volspline cannot write interactive pages: " + std::string(web_viewer_missing_reason()));
  validate_mesh(page.mesh);
  if (!page.vertex_colors.empty() && page.vertex_colors.size() != page.mesh.num_vertices())
    throw InvalidInput("page colours: " + std::to_string(page.mesh.num_vertices()) + " vertices, " +
                       std::to_string(page.vertex_colors.size()) + " colours");
  if (!page.vertex_scalars.empty() && (page.vertex_scalars.size() != page.mesh.num_vertices() || !page.color_bar || !page.vertex_colors.empty()))
    throw InvalidInput("page scalars: expected one per vertex (" + std::to_string(page.mesh.num_vertices()) + "), a colour bar and no colours, got " +
                       std::to_string(page.vertex_scalars.size()) + " scalars");
  std::vector<Eigen::Vector3d> colors = page.vertex_colors;
  for (const double s : page.vertex_scalars) {
    const double span = page.color_bar->max - page.color_bar->min;
    colors.push_back(colormap_color(page.color_bar->map, span > 0 ? (s - page.color_bar->min) / span : 0.5));
  }

  const ClusteredMesh shown = reduce_to_triangle_budget(page.mesh, page.max_triangles);
  if (shown.cell_size > 0 && !colors.empty()) {
    std::vector<Eigen::Vector3d> mean(shown.mesh.num_vertices(), Eigen::Vector3d::Zero());
    std::vector<int> members(shown.mesh.num_vertices(), 0);
    for (std::size_t v = 0; v < colors.size(); ++v) {
      const auto c = static_cast<std::size_t>(shown.cluster_of_vertex[v]);
      mean[c] += colors[v];
      ++members[c];
    }
    for (std::size_t c = 0; c < mean.size(); ++c) mean[c] /= std::max(members[c], 1);
    colors = std::move(mean);
  }

  nlohmann::json data;
  data["title"] = page.title;
  data["reduced"] = nullptr;
  if (shown.cell_size > 0)
    data["reduced"] = {{"triangles", page.mesh.num_triangles()}, {"shown", shown.mesh.num_triangles()}, {"cell_size", shown.cell_size}};
  data["command"] = page.command;
  data["info"] = page.info;
  data["parts"] = nlohmann::json::array();
  for (const auto& [number, part] : page_meshes_by_part(shown.mesh, colors))
    data["parts"].push_back({{"name", part_name(number)},
                             {"number", number},
                             {"srgb", srgb_json(part_color(number))},
                             {"triangles", part.mesh.num_triangles()},
                             {"glb", base64_of(glb_bytes(part.mesh, part.colors))}});
  data["probes"] = nlohmann::json::array();
  for (const PageProbe& probe : page.probes) {
    if (probe.meshes.empty() || probe.values.size() != probe.meshes.size())
      throw InvalidInput("probe '" + probe.name + "': expected one value per mesh and at least one mesh, got " +
                         std::to_string(probe.values.size()) + " values and " + std::to_string(probe.meshes.size()) + " meshes");
    if (probe.initial < 0 || probe.initial >= static_cast<int>(probe.meshes.size()))
      throw InvalidInput("probe '" + probe.name + "': the initial position " + std::to_string(probe.initial) + " is not one of its " +
                         std::to_string(probe.meshes.size()));
    nlohmann::json glbs = nlohmann::json::array();
    for (const TriangleMesh& m : probe.meshes) glbs.push_back(base64_of(glb_bytes(m)));
    data["probes"].push_back({{"name", probe.name},
                              {"label", probe.label},
                              {"values", probe.values},
                              {"initial", probe.initial},
                              {"shown", probe.shown},
                              {"srgb", srgb_json(probe.srgb)},
                              {"glbs", std::move(glbs)}});
  }
  data["probe_points"] = nullptr;
  if (page.probe_point) {
    std::size_t combinations = 1;
    for (const std::string& name : page.probe_point->probes) {
      const auto it = std::find_if(page.probes.begin(), page.probes.end(), [&](const PageProbe& p) { return p.name == name; });
      if (it == page.probes.end()) throw InvalidInput("the probe point names the probe '" + name + "', which the page lacks");
      combinations *= it->meshes.size();
    }
    if (page.probe_point->points.size() != combinations)
      throw InvalidInput("the probe point: expected " + std::to_string(combinations) + " points, one per combination of positions, got " +
                         std::to_string(page.probe_point->points.size()));
    nlohmann::json points = nlohmann::json::array();
    for (const Eigen::Vector3d& p : page.probe_point->points) points.push_back(srgb_json(p));
    data["probe_points"] = {{"probes", page.probe_point->probes}, {"points", std::move(points)}};
  }
  data["color_bar"] = nullptr;
  if (page.color_bar) {
    // Eleven stops of the map: its pieces are linear, so the gradient between them is the map.
    nlohmann::json stops = nlohmann::json::array();
    for (int i = 0; i <= 10; ++i) stops.push_back(srgb_json(colormap_color(page.color_bar->map, i / 10.0)));
    data["color_bar"] = {{"title", page.color_bar->title}, {"min", page.color_bar->min}, {"max", page.color_bar->max}, {"stops", stops}};
  }

  std::string html;
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"generator\" content=\"volspline\">\n<title>";
  html += page_html_escape(page.title);
  html += "</title>\n</head>\n<body>\n<noscript>This page shows a 3D model with JavaScript and WebGL.</noscript>\n";
  html += "<script id=\"volspline-page\" type=\"application/json\">";
  html += script_safe_json(data);
  html += "</script>\n<script>";
  html += web_viewer_script();
  html += "</script>\n</body>\n</html>\n";
  return html;
}

}  // namespace volspline
