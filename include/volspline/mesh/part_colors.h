#pragma once
// The colour of each mesh part (core/conventions.h), shared by everything that colours meshes:
// the renderer (render/mesh_renderer.h) and the glTF writer (mesh/mesh_writer.h).
#include <Eigen/Core>

namespace volspline {

/// The sRGB colour, components in [0, 1], used for a mesh part (core/conventions.h): blue for the
/// u faces, green for v, purple for w (darker at min, lighter at max), orange-red for the
/// Jacobian-zero surface, the matching mid tones for isoparametric surfaces u, v, w = const
/// (parts 7..9), sand for planar slices (10), grey for anything else.
Eigen::Vector3d part_color(int part);

}  // namespace volspline
