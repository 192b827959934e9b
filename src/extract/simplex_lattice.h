#pragma once
// The barycentric lattice of order k of every tetrahedron of a domain, with each tetrahedron cut
// into k³ tetrahedra by the edgewise subdivision (the Freudenthal simplices of the Kuhn simplex),
// vertices of each domain tetrahedron taken in the order of their global indices. That
// subdivision restricted to a face is the face's own edgewise subdivision, so neighbours agree on
// shared faces: a marching-tetrahedra surface over it has no cracks (Hua–He–Qin Fig. 13's
// upsampling, done alike everywhere). Lattice points shared by neighbours are named once.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

struct SimplexLattice {
  std::vector<Eigen::Vector3d> points;
  /// k³ per domain tetrahedron, in domain order, as indices into points.
  std::vector<std::array<std::int64_t, 4>> tetrahedra;
  int subdivisions = 1;
};

SimplexLattice simplex_lattice(const TetrahedralMesh& domain, int k);

}  // namespace volspline
