#include "volspline/pipeline/interactive_model_page.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "volspline/core/error.h"
#include "volspline/extract/isoparametric_surfaces.h"
#include "volspline/extract/planar_slices.h"
#include "volspline/io/model_volumes.h"
#include "volspline/pipeline/model_summary.h"

namespace volspline {

namespace {

// The trivariate volumes in R^3 of a model: what the probes can cut.
std::vector<const BSplineVolume*> probed_volumes(const Model& model) {
  std::vector<const BSplineVolume*> volumes;
  for (const ModelObject& object : model.objects)
    if (const auto* v = std::get_if<BSplineVolume>(&object.spline); v != nullptr && v->dimension() == 3) volumes.push_back(v);
  return volumes;
}

}  // namespace

void add_model_probes(InteractivePage& page, const Model& model, const ModelProbeOptions& options, const std::string& source_name) {
  if (options.levels < 2 || options.levels > 64)
    throw InvalidInput("expected 2 to 64 probe levels, got " + std::to_string(options.levels));
  if (options.iso_resolution < 1 || options.slice_resolution < 1)
    throw InvalidInput("expected probe resolutions >= 1, got " + std::to_string(options.iso_resolution) + " and " +
                       std::to_string(options.slice_resolution));
  if (!options.slice_normal.allFinite() || options.slice_normal.norm() == 0)
    throw InvalidInput("expected a finite nonzero slice normal");
  const std::vector<const BSplineVolume*> volumes = probed_volumes(model);
  if (volumes.empty()) return;
  const int n = options.levels;
  const int middle = n / 2;
  static const char* const names[] = {"u", "v", "w"};
  for (int direction = 0; direction < 3; ++direction) {
    PageProbe probe;
    probe.name = names[direction];
    probe.label = names[direction];
    probe.initial = middle;
    probe.srgb = part_color(isoparametric_part(direction));
    probe.meshes.resize(static_cast<std::size_t>(n));
    std::size_t object = 0;
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      const auto* v = std::get_if<BSplineVolume>(&model.objects[i].spline);
      if (v == nullptr || v->dimension() != 3) continue;
      try {
        const std::vector<double> values = isoparametric_values(v->knot_vector(direction), n);
        // The slider shows the first volume's values; other volumes move across their own domains
        // in step (the same fraction of each).
        if (object++ == 0) probe.values = values;
        for (int k = 0; k < n; ++k)
          probe.meshes[static_cast<std::size_t>(k)].append(
              isoparametric_surface(*v, direction, values[static_cast<std::size_t>(k)], {.resolution = options.iso_resolution}));
      } catch (const InvalidInput& e) {
        throw e.located(object_location(source_name, i));
      }
    }
    page.probes.push_back(std::move(probe));
  }
  if (volumes.size() == 1) {
    // Lasser Fig. 10: the point where the three surfaces meet, at every combination of positions.
    const BSplineVolume& v = *volumes.front();
    std::array<std::vector<double>, 3> values;
    for (int d = 0; d < 3; ++d) values[static_cast<std::size_t>(d)] = isoparametric_values(v.knot_vector(d), n);
    const std::vector<double> xyz = v.evaluate_grid(values);
    PageProbePoint point{{"u", "v", "w"}, {}};
    for (std::size_t p = 0; p + 2 < xyz.size(); p += 3) point.points.emplace_back(xyz[p], xyz[p + 1], xyz[p + 2]);
    page.probe_point = std::move(point);
  }
  if (options.slices) {
    const Eigen::Vector3d normal = options.slice_normal.normalized();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const BSplineVolume* v : volumes) {
      const auto [a, b] = sampled_bounding_box(*v, options.slice_resolution);
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d c((corner & 1) ? b.x() : a.x(), (corner & 2) ? b.y() : a.y(), (corner & 4) ? b.z() : a.z());
        lo = std::min(lo, normal.dot(c));
        hi = std::max(hi, normal.dot(c));
      }
    }
    PageProbe probe;
    probe.name = "slice";
    probe.label = "slice offset";
    probe.initial = middle;
    probe.shown = false;
    probe.srgb = part_color(Part::Slice);
    std::vector<Plane> planes;
    for (int k = 0; k < n; ++k) {
      const double offset = lo + (hi - lo) * (k + 0.5) / n;
      probe.values.push_back(offset);
      planes.push_back({normal, offset});
    }
    probe.meshes.resize(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      const auto* v = std::get_if<BSplineVolume>(&model.objects[i].spline);
      if (v == nullptr || v->dimension() != 3) continue;
      for (int k = 0; k < n; ++k) {
        try {
          probe.meshes[static_cast<std::size_t>(k)].append(
              planar_slice(*v, planes[static_cast<std::size_t>(k)], {.resolution = options.slice_resolution}));
        } catch (const InvalidInput& e) {
          throw e.located(object_location(source_name, i));
        }
      }
    }
    page.probes.push_back(std::move(probe));
  }
}

nlohmann::json model_page_info(const Model& model, const std::string& source_name) {
  return {{"file", source_name}, {"objects", model_object_summaries(model)}};
}

}  // namespace volspline
