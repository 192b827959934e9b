#include "volspline/mesh/solid_views.h"

#include <cmath>

#include "volspline/core/error.h"
#include "volspline/mesh/face_tessellation.h"
#include "volspline/mesh/isoparametric_surfaces.h"

namespace volspline {

bool SolidViewRequest::probes_empty() const {
  return families.empty() && !through && series.empty() && planes.empty() && !core && paddlewheels.empty();
}

std::vector<Plane> requested_planes(const SolidViewRequest& request, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (!lo.allFinite() || !hi.allFinite()) throw InvalidInput("the box of the solids is not finite");
  std::vector<Plane> planes;
  for (const Plane& p : request.planes) {
    if (!p.normal.allFinite() || !std::isfinite(p.offset) || p.normal.norm() == 0)
      throw InvalidInput("a cross section needs a finite nonzero normal and a finite offset");
    planes.push_back({p.normal.normalized(), p.offset / p.normal.norm()});
  }
  for (const auto& s : request.series) {
    const auto more = parallel_planes(s.axis, s.count, lo, hi);
    planes.insert(planes.end(), more.begin(), more.end());
  }
  if (request.core) {
    const auto more = core_planes(*request.core);
    planes.insert(planes.end(), more.begin(), more.end());
  }
  for (const auto& w : request.paddlewheels) {
    if (w.axis < 0 || w.axis > 2) throw InvalidInput("expected a paddlewheel axis 0..2 (x, y, z), got " + std::to_string(w.axis));
    const auto more = paddlewheel_planes(w.point.value_or(0.5 * (lo + hi)), Eigen::Vector3d::Unit(w.axis), w.count);
    planes.insert(planes.end(), more.begin(), more.end());
  }
  return planes;
}

TriangleMesh solid_view_mesh(const BSplineVolume& volume, const SolidViewRequest& request, const std::vector<Plane>& planes) {
  TriangleMesh mesh;
  if (request.faces) mesh.append(tessellate_faces(volume, {.resolution = request.resolution}));
  const IsoparametricOptions iso{.resolution = request.resolution};
  for (const auto& f : request.families) mesh.append(isoparametric_family(volume, f.direction, f.count, iso));
  if (request.through) mesh.append(isoparametric_surfaces_through(volume, *request.through, iso));
  if (!planes.empty()) mesh.append(planar_slices(volume, planes, {.resolution = request.resolution}));
  return mesh;
}

}  // namespace volspline
