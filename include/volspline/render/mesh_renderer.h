#pragma once
// A headless picture of a boundary mesh, for looking at results without a viewer: ray cast
// (Embree), shaded with a key, a fill and a rim light, coloured by boundary part so the six
// faces of a solid and its Jacobian-zero surface can be told apart at a glance.
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/parts.h"  // part_color, used by ColorMode::ByPart
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/render/colormap.h"
#include "volspline/render/image.h"

namespace volspline {

enum class ColorMode {
  /// Each part its own colour (part_color, the part table of mesh/parts.h).
  ByPart,
  /// Everything in RenderOptions::single_color.
  Single,
  /// RenderOptions::vertex_scalars through RenderOptions::colormap, interpolated across each
  /// triangle and mapped per pixel, so the colours are those of the field, not of a mesh of
  /// colours.
  Scalar,
};

struct RenderOptions {
  int width = 800;
  int height = 600;
  /// Dark lines along the triangle edges, about a pixel wide.
  bool edges = false;
  /// Dark lines along the borders of open surfaces (edges used by one triangle), so slices and
  /// isoparametric surfaces seen edge-on or stacked stay distinct. Closed meshes have none.
  bool outline_borders = true;
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

  /// ColorMode::Scalar: one value per vertex of the mesh.
  std::vector<double> vertex_scalars;
  /// The values at the two ends of the colour map; NaN (the default) takes the range of the
  /// values at vertices of triangles.
  double scalar_min = std::numeric_limits<double>::quiet_NaN();
  double scalar_max = std::numeric_limits<double>::quiet_NaN();
  Colormap colormap = Colormap::Sequential;
  /// ColorMode::Scalar: unless empty, a colour bar titled with this is drawn at the right and
  /// the mesh is framed in the rest of the picture.
  std::string color_bar_title;
};

/// The range [min, max] ColorMode::Scalar maps onto the colour map: the options' own where set,
/// else the extreme values at vertices of triangles, as suggested_coloring (unsigned) ranges them
/// (a field constant up to rounding is centred in a small range); a range of zero width is
/// widened so that the map stays defined. Exposed so that callers (colours in glTF files) agree with pictures.
std::pair<double, double> scalar_range(const TriangleMesh& mesh, const RenderOptions& options);

/// Renders `mesh` as seen through a perspective camera fitted to it. A mesh with no visible
/// triangles gives a picture of the background alone.
/// \throw InvalidInput for a malformed mesh (validate_mesh), options out of range or, for
/// ColorMode::Scalar, not one scalar per vertex; Error if Embree fails.
Image render_mesh(const TriangleMesh& mesh, const RenderOptions& options = {});

}  // namespace volspline
