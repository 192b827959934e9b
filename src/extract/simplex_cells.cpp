#include "volspline/extract/simplex_cells.h"

#include <Eigen/Geometry>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "simplex_lattice.h"
#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

TriangleMesh simplex_cell_mesh(const DmsSplineVolume& volume, int subdivisions, double shrink) {
  if (subdivisions < 1 || subdivisions > 16) throw InvalidInput("expected 1 to 16 cells per tetrahedron edge, got " + std::to_string(subdivisions));
  if (!(shrink > 0 && shrink <= 1)) throw InvalidInput("expected a shrink factor in (0, 1], got " + std::to_string(shrink));
  const SimplexLattice lattice = simplex_lattice(volume.domain(), subdivisions);
  std::vector<Eigen::Vector3d> mapped(lattice.points.size());
  const DmsSplineEvaluator prototype(volume);
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  tbb::parallel_for(std::size_t{0}, lattice.points.size(),
                    [&](std::size_t i) { mapped[i] = evaluators.local().evaluate(lattice.points[i]).value.head<3>(); });
  TriangleMesh mesh;
  for (const auto& t : lattice.tetrahedra) {
    std::array<Eigen::Vector3d, 4> p, x;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c) {
      p[static_cast<std::size_t>(c)] = mapped[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
      x[static_cast<std::size_t>(c)] = lattice.points[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
      centroid += p[static_cast<std::size_t>(c)] / 4;
    }
    const bool positive = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) > 0;
    int v[4];
    for (int c = 0; c < 4; ++c)
      v[c] = mesh.add_vertex(centroid + shrink * (p[static_cast<std::size_t>(c)] - centroid), x[static_cast<std::size_t>(c)]);
    // Faces opposite each corner, counter-clockwise from outside for a positive tetrahedron.
    static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    for (const auto& f : kFaces) {
      if (positive) mesh.add_triangle(v[f[0]], v[f[1]], v[f[2]], Part::DomainBoundary);
      else mesh.add_triangle(v[f[0]], v[f[2]], v[f[1]], Part::DomainBoundary);
    }
  }
  return mesh;
}

}  // namespace volspline
