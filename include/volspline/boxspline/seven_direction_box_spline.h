#pragma once
// The 7-direction box spline M of Peters & Wittman 1995 (§5): directions e1, e2, e3, (1,1,1),
// (-1,1,1), (1,-1,1), (-1,-1,1); degree 4, C², one quartic on each of the 24 tetrahedra into
// which the planes x_i ∈ Z and x_i ± x_j ∈ Z cut every unit cube. Its support is the zonotope
// Σ [0, ξ] ⊂ [-2,3] x [-2,3] x [0,5].
//
// Everything here is about M itself, in its own ("uncentred") coordinates; fields built from
// shifts of M live in lattice_field.h. The piecewise Bernstein–Bézier (BB) form of M is computed
// once per process (seven_direction_box_spline()): the refinement mask gives M at the integers as
// the eigenvector of the transition operator, three refinements give M on (1/8)Z³, and on every
// tetrahedron the 35 BB coefficients interpolate M at the 35 domain points, which lie on that
// grid. Every later computation is exact polynomial algebra on these coefficients.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace volspline {

/// The seven directions, in the paper's order (§5).
inline constexpr std::array<std::array<int, 3>, 7> kBoxSplineDirections{{
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {-1, 1, 1}, {1, -1, 1}, {-1, -1, 1}}};

/// Number of BB coefficients of a trivariate quartic on a tetrahedron.
inline constexpr int kQuarticCoefficients = 35;
/// Tetrahedra per unit cube.
inline constexpr int kCubeTetrahedra = 24;

/// A point of the unit cube [0,1]³ located in the tetrahedral partition: tetrahedron index
/// 0..23 and barycentric coordinates with respect to its vertices (cube centre C, face centre F,
/// edge ends A, B; see cube_tetrahedron_vertices).
struct CubeLocation {
  int tetrahedron = 0;
  std::array<double, 4> barycentric{};
};

/// The tetrahedron of [0,1]³ containing `local` and its barycentric coordinates. Points on a
/// shared face get one of the tetrahedra; all agree there (the pieces join C²).
CubeLocation locate_in_cube(const Eigen::Vector3d& local);

/// Vertices C, F, A, B of tetrahedron `t` of [0,1]³: C the cube centre, F the centre of the
/// face the tetrahedron rests on, A and B the ends of one edge of that face.
std::array<Eigen::Vector3d, 4> cube_tetrahedron_vertices(int t);

/// Gradients of the barycentric coordinates of tetrahedron `t` (constant on it), in cube units.
std::array<Eigen::Vector3d, 4> cube_tetrahedron_barycentric_gradients(int t);

/// Multi-indices (β_C, β_F, β_A, β_B), |β| = 4, in the order BB coefficients are stored.
const std::array<std::array<int, 4>, kQuarticCoefficients>& quartic_multi_indices();

/// Value, gradient and Hessian of a quartic in BB form on tetrahedron `t` of the unit cube at
/// barycentric coordinates `b`, by de Casteljau's algorithm; derivatives in cube units.
/// `gradient` and `hessian` may be null.
double evaluate_cube_quartic(const double* bb, int t, const std::array<double, 4>& b, Eigen::Vector3d* gradient,
                             Eigen::Matrix3d* hessian);

/// Tables of M computed once per process.
struct SevenDirectionBoxSpline {
  /// The unit cube of M's support a piece belongs to: cube [r, r + 1]³; r ∈ [-2,2]²x[0,4].
  struct Piece {
    std::array<int, 3> cube;
    int tetrahedron;
    std::array<double, kQuarticCoefficients> bb;
  };
  /// The refinement mask a: M(x) = Σ_k a_k M(2x − k), a = 2⁻⁴ ∏_ξ (1 + z^ξ) (§7), on k ∈
  /// [-2,3] x [-2,3] x [0,5], x fastest (6³ entries).
  std::vector<double> mask;
  /// Every nonzero polynomial piece of M.
  std::vector<Piece> pieces;
  /// For each of the 24 tetrahedra of a unit cube [q, q+1]³: the pieces of the shifts
  /// M(· − j) nonzero there, as indices into `pieces`; the shift is j = q − piece.cube.
  std::array<std::vector<int>, kCubeTetrahedra> pieces_on_tetrahedron;

  /// M at a point of (1/8)Z³ given as 8x (exact up to rounding; 0 outside the support).
  double value_at_eighths(const std::array<int, 3>& eight_x) const;
  /// M at any point, from the BB pieces.
  double value(const Eigen::Vector3d& x) const;

  std::vector<double> eighths;  ///< M on 8·[-2,3]²x[0,5] ∩ Z³ (41³ values, x fastest)

  /// The pieces of a centred field on tetrahedron 0 of the knot cube centred at a lattice point
  /// m: the shifts M_c(· − r) nonzero there, as offsets r (the coefficient c_{m+r}), and their BB
  /// coefficients on that tetrahedron.
  /// M_c is invariant under the 48 signed permutations of the axes (they permute the seven
  /// directions up to sign, and the centred spline does not see signs), and every tetrahedron of
  /// the cube is the image of tetrahedron 0 under one of them, with the same barycentric
  /// coordinates; so these 53 pieces serve all 24 tetrahedra (lattice_field.cpp).
  std::vector<std::array<int, 3>> canonical_offsets;
  std::vector<std::array<double, kQuarticCoefficients>> canonical_bb;
};

/// The tables, built on first use (thread-safe).
const SevenDirectionBoxSpline& seven_direction_box_spline();

}  // namespace volspline
