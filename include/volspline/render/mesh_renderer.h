#pragma once
// A headless picture of a boundary mesh, for looking at results without a viewer: ray cast
// (Embree), shaded with a key, a fill and a rim light, coloured by boundary part so the six
// faces of a solid and its Jacobian-zero surface can be told apart at a glance.
#include <Eigen/Core>

#include "volspline/mesh/part_colors.h"  // part_color, used by ColorMode::ByPart
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/render/image.h"

namespace volspline {

enum class ColorMode {
  /// Each part its own colour (part_color).
  ByPart,
  /// Everything in RenderOptions::single_color.
  Single,
};

struct RenderOptions {
  int width = 800;
  int height = 600;
  /// Dark lines along the triangle edges, about a pixel wide.
  bool edges = false;
  /// Background pixels get alpha 0 instead of the light gradient.
  bool transparent_background = false;
  ColorMode color = ColorMode::ByPart;
  /// sRGB colour in [0, 1] for ColorMode::Single.
  Eigen::Vector3d single_color{0.72, 0.74, 0.78};
  /// The direction the camera looks in; the camera is placed on the opposite side of the mesh.
  /// The default looks down on the mesh from the +x, +y, +z side.
  Eigen::Vector3d view_direction{-1.0, -1.3, -0.8};
  /// World direction that appears upwards in the picture (need not be orthogonal to the view).
  Eigen::Vector3d up{0.0, 0.0, 1.0};
  /// Angle of view across the shorter image side; it sets how strong the perspective is, and the
  /// camera distance is then chosen so the mesh fills about 90% of the frame.
  double field_of_view_deg = 35;
  /// 2 x 2 samples per pixel, which smooths silhouettes and edge lines.
  bool supersample = true;
  /// Interpolate area-weighted vertex normals so curved surfaces look smooth.
  bool smooth_normals = true;
  /// With smooth_normals, a triangle's corner normal averages only the neighbouring triangles
  /// whose normals are within this angle of its own, so creases (the edges of a cube, the seams
  /// between a solid's faces) stay crisp.
  double crease_angle_deg = 40;
};

/// Renders `mesh` as seen through a perspective camera fitted to it. A mesh with no visible
/// triangles gives a picture of the background alone.
/// \throw InvalidInput for a malformed mesh (validate_mesh) or options out of range, Error if
/// Embree fails.
Image render_mesh(const TriangleMesh& mesh, const RenderOptions& options = {});

}  // namespace volspline
