#pragma once
// The sampling tetrahedra over which isosurfaces and slices of a DMS spline volume are marched
// (Hua–He–Qin Fig. 13's upsampling), crack-free either way:
// - locally (subdivisions = 0): conforming longest-edge bisection (mesh/longest_edge_bisection.h)
//   until every edge is at most the target edge; large tetrahedra are refined, small ones left
//   alone, and neighbours share every sampled edge;
// - uniformly (subdivisions = k > 0): every domain tetrahedron cut into k³ by the edgewise
//   subdivision of its barycentric lattice (simplex_lattice.h).
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

struct SimplexSampling {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<std::int64_t, 4>> tetrahedra;
  /// k of the uniform lattice; 0 for local bisection.
  int subdivisions = 0;
};

/// target_edge 0: the domain's bounding-box diagonal / 40.
/// \throw InvalidInput for a k outside 0..64, a negative or non-finite target edge, or one so
/// short that bisection would exceed its tetrahedron budget.
SimplexSampling simplex_sampling(const TetrahedralMesh& domain, int subdivisions, double target_edge);

}  // namespace volspline
