#pragma once
// A picture of scattered data: each point drawn as a small octahedron coloured by its value
// (the "point view" of the data beside the pictures of a fit, Hua–He–Qin Figs. 7 and 10–12).
// Drawn by the mesh renderer (Embree), so points in front hide those behind; a cutting plane
// leaves out one side to show the inside of a solid cloud.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/plane.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline {

struct PointCloudPictureOptions {
  /// Size, camera and colour map. The colour mode is Scalar and the colour bar is titled with
  /// the value's name whatever these say.
  RenderOptions render;
  /// The octahedra's half-diagonal; 0: 0.35 x the mean spacing of the points drawn (the cube
  /// root of their box's volume per point drawn, flat sides counting as 1e-3 of its diagonal).
  double marker_size = 0;
  /// Points beyond this are thinned to every k-th (in their order) so that at most this many are
  /// drawn; the picture says how many (point_markers' count).
  std::size_t max_points = 250000;
  /// Points on the positive side of this plane (normal·x > offset) are left out.
  std::optional<Plane> cut;
};

/// The octahedra of the points drawn (after thinning and the cut), their vertices carrying the
/// point's value as the mesh's first parameter (u), and how many points they show.
struct PointMarkers {
  TriangleMesh mesh;
  std::vector<double> vertex_values;
  std::size_t points_drawn = 0;
};

/// \throw InvalidInput if the values are not one per point, a point or value is not finite, the
/// marker size is negative or max_points is 0.
PointMarkers point_markers(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& values,
                           const PointCloudPictureOptions& options = {});

/// The picture of the markers, coloured by value with a colour bar titled `value_name`; the range
/// of the colour map is that of all values (not only those drawn) unless the options set it.
/// \throw as point_markers and render_mesh; InvalidInput if no point is left to draw.
Image point_cloud_image(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& values, const std::string& value_name,
                        const PointCloudPictureOptions& options = {});

}  // namespace volspline
