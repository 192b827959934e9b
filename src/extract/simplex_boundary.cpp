#include "volspline/extract/simplex_boundary.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/mesh/longest_edge_bisection.h"
#include "volspline/mesh/parts.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

TriangleMesh simplex_boundary_mesh(const DmsSplineVolume& volume, const SimplexBoundaryOptions& options) {
  if (!(options.target_edge >= 0) || !std::isfinite(options.target_edge))
    throw InvalidInput("expected a target edge length >= 0, got " + format_double(options.target_edge));
  const TetrahedralMesh& domain = volume.domain();
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : domain.points) box.extend(p);
  LongestEdgeBisectionOptions bisection;
  bisection.target_edge = options.target_edge > 0 ? options.target_edge : box.diagonal().norm() / 40;
  const LongestEdgeBisection refined = bisect_longest_edges(domain, bisection);
  const std::vector<BoundaryFace> faces = boundary_faces(refined.mesh);

  // The boundary's own vertices, numbered in order of first use.
  std::vector<int> vertex_of(refined.mesh.points.size(), -1);
  std::vector<Eigen::Vector3d> points;
  for (const BoundaryFace& f : faces)
    for (const int v : f.vertices)
      if (vertex_of[static_cast<std::size_t>(v)] < 0) {
        vertex_of[static_cast<std::size_t>(v)] = static_cast<int>(points.size());
        points.push_back(refined.mesh.points[static_cast<std::size_t>(v)]);
      }
  std::vector<Eigen::Vector3d> mapped(points.size());
  const DmsSplineEvaluator prototype(volume);
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { mapped[i] = evaluators.local().evaluate(points[i]).value.head<3>(); });

  TriangleMesh mesh;
  for (std::size_t i = 0; i < points.size(); ++i) mesh.add_vertex(mapped[i], points[i]);
  for (const BoundaryFace& f : faces)
    mesh.add_triangle(vertex_of[static_cast<std::size_t>(f.vertices[0])], vertex_of[static_cast<std::size_t>(f.vertices[1])],
                      vertex_of[static_cast<std::size_t>(f.vertices[2])], Part::DomainBoundary);
  return mesh;
}

}  // namespace volspline
