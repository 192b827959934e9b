// volspline data DATA [--json] [--png P.png [--attribute A] [--size W,H] [--view DX,DY,DZ]
//   [--cut-open NX,NY,NZ,D] [--marker-size S] [--max-points N]] [--iso NAME:VALUE [-o OUT.ply]]
// What volume data holds (points, box, grid, attributes and their ranges) and, with --png, the
// data's point view: every point a small octahedron coloured by an attribute
// (render/point_cloud_image.h), the picture beside which a fit's X-ray and isosurfaces are
// judged (docs/fitting.md, "Examples"); with --iso, on grid data, the data's own isosurface
// (pipeline/grid_isosurface.h) instead of the points.
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/io/volume_data.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/fit_baselines.h"
#include "volspline/pipeline/grid_isosurface.h"
#include "volspline/render/point_cloud_image.h"

namespace volspline::cli {

namespace {

struct DataRequest {
  std::string data, png, attribute, size = "800,600", view, cut_open, iso, out;
  double marker_size = 0;
  long long max_points = 250000;
  bool json = false;
};

void run_data(const DataRequest& r) {
  if (!r.png.empty() && std::filesystem::path(r.png).extension() != ".png")
    throw InvalidInput("expected a file name ending in .png, got '" + r.png + "'", "--png");
  if (r.png.empty() && (!r.attribute.empty() || !r.view.empty() || !r.cut_open.empty()))
    throw InvalidInput("--attribute, --view and --cut-open shape the picture; give --png too", "--png");
  if (!r.out.empty() && r.iso.empty()) throw InvalidInput("-o writes the isosurface of --iso; give --iso too", "-o");
  std::optional<MeshFormat> format;
  if (!r.out.empty()) format = mesh_format_from_path(r.out);
  std::string iso_name;
  double iso_value = 0;
  if (!r.iso.empty()) {
    const std::size_t colon = r.iso.rfind(':');
    if (colon == std::string::npos || colon == 0) throw InvalidInput("expected NAME:VALUE, got '" + r.iso + "'", "--iso");
    iso_name = r.iso.substr(0, colon);
    iso_value = parse_numbers(r.iso.substr(colon + 1), 1, "--iso")[0];
    if (!r.cut_open.empty()) throw InvalidInput("--cut-open cuts the points' picture; an isosurface is drawn whole", "--cut-open");
    if (!r.attribute.empty()) throw InvalidInput("--iso names its attribute (NAME:VALUE); --attribute colours the points' picture", "--attribute");
  }
  if (!(r.marker_size >= 0)) throw InvalidInput("expected a size >= 0 (0: from the spacing of the points)", "--marker-size");
  if (r.max_points < 1) throw InvalidInput("expected at least 1", "--max-points");
  PointCloudPictureOptions picture;
  if (!r.png.empty()) {
    const auto wh = parse_integers(r.size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + r.size + "'", "--size");
    picture.render.width = wh[0];
    picture.render.height = wh[1];
    if (!r.view.empty()) picture.render.view_direction = parse_view_direction(r.view, "--view");
    if (!r.cut_open.empty()) picture.cut = parse_plane(r.cut_open, "--cut-open");
    picture.marker_size = r.marker_size;
    picture.max_points = static_cast<std::size_t>(r.max_points);
  }
  std::optional<VolumeData> generated = generated_volume_data(r.data);
  const VolumeData data = generated ? std::move(*generated) : read_volume_data(r.data);
  int column = 0;
  if (!r.attribute.empty()) column = data.attribute_column(r.attribute);
  else if (!r.png.empty() && data.attribute_names.empty())
    throw InvalidInput(r.data + " has no attribute to colour the points by", "--png");

  Eigen::AlignedBox3d box;
  for (const auto& p : data.points) box.extend(p);
  const std::optional<RegularGridData> grid = regular_grid_of(data);
  nlohmann::json summary = {{"data", r.data}, {"points", data.size()}};
  if (!data.points.empty()) summary["box"] = {{box.min().x(), box.min().y(), box.min().z()}, {box.max().x(), box.max().y(), box.max().z()}};
  if (grid) summary["grid"] = {grid->axes[0].size(), grid->axes[1].size(), grid->axes[2].size()};
  summary["attributes"] = nlohmann::json::array();
  for (std::size_t a = 0; a < data.attribute_names.size(); ++a) {
    const auto values = data.attributes.col(static_cast<Eigen::Index>(a));
    summary["attributes"].push_back({{"name", data.attribute_names[a]},
                                     {"min", data.size() ? values.minCoeff() : 0.0},
                                     {"max", data.size() ? values.maxCoeff() : 0.0},
                                     {"mean", data.size() ? values.mean() : 0.0}});
  }
  if (!r.iso.empty()) {
    if (!grid)
      throw InvalidInput(r.data + ": isosurfaces need data on a regular 3-D grid (at least 2 distinct coordinates along each axis, "
                                  "every combination once: images, generated grids); these points are not",
                         "--iso");
    const TriangleMesh surface = grid_isosurface(*grid, iso_name, iso_value);
    summary["isosurface"] = {{"attribute", iso_name}, {"value", iso_value}, {"triangles", surface.num_triangles()}};
    RenderOptions render = picture.render;
    render.color = ColorMode::Single;
    if (!r.png.empty() && surface.num_triangles() == 0)
      throw InvalidInput(iso_name + " does not take the value " + r.iso.substr(r.iso.rfind(':') + 1) + " inside the grid's cells", "--iso");
    if (format && !r.png.empty()) write_mesh_and_picture(surface, r.out, *format, false, r.png, render);
    else if (format) write_mesh(surface, r.out);
    else if (!r.png.empty()) write_png(render_mesh(surface, render), r.png);
  } else if (!r.png.empty()) {
    const std::vector<double> values(data.attributes.col(column).begin(), data.attributes.col(column).end());
    const PointMarkers markers = point_markers(data.points, values, picture);
    summary["picture"] = {{"png", r.png}, {"attribute", data.attribute_names[static_cast<std::size_t>(column)]}, {"points_drawn", markers.points_drawn}};
    write_png(point_cloud_image(data.points, values, data.attribute_names[static_cast<std::size_t>(column)], picture), r.png);
  }
  if (r.json) {
    std::cout << json_text(summary) << "\n";
    return;
  }
  std::cout << r.data << ": " << data.size() << " points";
  if (!data.points.empty())
    std::cout << " in [" << box.min().x() << ", " << box.max().x() << "] x [" << box.min().y() << ", " << box.max().y() << "] x ["
              << box.min().z() << ", " << box.max().z() << "]";
  if (grid) std::cout << ", a regular grid of " << grid->axes[0].size() << " x " << grid->axes[1].size() << " x " << grid->axes[2].size();
  std::cout << "\n";
  for (const auto& a : summary["attributes"])
    std::cout << "  " << a["name"].get<std::string>() << ": " << a["min"].get<double>() << " .. " << a["max"].get<double>() << " (mean "
              << a["mean"].get<double>() << ")\n";
  if (!r.iso.empty()) {
    std::cout << "isosurface " << r.iso << ": " << summary["isosurface"]["triangles"].get<std::size_t>() << " triangles\n";
    if (!r.out.empty()) std::cout << "wrote " << r.out << "\n";
    if (!r.png.empty()) std::cout << "wrote " << r.png << "\n";
  } else if (!r.png.empty())
    std::cout << "wrote " << r.png << ": " << summary["picture"]["points_drawn"].get<std::size_t>() << " points coloured by "
              << summary["picture"]["attribute"].get<std::string>() << "\n";
}

}  // namespace

void add_data_command(CLI::App& app) {
  auto r = std::make_shared<DataRequest>();
  auto* cmd = app.add_subcommand("data", "What volume data holds (points, box, grid, attributes and their ranges) and, with --png, a "
                                         "picture of its points coloured by an attribute");
  cmd->add_option("DATA", r->data, kVolumeDataHelp)->required();
  cmd->add_flag("--json", r->json, "print the summary as JSON");
  cmd->add_option("--png", r->png, "the points as small octahedra coloured by an attribute (.png)");
  cmd->add_option("--attribute", r->attribute, "the attribute the points are coloured by (default: the first)");
  cmd->add_option("--size", r->size, "W,H in pixels (default 800,600)");
  cmd->add_option("--view", r->view, "DX,DY,DZ: the direction the camera looks in (default -1,-1.3,-0.8)");
  cmd->add_option("--cut-open", r->cut_open, "NX,NY,NZ,D: leave out the points where N.x > D, to show the inside");
  cmd->add_option("--marker-size", r->marker_size, "the octahedra's half-diagonal (default 0: 0.35 x the mean spacing of the points)");
  cmd->add_option("--iso", r->iso, "NAME:VALUE: the isosurface of an attribute of grid data (images, generated grids), linear on "
                                  "the grid's Kuhn tetrahedra; --png draws it instead of the points");
  cmd->add_option("-o,--output", r->out, "with --iso: the isosurface as a mesh (.ply, .obj, .stl or .glb)");
  cmd->add_option("--max-points", r->max_points, "at most this many points are drawn, every k-th of more (default 250000)");
  cmd->callback([r] { run_data(*r); });
}

}  // namespace volspline::cli
