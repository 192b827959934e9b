#pragma once
// The collocation matrix of eq. 10, A(i, r) = N_r(x_i), assembled in parallel (oneTBB) for
// fitting volume data: the points are cut into fixed blocks, each block's entries are collected
// in point order by whichever thread takes it, and the blocks are joined in their order, so the
// matrix is the same bit for bit whatever the number of threads (the fit stays deterministic).
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// A(i, r) = N_r(x_i), rows of points outside Ω empty; row-major, so that a point's entries are
/// contiguous (the sums and products of the fit read them by point).
Eigen::SparseMatrix<double, Eigen::RowMajor> parallel_basis_matrix(const DmsSplineVolume& volume, const std::vector<Eigen::Vector3d>& points);

}  // namespace volspline
