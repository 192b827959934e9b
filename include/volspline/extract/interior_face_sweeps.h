#pragma once
// Face sweeps inside the swept volume: a face that two generator patches share from opposite
// sides (the paper's torus of four quarter patches, a closed periodic direction) is interior to
// the generator, so its sweep is interior to the swept volume and bounds nothing.
// docs/envelopes.md, "Faces the generator's patches share".
#include <vector>

#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// One 3-face of a 4-variate patch: parameter `direction` (0, 1 or 2: u, v or w; never t) fixed
/// at its domain minimum (end 0) or maximum (end 1).
struct PatchFace {
  int patch = 0;
  int direction = 0;
  int end = 0;
  friend bool operator==(const PatchFace&, const PatchFace&) = default;
};

/// The faces whose sweeps lie inside the swept volume S = union of s_p(domain): face F of patch
/// p is listed when another face of p or of another patch is the same map (equal knot vectors and
/// homogeneous control points up to 1e-12 of their scale, after one of the eight symmetries of
/// F's two face parameters; t as it is), both patches' Jacobians det[s_u s_v s_w] keep a weak
/// sign (every Bernstein coefficient of every piece on one side, up to 1e-10 of the largest), and
/// the two patches lie on opposite sides of F. Then every point of F away from the Jacobians'
/// zeros is an interior point of the moving generator at each t, so its image is interior to S.
/// Sorted by (patch, direction, end). \throw InvalidInput if a patch does not map into R^3.
std::vector<PatchFace> interior_face_sweeps(const std::vector<BSplineHypervolume>& patches);

}  // namespace volspline
