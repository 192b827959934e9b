#pragma once
// Local knot optimisation of a volume-data fit (Hua–He–Qin §5.1 step 3, §5.3): for every domain
// vertex whose 1-ring error is above a threshold, its knot cloud t_0..t_n is the free variable of
// eq. 10 restricted to the data in its 1-ring, with all other knots and the control vectors fixed;
// Levenberg–Marquardt (finite-difference Jacobian, Eigen) moves it. Then all control vectors are
// fitted again. Decisions (docs/fitting.md, "Knot optimisation"):
// * The primary knot t_0 (the domain's vertex) moves only where Ω stays the same: anywhere inside
//   Ω (its tetrahedra keep their orientation and a quarter of their volume), within the plane of a
//   flat boundary, along a straight feature line where the boundary is two planes (§5.3: "primary
//   knots on feature lines move only along them"); corners and vertices of a curved boundary stay.
//   So the data fitted stay the same points, and the domain stays a valid mesh.
// * Every step keeps the clouds valid: each knot tetrahedron [p_i, q_j, r_k, s_l] of the 1-ring
//   stays positively oriented and the tetrahedron's centroid strictly inside all of them (a
//   certificate of eq. 3), exact predicates; sub-knots of boundary vertices stay outside Ω and
//   beyond the plane of every boundary face at their vertex (else the basis need not sum to 1
//   next to that face: docs/fitting.md, "The local step"); knots
//   keep a minimal distance. A step that breaks one is refused like one that raises the error.
//   The volume built after a sweep is checked in full again (validate_knot_clouds).
// * The objective sees the attributes only: the identity geometry lies in the spline space for
//   every valid knot set, so the refit restores it exactly.
// * Judged on held-out data (KnotOptimisationOptions::held_out): every 8th point is left out of
//   the objective and the refits; a vertex's move must lower the error at its ring's held-out
//   points too, and a sweep is undone unless its refit lowers the error at all of them (moves
//   judged at the data alone fit the samples and raise the error against the truth:
//   Marschner-Lobb, the tilted jump). The knots kept are fitted to all the data at the end.
// * A sweep whose refit no longer reproduces the identity geometry (to 1e-9 of the data's
//   size), or fits fewer data points, is undone; judged at the data, so is one that raises the
//   error there.
#include "volspline/io/volume_data.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline {

/// Optimises the knot clouds of `volume` (fitted to `data`, `errors` its errors, updated).
KnotOptimisationReport optimise_knots(DmsSplineVolume& volume, VolumeFitErrors& errors, const VolumeData& data,
                                      const KnotOptimisationOptions& options, const ControlVectorFitOptions& fit_options);

/// Whether the clouds of the tetrahedra around `vertex` pass the checks above (orientation of
/// every knot tetrahedron, the centroid certificate of eq. 3). Exact predicates.
bool knot_ring_is_valid(const TetrahedralMesh& domain, const KnotClouds& clouds, const std::vector<int>& ring);

}  // namespace volspline
