#include "volspline/pipeline/solid_view_picture.h"

#include <limits>

#include "volspline/core/error.h"
#include "volspline/core/progress.h"
#include "volspline/extract/planar_slices.h"
#include "volspline/io/model_volumes.h"
#include "volspline/render/colormap.h"

namespace volspline {
namespace {

// The control values of the attribute `name` of `object`. \throw InvalidInput naming the
// attributes it has.
const std::vector<double>& attribute_values(const ModelObject& object, const std::string& name) {
  const auto it = object.attributes.find(name);
  if (it != object.attributes.end()) return it->second;
  std::string known;
  for (const auto& [attribute, values] : object.attributes) known += (known.empty() ? "" : ", ") + attribute;
  throw InvalidInput("cannot colour by '" + name + "': expected jacobian, u, v, w or an attribute of the object (" +
                     (known.empty() ? std::string("it has none") : "it has " + known) + ")");
}

// One frame for all volumes: the box around their sampled boxes.
std::pair<Eigen::Vector3d, Eigen::Vector3d> model_box(const Model& model, const std::string& source_name) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for_each_volume(model, source_name, [&](std::size_t, const ModelObject&, const BSplineVolume& volume) {
    const auto box = sampled_bounding_box(volume);
    lo = lo.cwiseMin(box.first);
    hi = hi.cwiseMax(box.second);
  });
  return {lo, hi};
}

// Sets the colouring of `picture` (render options and mesh fields) from `scalars`.
void color_by(SolidViewPicture& picture, const SolidViewPictureRequest& request, std::vector<double> scalars) {
  const ScalarField& field = *request.color;
  const ScalarColoring coloring = suggested_coloring(scalars, field.kind == ScalarKind::Jacobian);
  RenderOptions& options = picture.render;
  options.color = ColorMode::Scalar;
  options.colormap = coloring.map;
  options.scalar_min = request.range ? request.range->first : coloring.min;
  options.scalar_max = request.range ? request.range->second : coloring.max;
  options.color_bar_title = field.name();
  options.vertex_scalars = std::move(scalars);
  const auto [low, high] = scalar_range(picture.mesh, options);
  for (const double s : options.vertex_scalars)
    picture.mesh_fields.vertex_colors.push_back(colormap_color(options.colormap, (s - low) / (high - low)));
  // The PLY vertex already has x, y, z, u, v, w: a field of one of those names (--color u) is
  // written as color_u.
  const std::string name = field.name();
  const bool reserved = name == "x" || name == "y" || name == "z" || name == "u" || name == "v" || name == "w";
  picture.mesh_fields.scalar_name = !is_ply_property_name(name) ? "attribute" : reserved ? "color_" + name : name;
  picture.mesh_fields.vertex_scalars = options.vertex_scalars;
}

}  // namespace

SolidViewPicture solid_view_picture(const Model& model, const SolidViewPictureRequest& request, Progress* progress) {
  if (request.range && !(request.range->first < request.range->second))
    throw InvalidInput("expected a colour range MIN < MAX, got " + std::to_string(request.range->first) + ", " +
                       std::to_string(request.range->second));
  SolidViewPicture picture;
  picture.render = request.render;
  std::optional<ProgressPhase> phase(std::in_place, progress, "surfaces", static_cast<double>(count_volumes(model)), "volumes");
  const auto [lo, hi] = model_box(model, request.source_name);
  picture.planes = requested_planes(request.view, lo, hi);
  std::vector<double> scalars;
  picture.volumes = for_each_volume(model, request.source_name, [&](std::size_t, const ModelObject& object, const BSplineVolume& volume) {
    const TriangleMesh part = solid_view_mesh(volume, request.view, picture.planes);
    if (request.color) {
      static const std::vector<double> none;
      const auto& attribute = request.color->kind == ScalarKind::Attribute ? attribute_values(object, request.color->attribute) : none;
      const auto values = evaluate_scalar_field(volume, *request.color, part.parameters, attribute);
      scalars.insert(scalars.end(), values.begin(), values.end());
    }
    picture.mesh.append(part);
    phase->advance();
  });
  if (request.color) color_by(picture, request, std::move(scalars));
  phase.emplace(progress, "rendering");
  picture.image = render_mesh(picture.mesh, picture.render);
  return picture;
}

}  // namespace volspline
