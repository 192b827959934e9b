#include "simplex_sampling.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "simplex_lattice.h"
#include "volspline/core/error.h"
#include "volspline/mesh/longest_edge_bisection.h"

namespace volspline {

SimplexSampling simplex_sampling(const TetrahedralMesh& domain, int subdivisions, double target_edge) {
  if (subdivisions < 0 || subdivisions > 64)
    throw InvalidInput("expected 1 to 64 subdivisions per tetrahedron edge, got " + std::to_string(subdivisions));
  if (!(target_edge >= 0) || !std::isfinite(target_edge))
    throw InvalidInput("expected a target edge length >= 0, got " + std::to_string(target_edge));
  SimplexSampling sampling;
  sampling.subdivisions = subdivisions;
  if (subdivisions > 0) {
    SimplexLattice lattice = simplex_lattice(domain, subdivisions);
    sampling.points = std::move(lattice.points);
    sampling.tetrahedra = std::move(lattice.tetrahedra);
    return sampling;
  }
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : domain.points) box.extend(p);
  LongestEdgeBisectionOptions bisection;
  bisection.target_edge = target_edge > 0 ? target_edge : box.diagonal().norm() / 40;
  LongestEdgeBisection refined = bisect_longest_edges(domain, bisection);
  sampling.points = std::move(refined.mesh.points);
  sampling.tetrahedra.reserve(refined.mesh.tetrahedra.size());
  for (const auto& t : refined.mesh.tetrahedra) sampling.tetrahedra.push_back({t[0], t[1], t[2], t[3]});
  return sampling;
}

}  // namespace volspline
