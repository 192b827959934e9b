#pragma once
// Local knot optimisation of a volume-data fit (Hua–He–Qin §5.1 step 3, §5.3): for every domain
// vertex whose 1-ring error is above a threshold, the sub-knots t_1..t_n of its cloud are the free
// variables of eq. 10 restricted to the data in its 1-ring, with all other knots and the control
// vectors fixed; Levenberg–Marquardt (finite-difference Jacobian, Eigen) moves them. Then all
// control vectors are fitted again. Decisions (docs/fitting.md, "Knot optimisation"):
// * Primary knots (the domain's vertices) do not move, so feature vertices stay on their feature
//   lines trivially, and the domain stays valid; only sub-knots move.
// * Every step keeps the clouds valid: each knot tetrahedron [p_i, q_j, r_k, s_l] of the 1-ring
//   stays positively oriented and the tetrahedron's centroid strictly inside all of them (a
//   certificate of eq. 3), exact predicates; sub-knots of boundary vertices stay outside Ω; knots
//   keep a minimal distance. A step that breaks one is refused like one that raises the error.
//   The volume built after a sweep is checked in full again (validate_knot_clouds).
// * The objective sees the attributes only: the identity geometry lies in the spline space for
//   every valid knot set, so the refit restores it exactly.
// * A sweep whose refit raises the total error, or no longer reproduces the identity geometry
//   (to 1e-9 of the data's size), is undone.
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
