#pragma once
// Least-squares control vectors of a DMS spline volume (attribute assignment, local refinement,
// fitting volume data, Hua–He–Qin eq. 10): the columns minimise
//   Σ_s |Σ_r N_r(x_s) c_r − t_s|² + λ |c − prior|²,
// λ = 1e-8 of the normal matrix's mean diagonal (a Tikhonov term that keeps a coefficient seen
// by almost no sample defined), solved by Eigen's SimplicialLDLT on the normal equations.
// Optionally the prior is then replaced by the solution and the problem solved again
// (iterated Tikhonov regularisation, with the same factorisation): each step shrinks the
// regularisation's bias by λ / (λ + σ) along each eigenvector of AᵀA (σ its eigenvalue), so
// the least-squares solution is approached where the data determine it, while a direction no
// sample sees keeps the first prior. The residual is recomputed from A in every step, so this is
// also iterative refinement of the normal equations' rounding.
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// The points (a_0 p + a_1 q + a_2 r + a_3 s) / m, Σ a = m, of every domain tetrahedron, pulled
/// 0.1 % toward its centroid so that none lies on a face.
std::vector<Eigen::Vector3d> lattice_samples(const TetrahedralMesh& domain, int m);

/// The collocation matrix A(s, r) = N_r(x_s) (a sample outside Ω has an empty row).
Eigen::SparseMatrix<double> basis_matrix(const DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& samples);

struct ControlFitOptions {
  /// λ as a fraction of the mean diagonal of AᵀA.
  double regularisation = 1e-8;
  /// Iterated Tikhonov steps after the first solve, at most (0: the plain regularised
  /// solution); they stop early once a step changes no entry by more than 1e-15 of the largest.
  int refinement_steps = 0;
  /// Up to this many control vectors: SimplicialLDLT; above: conjugate gradients with an
  /// incomplete Cholesky preconditioner, to this relative residual. The default keeps the
  /// factorisation always (fit_control_columns); fitting volume data sets 8,000.
  Eigen::Index direct_limit = std::numeric_limits<Eigen::Index>::max();
  double iterative_tolerance = 1e-12;
  int iterative_max_iterations = 5000;
};

/// The control columns minimising |A c − targets|² + λ |c − prior|² (then refined), one column
/// per column of targets and prior. \throw Error if the system cannot be factored.
Eigen::MatrixXd solve_control_columns(const Eigen::SparseMatrix<double>& a, const Eigen::MatrixXd& targets, const Eigen::MatrixXd& prior,
                                      const ControlFitOptions& options = {});

/// Sets `columns` of volume.control_vectors() (targets and prior have one column each, in that
/// order; targets one row per sample, prior one row per control vector).
/// \throw Error if the system cannot be factored.
void fit_control_columns(DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& samples, const Eigen::MatrixXd& targets,
                         const std::vector<int>& columns, const Eigen::MatrixXd& prior);

}  // namespace volspline
