#pragma once
// Face sweeps inside the swept volume: a face that two generator patches share from opposite
// sides (the paper's torus of four quarter patches, a closed periodic direction) is interior to
// the generator, so its sweep is interior to the swept volume and bounds nothing. Squares that
// two patches (or the two ends of a closed direction) share are one sheet listed twice.
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

/// One square (2-face) of a 4-variate patch: the two parameters set in `fixed` (bit d: u, v, w,
/// t) at their domain maximum where the same bit of `at_max` is set, at the minimum otherwise.
struct PatchSquare {
  int patch = 0;
  int fixed = 0;
  int at_max = 0;
  friend bool operator==(const PatchSquare&, const PatchSquare&) = default;
};

/// A square that repeats an earlier one as a map (`same_as`: the first such, itself no repeat).
struct RepeatedSquare {
  PatchSquare square;
  PatchSquare same_as;
  friend bool operator==(const RepeatedSquare&, const RepeatedSquare&) = default;
};

/// The squares that repeat an earlier square as a map (equal knot vectors and homogeneous control
/// points up to 1e-12 of their scale, after one of the eight symmetries of the two free
/// parameters), in the order (patch, fixed, at_max). Two patches sharing a face share the
/// squares its edges sweep (the torus's quarters along their cross-sections), and a closed
/// direction makes a patch's squares at its two ends one (the torus's seam v = 0 ~ 1). Each such
/// square is one sheet of the superset twice over; the trimming needs each sheet once
/// (docs/envelopes.md, "Faces the generator's patches share"). \throw InvalidInput if a patch
/// does not map into R^3.
std::vector<RepeatedSquare> duplicate_squares(const std::vector<BSplineHypervolume>& patches);

}  // namespace volspline
