#pragma once
// Point location in a tetrahedral mesh: which tetrahedron's closed region holds a point,
// decided by exact orientation predicates after a uniform-grid search over the tetrahedra's
// bounding boxes.
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

class TetrahedronLocator {
 public:
  /// Indexes `mesh`, which must outlive the locator and stay unchanged; its tetrahedra must be
  /// positively oriented with indices in range (validate_tetrahedral_mesh). No member throws
  /// except std::bad_alloc.
  explicit TetrahedronLocator(const TetrahedralMesh& mesh);
  /// The lowest index of a tetrahedron whose closed region contains `x` (boundary included,
  /// exactly), or -1 if none does (x is outside Ω) or x is not finite.
  int locate(const Eigen::Vector3d& x) const;

 private:
  const TetrahedralMesh* mesh_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d upper_ = Eigen::Vector3d::Zero();
  double cell_size_ = 1;
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  /// Tetrahedra of grid cell c: tetrahedra_[cell_start_[c] .. cell_start_[c + 1]).
  std::vector<int> cell_start_;
  std::vector<int> tetrahedra_;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& x) const;
};

}  // namespace volspline
