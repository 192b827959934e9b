#include "volspline/extract/simplex_slices.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "simplex_lattice.h"
#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

SimplexSlice simplex_plane_slice(const DmsSplineVolume& volume, const Plane& plane, const SimplexSliceOptions& options) {
  if (!(plane.normal.norm() > 0) || !plane.normal.allFinite() || !std::isfinite(plane.offset))
    throw InvalidInput("expected a plane with a finite, nonzero normal");
  const int column = !options.attribute.empty() ? volume.attribute_column(options.attribute) : (volume.attribute_names().empty() ? -1 : 3);
  const TetrahedralMesh& domain = volume.domain();
  const int k = options.subdivisions > 0 ? options.subdivisions
                                         : automatic_lattice_subdivisions(domain, options.target_edge, options.max_subdivisions);
  if (k < 1 || k > 64) throw InvalidInput("expected 1 to 64 subdivisions per tetrahedron edge, got " + std::to_string(k));
  const SimplexLattice lattice = simplex_lattice(domain, k);
  const Eigen::Vector3d n = plane.normal.normalized();
  const double d = plane.offset / plane.normal.norm();
  MarchingTetrahedra marching;
  for (const auto& t : lattice.tetrahedra) {
    std::array<MarchingTetrahedra::Sample, 4> s;
    for (int c = 0; c < 4; ++c) {
      const std::int64_t id = t[static_cast<std::size_t>(c)];
      const Eigen::Vector3d& x = lattice.points[static_cast<std::size_t>(id)];
      s[static_cast<std::size_t>(c)] = {id, x, n.dot(x) - d};
    }
    marching.add_tetrahedron_oriented_by_corners(s);
  }
  SimplexSlice result;
  result.subdivisions = k;
  const std::size_t vertices = marching.vertices().size();
  std::vector<Eigen::Vector3d> positions(vertices);
  if (column >= 0) result.values.resize(vertices);
  const DmsSplineEvaluator prototype(volume);
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  tbb::parallel_for(std::size_t{0}, vertices, [&](std::size_t v) {
    const DmsSplinePoint p = evaluators.local().evaluate(marching.vertices()[v]);
    positions[v] = p.value.head<3>();
    if (column >= 0) result.values[v] = p.value[column];
  });
  for (std::size_t v = 0; v < vertices; ++v) result.mesh.add_vertex(positions[v], marching.vertices()[v]);
  for (const auto& t : marching.triangles()) result.mesh.add_triangle(t[0], t[1], t[2], Part::Slice);
  return result;
}

}  // namespace volspline
