#pragma once
// Local refinement of a DMS spline volume (Hua–He–Qin §4, §5.4): one domain tetrahedron split
// 1 → 4 at a new primary knot, more degrees of freedom where they are needed.
//
// Decision (docs/simplex-splines.md, "Local refinement"): the paper re-solves the fit instead of
// the polar-form knot insertion of Seidel–Vermeulen (1994), and so do we: the knot clouds of the
// old vertices are kept, the new vertex gets a generated cloud (all clouds are regenerated only if
// keeping them fails the checks of §3.2), and every column of the control vectors — geometry and
// attributes — is fitted by least squares to the old spline sampled on the lattice of order
// n + 2 of every new tetrahedron, with the old control vectors as the regularisation's prior.
// Polynomials of degree ≤ n (the identity geometry among them) are reproduced exactly up to that
// regularisation; anything else is approximated, and the report says how well.
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct LocalRefinementReport {
  /// The new domain point (the last one).
  int new_vertex = -1;
  /// Whether the old vertices' knot clouds were kept (false: all regenerated).
  bool clouds_kept = true;
  /// Where the refined spline was compared with the old: samples, and the largest and root
  /// mean square distance between the two control-vector-valued splines there.
  int samples = 0;
  double max_error = 0;
  double rms_error = 0;
};

/// The volume with tetrahedron `tetrahedron` split at `point` into four (each corner in turn
/// replaced by the point, so all stay positively oriented).
/// \throw InvalidInput if the tetrahedron does not exist or the point is not strictly inside it
/// (exact predicates), or as the volume's constructor.
DmsSplineVolume refine_tetrahedron(const DmsSplineVolume& volume, int tetrahedron, const Eigen::Vector3d& point,
                                   LocalRefinementReport* report = nullptr);

}  // namespace volspline
