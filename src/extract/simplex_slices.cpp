#include "volspline/extract/simplex_slices.h"

#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "simplex_sampling.h"
#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

using SliceEvaluators = tbb::enumerable_thread_specific<DmsSplineEvaluator>;

SimplexSlice slice_through_sampling(const Plane& plane, const SimplexSampling& sampling, int column, SliceEvaluators& evaluators) {
  const Eigen::Vector3d n = plane.normal.normalized();
  const double d = plane.offset / plane.normal.norm();
  MarchingTetrahedra marching;
  for (const auto& t : sampling.tetrahedra) {
    std::array<MarchingTetrahedra::Sample, 4> s;
    for (int c = 0; c < 4; ++c) {
      const std::int64_t id = t[static_cast<std::size_t>(c)];
      const Eigen::Vector3d& x = sampling.points[static_cast<std::size_t>(id)];
      s[static_cast<std::size_t>(c)] = {id, x, n.dot(x) - d};
    }
    marching.add_tetrahedron_oriented_by_corners(s);
  }
  SimplexSlice result;
  result.subdivisions = sampling.subdivisions;
  result.sampled_tetrahedra = static_cast<long long>(sampling.tetrahedra.size());
  const std::size_t vertices = marching.vertices().size();
  std::vector<Eigen::Vector3d> positions(vertices);
  if (column >= 0) result.values.resize(vertices);
  tbb::parallel_for(std::size_t{0}, vertices, [&](std::size_t v) {
    const DmsSplinePoint p = evaluators.local().evaluate(marching.vertices()[v]);
    positions[v] = p.value.head<3>();
    if (column >= 0) result.values[v] = p.value[column];
  });
  for (std::size_t v = 0; v < vertices; ++v) result.mesh.add_vertex(positions[v], marching.vertices()[v]);
  for (const auto& t : marching.triangles()) result.mesh.add_triangle(t[0], t[1], t[2], Part::Slice);
  return result;
}

}  // namespace

std::vector<SimplexSlice> simplex_plane_slices(const DmsSplineVolume& volume, std::span<const Plane> planes, const SimplexSliceOptions& options) {
  for (const Plane& plane : planes)
    if (!(plane.normal.norm() > 0) || !plane.normal.allFinite() || !std::isfinite(plane.offset))
      throw InvalidInput("expected a plane with a finite, nonzero normal");
  const int column = !options.attribute.empty() ? volume.attribute_column(options.attribute) : (volume.attribute_names().empty() ? -1 : 3);
  if (planes.empty()) return {};
  const SimplexSampling sampling = simplex_sampling(volume.domain(), options.subdivisions, options.target_edge);
  const DmsSplineEvaluator prototype(volume);
  SliceEvaluators evaluators(prototype);
  std::vector<SimplexSlice> slices;
  slices.reserve(planes.size());
  for (const Plane& plane : planes) slices.push_back(slice_through_sampling(plane, sampling, column, evaluators));
  return slices;
}

SimplexSlice simplex_plane_slice(const DmsSplineVolume& volume, const Plane& plane, const SimplexSliceOptions& options) {
  return std::move(simplex_plane_slices(volume, std::span<const Plane>(&plane, 1), options).front());
}

}  // namespace volspline
