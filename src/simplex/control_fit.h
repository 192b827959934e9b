#pragma once
// Least-squares control vectors of a DMS spline volume (attribute assignment, local refinement):
// the columns minimise Σ_s |Σ_r N_r(x_s) c_r − t_s|² + λ |c − prior|², λ = 1e-8 of the normal
// matrix's mean diagonal (a Tikhonov term that keeps a coefficient seen by almost no sample
// defined), solved by Eigen's SimplicialLDLT on the normal equations.
#include <vector>

#include <Eigen/Core>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// The points (a_0 p + a_1 q + a_2 r + a_3 s) / m, Σ a = m, of every domain tetrahedron, pulled
/// 0.1 % toward its centroid so that none lies on a face.
std::vector<Eigen::Vector3d> lattice_samples(const TetrahedralMesh& domain, int m);

/// Sets `columns` of volume.control_vectors() (targets and prior have one column each, in that
/// order; targets one row per sample, prior one row per control vector).
/// \throw Error if the system cannot be factored.
void fit_control_columns(DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& samples, const Eigen::MatrixXd& targets,
                         const std::vector<int>& columns, const Eigen::MatrixXd& prior);

}  // namespace volspline
