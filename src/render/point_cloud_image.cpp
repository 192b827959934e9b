#include "volspline/render/point_cloud_image.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/mesh/parts.h"

namespace volspline {

PointMarkers point_markers(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& values,
                           const PointCloudPictureOptions& options) {
  if (values.size() != points.size())
    throw InvalidInput("expected one value per point: " + std::to_string(points.size()) + " points, " + std::to_string(values.size()) +
                           " values",
                       "values");
  if (!(options.marker_size >= 0) || !std::isfinite(options.marker_size)) throw InvalidInput("expected a marker size >= 0", "marker_size");
  if (options.max_points == 0) throw InvalidInput("expected max_points >= 1", "max_points");
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput("point " + std::to_string(i) + " is not finite", "points");
    if (!std::isfinite(values[i])) throw InvalidInput("the value of point " + std::to_string(i) + " is not finite", "values");
    box.extend(points[i]);
  }
  PointMarkers out;
  if (points.empty()) return out;
  const std::size_t stride = (points.size() + options.max_points - 1) / options.max_points;
  double size = options.marker_size;
  if (size == 0) {
    // The spacing of the points drawn (every stride-th): thinned points are farther apart.
    const double diagonal = box.diagonal().norm();
    const Eigen::Vector3d sides = box.diagonal().cwiseMax(Eigen::Vector3d::Constant(1e-3 * std::max(diagonal, 1e-300)));
    const std::size_t drawn = (points.size() + stride - 1) / stride;
    size = 0.35 * std::cbrt(sides.prod() / static_cast<double>(drawn));
    if (!(size > 0)) size = 1e-3;  // a single point, or all at one place
  }
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  // The eight faces of the octahedron, outward (counter-clockwise seen from outside).
  static constexpr int kFaces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector3d& p = points[i];
    if (options.cut && options.cut->normal.dot(p) > options.cut->offset) continue;
    const int base = static_cast<int>(out.mesh.num_vertices());
    // +x, -x, +y, -y, +z, -z
    for (int a = 0; a < 3; ++a)
      for (const double side : {1.0, -1.0}) {
        out.mesh.add_vertex(p + side * size * axes[a], Eigen::Vector3d(values[i], 0, 0));
        out.vertex_values.push_back(values[i]);
      }
    for (const auto& f : kFaces) {
      // Vertex order in the loop above: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
      out.mesh.add_triangle(base + f[0], base + f[1], base + f[2], Part::AttributeIsosurface);
    }
    ++out.points_drawn;
  }
  return out;
}

Image point_cloud_image(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& values, const std::string& value_name,
                        const PointCloudPictureOptions& options) {
  const PointMarkers markers = point_markers(points, values, options);
  if (markers.points_drawn == 0) throw InvalidInput("no point is left to draw (all are on the cut's positive side)", "cut");
  RenderOptions render = options.render;
  render.color = ColorMode::Scalar;
  render.vertex_scalars = markers.vertex_values;
  render.color_bar_title = value_name;
  render.smooth_normals = false;
  render.outline_borders = false;
  // All values' range (not only those drawn); a constant one is left to the renderer, which
  // widens it.
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  if (*low < *high && std::isnan(render.scalar_min) && std::isnan(render.scalar_max)) {
    render.scalar_min = *low;
    render.scalar_max = *high;
  }
  return render_mesh(markers.mesh, render);
}

}  // namespace volspline
