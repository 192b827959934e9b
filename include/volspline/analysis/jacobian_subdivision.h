#pragma once
// The adaptive subdivision of Joy–Duchaineau §6: boxes of the parameter domain ("cells"), each
// inside one Bézier piece of the volume, with a certified bound of the Jacobian determinant on it,
// split in two through their centre along the direction the paper's gradient rule picks.
//
// Cells live on a dyadic lattice: along each direction, coordinate c * 2^kMaxLevel + m *
// 2^(kMaxLevel - level) is the m-th subdivision point of piece c at that level. Equal lattice
// coordinates mean bitwise-equal points, which is what makes the tetrahedral meshes built on the
// cells (jacobian_zero_surface in extract/solid_boundary.h) conforming.
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/analysis/jacobian_bezier.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// How the Jacobian determinant is bounded on a cell.
enum class JacobianBoundMethod {
  /// Convex hull of the Bernstein coefficients of J (jacobian_bezier.h), with a proven error
  /// bound: certified, and quadratically convergent under subdivision.
  Bezier,
  /// The cones of Joy–Duchaineau §5 (cone_bounds.h); polynomial volumes only.
  Cone,
};

struct JacobianCell {
  /// Index into JacobianSubdivision::pieces().
  int piece = 0;
  /// Lattice coordinates of the low corner, and binary splits made in each direction.
  std::array<std::int64_t, 3> origin{0, 0, 0};
  std::array<int, 3> level{0, 0, 0};
  /// Bezier method: J (or w^4 J for a rational volume) on the cell. Its error_bound covers
  /// extraction and every split since.
  JacobianBernstein jacobian;
  /// Cone method: the cell's points (x, y, z) in Bernstein form (three components).
  BernsteinTensor<3> geometry;
  /// A certified interval containing sign-equivalent J (w^4 J for rational volumes) on the cell.
  double lower = 0, upper = 0;

  double width() const { return upper - lower; }
  bool excludes_zero() const { return lower > 0 || upper < 0; }
};

class JacobianSubdivision {
 public:
  /// Levels of binary splitting available per direction inside one Bézier piece.
  static constexpr int kMaxLevel = 40;

  /// \throw InvalidInput unless the volume maps into R^3; for the cone method, if it is
  /// rational (the paper's cones bound polynomial derivatives).
  JacobianSubdivision(const BSplineVolume& volume, JacobianBoundMethod method);

  JacobianBoundMethod method() const { return method_; }
  const BSplineVolume& volume() const { return volume_; }
  const std::vector<BSplineVolume>& pieces() const { return pieces_; }
  /// Pieces per direction.
  const std::array<int, 3>& piece_counts() const { return counts_; }

  /// One cell per Bézier piece, bounded (computed once, at construction).
  const std::vector<JacobianCell>& roots() const { return roots_; }
  /// The two halves of `cell` along `direction`, bounded. \throw InvalidInput if the cell is at
  /// kMaxLevel in that direction.
  std::pair<JacobianCell, JacobianCell> split(const JacobianCell& cell, int direction) const;
  /// Joy–Duchaineau §6: the direction d maximising width(bound of J_d) * (cell size in d),
  /// among those not yet at kMaxLevel; -1 if none is left. This makes the zero set flat
  /// relative to the cell; it never splits a direction in which J is linear, so when cells are
  /// split until the bound of J itself is narrow, `by_magnitude` uses max |bound of J_d| *
  /// (cell size in d) instead (the direction in which J varies most).
  int split_direction(const JacobianCell& cell, bool by_magnitude = false) const;

  /// Bezier method: a bound of |J - A| on the cell for an affine function A (fitted to the
  /// coefficients), error bound included. Marching tetrahedra interpolate J linearly; they
  /// reproduce affine functions, so their error on the cell is at most twice this.
  double nonlinearity(const JacobianCell& cell) const;

  /// The largest |J| bound over the whole domain (the scale of relative tolerances); 0 for a
  /// volume with J = 0 everywhere.
  double scale() const { return scale_; }

  /// The global parameters of a lattice point (components may be any lattice coordinates of
  /// the domain, piece boundaries included).
  Eigen::Vector3d parameter(const std::array<std::int64_t, 3>& lattice) const;
  /// Lattice size of a cell along `direction`.
  static std::int64_t extent(const JacobianCell& cell, int direction) {
    return std::int64_t{1} << (kMaxLevel - cell.level[static_cast<std::size_t>(direction)]);
  }
  /// Lattice coordinate of the top of the domain along `direction`.
  std::int64_t lattice_end(int direction) const {
    return static_cast<std::int64_t>(counts_[static_cast<std::size_t>(direction)]) << kMaxLevel;
  }

  /// Bounds of J itself on the cell (for a rational volume from w^4 J and the weights; an
  /// infinite end where the weights' bound reaches 0).
  std::pair<double, double> jacobian_bounds(const JacobianCell& cell) const;

  /// The certified sign of J at corner c (bit 0: u max, bit 1: v max, bit 2: w max) of a cell
  /// under the Bezier method: +1, -1, or 0 when |J| there is within the error bound.
  int corner_sign(const JacobianCell& cell, int corner) const;
  /// The global parameters of that corner.
  Eigen::Vector3d corner_parameter(const JacobianCell& cell, int corner) const;
  /// J at a corner from the cell's coefficients (Bezier method; w^4 J for rational volumes).
  double corner_value(const JacobianCell& cell, int corner) const;

 private:
  void bound(JacobianCell& cell) const;
  std::vector<JacobianCell> make_roots() const;

  BSplineVolume volume_;
  JacobianBoundMethod method_;
  std::vector<BSplineVolume> pieces_;
  std::array<int, 3> counts_{1, 1, 1};
  std::array<std::vector<double>, 3> breakpoints_;
  double input_error_ = 0;
  double scale_ = 0;
  std::vector<JacobianCell> roots_;
};

}  // namespace volspline
