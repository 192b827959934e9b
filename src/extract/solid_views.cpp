#include "volspline/extract/solid_views.h"

#include <algorithm>
#include <cmath>

#include "volspline/core/error.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/extract/isoparametric_surfaces.h"
#include "volspline/mesh/mesh_clipping.h"

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

std::vector<Plane> cut_planes(const SolidViewRequest& request) {
  std::vector<Plane> cuts;
  if (!request.cutaway) return cuts;
  for (const Plane& p : request.planes) cuts.push_back({p.normal.normalized(), p.offset / p.normal.norm()});
  if (request.core) {
    const auto core = core_planes(*request.core);
    cuts.insert(cuts.end(), core.begin(), core.end());
  }
  return cuts;
}

TriangleMesh solid_view_mesh(const BSplineVolume& volume, const SolidViewRequest& request, const std::vector<Plane>& planes) {
  TriangleMesh mesh;
  const std::vector<Plane> cuts = cut_planes(request);
  const auto is_cut = [&cuts](const Plane& p) {
    return std::any_of(cuts.begin(), cuts.end(), [&p](const Plane& c) { return c.normal == p.normal && c.offset == p.offset; });
  };
  if (request.faces || request.cutaway) {
    const TriangleMesh faces = tessellate_faces(volume, {.resolution = request.resolution});
    mesh.append(cuts.empty() ? faces : remove_convex_region(faces, cuts));
  }
  const IsoparametricOptions iso{.resolution = request.resolution};
  for (const auto& f : request.families) mesh.append(isoparametric_family(volume, f.direction, f.count, iso));
  if (request.through) mesh.append(isoparametric_surfaces_through(volume, *request.through, iso));
  std::vector<Plane> whole;
  for (const Plane& p : planes)
    if (!is_cut(p)) whole.push_back(p);
  if (!whole.empty()) mesh.append(planar_slices(volume, whole, {.resolution = request.resolution}));
  // Each wall of the wedge is its slice where the point is on the positive side of the others.
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    std::vector<Plane> others;
    for (std::size_t j = 0; j < cuts.size(); ++j)
      if (j != i) others.push_back(cuts[j]);
    const TriangleMesh slice = planar_slice(volume, cuts[i], {.resolution = request.resolution});
    mesh.append(others.empty() ? slice : keep_convex_region(slice, others));
  }
  return mesh;
}

}  // namespace volspline
