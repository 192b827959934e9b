#pragma once
// Looking inside the solids of a model (Lasser 1994 §IV) in one call: the planes of the request
// in one frame for all volumes (so a series of slices cuts a multipatch model evenly), each
// volume's solid_view_mesh, the scalar field it is coloured by, the colour map and bar, and the
// rendered picture — everything `volspline view` shows, as values in memory; the caller decides
// what to write where.
//
// This is a pipeline: it joins io/ (the model and its attributes), extract/ (the meshes),
// analysis/ (the fields) and render/ (the picture), so it lives above all of them.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "volspline/analysis/scalar_fields.h"
#include "volspline/extract/solid_views.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline {

class Progress;

struct SolidViewPictureRequest {
  /// What to show of every volume.
  SolidViewRequest view;
  /// Colour by this field (the Jacobian, a parameter or an attribute of each object); without
  /// one, every part has its own colour (part_color).
  std::optional<ScalarField> color;
  /// The values at the ends of the colour map, min < max; without them, suggested_coloring's
  /// (a Jacobian of both signs is centred on 0).
  std::optional<std::pair<double, double>> range;
  /// Size, camera, edges, background. Its colouring fields are set from `color` and `range`.
  RenderOptions render;
  /// Names the model in error messages ("model.json: objects[1]: ..."), as parse_model's
  /// source_name.
  std::string source_name;
};

struct SolidViewPicture {
  /// Every volume's solid_view_mesh in object order, appended.
  TriangleMesh mesh;
  /// requested_planes for the box around all volumes.
  std::vector<Plane> planes;
  /// The number of volume objects shown.
  std::size_t volumes = 0;
  /// The options `image` was rendered with: the request's, with the field's values, colour map,
  /// range and bar title filled in when coloured.
  RenderOptions render;
  /// What a mesh file needs to carry the colouring like the picture: the field per vertex (PLY
  /// property named after the field where it can be, else "attribute") and its colours (glTF).
  /// Empty without a field.
  MeshWriteOptions mesh_fields;
  Image image;
};

/// The picture of the request for the volume objects of `model`, reporting the phases
/// "surfaces" (counting volumes) and "rendering" to `progress` unless null. Other objects
/// (curves, surfaces) are ignored; probes that miss the solids give an empty mesh and a
/// picture of the background.
/// \throw InvalidInput located at request.source_name if the model has no volume objects; as
/// requested_planes, solid_view_mesh and evaluate_scalar_field (located at the object,
/// "SOURCE: objects[i]"), also where an object lacks the attribute to colour by; as
/// render_mesh for bad render options. Error if Embree fails.
SolidViewPicture solid_view_picture(const Model& model, const SolidViewPictureRequest& request, Progress* progress = nullptr);

}  // namespace volspline
