#pragma once
// Knot clouds of a trivariate DMS spline (Hua–He–Qin §3.2): one cloud [t_0 = t, t_1..t_n] per
// vertex t of the domain Ω, subject to the validity conditions around eq. 3–4. Generation and
// its decisions, and what cannot be made valid: docs/tetrahedral-domains.md.
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

/// One knot cloud [t_0 = t, t_1..t_n] per vertex of Ω (paper §3.2): knots[v*(degree+1) + l].
struct KnotClouds {
  int degree = 0;
  std::vector<Eigen::Vector3d> knots;
  const Eigen::Vector3d* cloud(int vertex) const { return knots.data() + static_cast<std::size_t>(vertex) * (degree + 1); }
  /// The number of clouds (vertices) the knots make.
  std::size_t num_clouds() const { return knots.size() / static_cast<std::size_t>(degree + 1); }
};

struct KnotCloudOptions {
  double spread = 0.15;  /* sub-knot distance as a fraction of the vertex's shortest incident edge */
  /// tan of the angle by which a boundary vertex's sub-knots lean from its outward pseudo-normal
  /// (around it, in the cloud's fixed directions), halved with the spread; 0: on the ray. At
  /// wedges of Ω sharper than about 65° a lean lets the basis sum to less than 1 near the edge
  /// (docs/fitting.md, "Sharp features"); a domain cut at an interface uses 0.
  double lean = 0.5;
};

/// The degrees the clouds support: 0..kMaxKnotCloudDegree.
inline constexpr int kMaxKnotCloudDegree = 5;

/// The index quadruples (i, j, k, l), i+j+k+l <= degree, of the knot tetrahedra
/// [p_i, q_j, r_k, s_l] of a domain tetrahedron (p, q, r, s) that §3.2 requires non-degenerate:
/// C(degree + 4, 4) of them, lexicographically ordered. \throw InvalidInput for a negative degree.
std::vector<std::array<int, 4>> knot_tetrahedron_indices(int degree);

/// Generates valid clouds: t_0 is the vertex; interior vertices get sub-knots near it in fixed,
/// deterministic, well-spread directions; vertices on ∂Ω get their sub-knots outside Ω (along
/// the outward pseudo-normal, so that every boundary face's knots lie outside Ω as §3.2
/// requires). Every tetrahedron is checked against eq. 3 and the non-degeneracy condition, and
/// the spread is shrunk locally where a check fails; when no spread works, InvalidInput names
/// the tetrahedron (docs/tetrahedral-domains.md, "What cannot be made valid"). Deterministic.
/// The result passes validate_knot_clouds. Sub-knot l of a vertex lies at distance
/// spread * e * (n + l) / (2n) from it (e: its shortest incident edge), halved for the vertex
/// each time a check of an incident tetrahedron fails, at most kMaxKnotCloudHalvings times.
/// \throw InvalidInput for a degree outside 0..kMaxKnotCloudDegree, a spread outside (0, 0.5)
/// (at 0.5 the clouds of an edge's two ends could meet), a domain that fails
/// validate_tetrahedral_mesh, or, naming `tetrahedra[i]`, a tetrahedron whose checks still fail
/// when none of its corners can be halved again (or whose boundary face has a vertex at the
/// limit with a sub-knot still inside Ω).
KnotClouds generate_knot_clouds(const TetrahedralMesh& domain, int degree, const KnotCloudOptions& options = {});

/// How often generate_knot_clouds halves a vertex's spread before it gives up (2^-30: about
/// 1e-9 of the spread).
inline constexpr int kMaxKnotCloudHalvings = 30;

/// The checks of §3.2 for every tetrahedron I = (p, q, r, s): all [p_i, q_j, r_k, s_l],
/// i+j+k+l <= n, non-degenerate with the orientation of I (exact predicate); the interior of
/// their intersection non-empty (eq. 3) — certified by a point strictly inside all of them (I's
/// centroid, else a relaxation-method candidate, each tested exactly) and otherwise decided
/// exactly by a small linear programme (CGAL's QP solver over Gmpzf, maximising the common
/// slack); the sub-knots of boundary faces outside Ω.
/// \throw InvalidInput naming `tetrahedra[i]`, the condition and the knots.
/// "Outside Ω" is strict: a sub-knot on ∂Ω is inside. Also checked first: the degree is in
/// 0..kMaxKnotCloudDegree, there are degree + 1 finite knots per point of the domain (else
/// InvalidInput naming `knots`), each cloud's t_0 is its vertex exactly (else naming
/// `knots[i]`), and the domain passes validate_tetrahedral_mesh (its errors as they are).
void validate_knot_clouds(const TetrahedralMesh& domain, const KnotClouds& clouds);

}  // namespace volspline
