// Face sweeps inside the swept volume: shared faces of generator patches found from the control
// nets and the Jacobians' signs, and the envelope unchanged without them.
#include "volspline/extract/interior_face_sweeps.h"

#include <array>
#include <functional>

#include <gtest/gtest.h>

#include "volspline/construct/swept_examples.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/extract/swept_envelope.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

// s(u, v, w, t) = g(u, v, w) + t d for an affine g given by its values at the cube's corners
// (degree 1 in every direction).
BSplineHypervolume translated_affine_box(const std::function<Eigen::Vector3d(double, double, double)>& g, const Eigen::Vector3d& d) {
  std::vector<double> points;
  for (int l = 0; l < 2; ++l)
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const Eigen::Vector3d x = g(i, j, k) + l * d;
          points.insert(points.end(), {x.x(), x.y(), x.z()});
        }
  return BSplineHypervolume({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3,
                            points);
}

const Eigen::Vector3d kMotion(0.7, 0.4, -0.3);

BSplineHypervolume unit_box() {
  return translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(u, v, w); }, kMotion);
}

TEST(InteriorFaceSweeps, BoxesSideBySideShareTheirMiddleFace) {
  // [1, 2] x [0, 1]^2 beside [0, 1]^3: the face x = 1 is u = 1 of the first and u = 0 of the second.
  const BSplineHypervolume right = translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + u, v, w); }, kMotion);
  const std::vector<PatchFace> faces = interior_face_sweeps({unit_box(), right});
  const std::vector<PatchFace> expected{{0, 0, 1}, {1, 0, 0}};
  EXPECT_EQ(faces, expected);
}

TEST(InteriorFaceSweeps, SharedFaceFoundUnderEverySymmetryOfItsParameters) {
  // The second box reaches x = 1 at u = 1 (reversed u) with its face parameters (v, w) swapped
  // and reversed: the same face, and still on the other side (its Jacobian is negative or
  // positive as the symmetry says, which the test covers both ways).
  const BSplineHypervolume reversed =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(2 - u, 1 - w, v); }, kMotion);
  const std::vector<PatchFace> faces = interior_face_sweeps({unit_box(), reversed});
  const std::vector<PatchFace> expected{{0, 0, 1}, {1, 0, 1}};
  EXPECT_EQ(faces, expected);
  const BSplineHypervolume swapped =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + w, u, v); }, kMotion);
  const std::vector<PatchFace> expected_swapped{{0, 0, 1}, {1, 2, 0}};
  EXPECT_EQ(interior_face_sweeps({unit_box(), swapped}), expected_swapped);
}

TEST(InteriorFaceSweeps, FacesSharedFromTheSameSideBoundTheGenerator) {
  // [1/2, 1] x [0, 1]^2 lies on the same side of x = 1 as the unit box: that face bounds their
  // union; and a copy of the unit box shares all six faces from the same side.
  const BSplineHypervolume inner =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 - 0.5 * u, v, w); }, kMotion);
  EXPECT_TRUE(interior_face_sweeps({unit_box(), inner}).empty());
  EXPECT_TRUE(interior_face_sweeps({unit_box(), unit_box()}).empty());
  // Moving differently (another d), the faces are different maps even where they meet at t = 0.
  const BSplineHypervolume other_motion =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + u, v, w); }, 2 * kMotion);
  EXPECT_TRUE(interior_face_sweeps({unit_box(), other_motion}).empty());
}

TEST(InteriorFaceSweeps, TorusQuartersShareTheirCrossSectionsAndSeams) {
  // Fig. 4's generator: four rational quarter patches, each closed around the tube (its seam
  // v = 0 / v = 1 lies inside the tube) and meeting its neighbours in the cross-section disks.
  // The torus surface (u = 1) and the tube's centre circle (u = 0) are never listed.
  const std::vector<BSplineHypervolume> patches = swept_patches(torus_along_semicircle());
  const std::vector<PatchFace> faces = interior_face_sweeps(patches);
  EXPECT_EQ(faces.size(), 16u);
  for (const PatchFace& f : faces) EXPECT_NE(f.direction, 0) << "patch " << f.patch << " end " << f.end;
}

// Repeated squares: the edges of a shared face sweep the same squares in both patches; a box
// alone repeats none.
TEST(DuplicateSquares, BoxesSideBySideRepeatTheSquaresOfTheirSharedFace) {
  EXPECT_TRUE(duplicate_squares({unit_box()}).empty());
  const BSplineHypervolume right = translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + u, v, w); }, kMotion);
  const std::vector<RepeatedSquare> repeated = duplicate_squares({unit_box(), right});
  // The face x = 1 (u = 1 of the first, u = 0 of the second): its four edges swept (u and v or
  // w fixed, t free) and the face itself at t = 0 and t = 1 (u and t fixed).
  ASSERT_EQ(repeated.size(), 6u);
  for (const RepeatedSquare& r : repeated) {
    EXPECT_EQ(r.square.patch, 1);
    EXPECT_EQ(r.same_as.patch, 0);
    EXPECT_EQ(r.square.fixed, r.same_as.fixed);
    EXPECT_TRUE(r.square.fixed & 1) << r.square.fixed;
    EXPECT_EQ(r.square.at_max & 1, 0);
    EXPECT_EQ(r.same_as.at_max & 1, 1);
  }
  // Found under the symmetries of the free parameters too (u reversed, (v, w) swapped and
  // reversed); a box that moves differently shares only the face at t = 0.
  const BSplineHypervolume reversed =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(2 - u, 1 - w, v); }, kMotion);
  EXPECT_EQ(duplicate_squares({unit_box(), reversed}).size(), 6u);
  const BSplineHypervolume other_motion =
      translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + u, v, w); }, 2 * kMotion);
  const std::vector<RepeatedSquare> at_start = duplicate_squares({unit_box(), other_motion});
  const std::vector<RepeatedSquare> expected{{{1, 1 | 8, 0}, {0, 1 | 8, 1}}};
  EXPECT_EQ(at_start, expected);
}

TEST(DuplicateSquares, TorusQuartersRepeatTheirCrossSectionsAndSeamSquares) {
  // Each quarter's seam v = 0 ~ 1 makes its squares at v = 0 and v = 1 one; neighbouring quarters
  // share the squares of their cross-section disks. Every repeat is an equal map, checked
  // independently at sample points of the two squares' domains.
  const std::vector<BSplineHypervolume> patches = swept_patches(torus_along_semicircle());
  const std::vector<RepeatedSquare> repeated = duplicate_squares(patches);
  ASSERT_FALSE(repeated.empty());
  int seams = 0, across = 0;
  for (const RepeatedSquare& r : repeated) {
    (r.square.patch == r.same_as.patch ? seams : across) += 1;
    EXPECT_EQ(r.square.fixed, r.same_as.fixed);
    // The image of one is the image of the other: every sampled point of the repeat lies on
    // the original (found among its samples under one of the symmetries, here compared as sets).
    const auto image = [&](const PatchSquare& q) {
      const BSplineHypervolume& s = patches[static_cast<std::size_t>(q.patch)];
      std::vector<Eigen::Vector3d> points;
      std::array<int, 2> free{};
      int k = 0;
      for (int d = 0; d < 4; ++d)
        if (!((q.fixed >> d) & 1)) free[static_cast<std::size_t>(k++)] = d;
      for (int i = 0; i <= 4; ++i)
        for (int j = 0; j <= 4; ++j) {
          std::array<double, 4> p{};
          for (int d = 0; d < 4; ++d) p[static_cast<std::size_t>(d)] = (q.at_max >> d) & 1 ? s.domain_max(d) : s.domain_min(d);
          p[static_cast<std::size_t>(free[0])] = s.domain_min(free[0]) + (s.domain_max(free[0]) - s.domain_min(free[0])) * i / 4.0;
          p[static_cast<std::size_t>(free[1])] = s.domain_min(free[1]) + (s.domain_max(free[1]) - s.domain_min(free[1])) * j / 4.0;
          Eigen::Vector3d x;
          s.evaluate(p, x.data());
          points.push_back(x);
        }
      return points;
    };
    const std::vector<Eigen::Vector3d> a = image(r.square), b = image(r.same_as);
    for (const Eigen::Vector3d& x : a) {
      double nearest = 1e300;
      for (const Eigen::Vector3d& y : b) nearest = std::min(nearest, (x - y).norm());
      EXPECT_LT(nearest, 1e-9);
    }
  }
  EXPECT_GT(seams, 0);
  EXPECT_GT(across, 0);
}

TEST(InteriorFaceSweeps, TrimmedEnvelopeUnchangedWithoutThem) {
  // Two boxes side by side translated: the hull of the 2 x 1 x 1 box and its translate, whether
  // the trimming is given the full superset or computes it without the shared face.
  const BSplineHypervolume right = translated_affine_box([](double u, double v, double w) { return Eigen::Vector3d(1 + u, v, w); }, kMotion);
  const std::vector<BSplineHypervolume> patches{unit_box(), right};
  SweptEnvelopeOptions options;
  options.tolerance = 4e-3;
  const SweptEnvelope full = swept_envelope_superset(patches, options);
  options.interior_faces = false;
  const SweptEnvelope reduced = swept_envelope_superset(patches, options);
  EXPECT_EQ(reduced.stats.interior_face_sweeps, 2);
  EXPECT_LT(reduced.mesh.num_triangles(), full.mesh.num_triangles());
  const double exact = 2 + std::abs(kMotion.x()) * 1 + std::abs(kMotion.y()) * 2 + std::abs(kMotion.z()) * 2;
  for (const SweptEnvelope* superset : {&full, &reduced}) {
    const SweptEnvelope trimmed = trim_swept_envelope(patches, *superset, options);
    EXPECT_TRUE(edge_statistics(trimmed.mesh).closed_and_oriented());
    EXPECT_TRUE(trimmed.stats.trimming.self_intersection_free);
    EXPECT_NEAR(enclosed_volume(trimmed.mesh), exact, 1e-3 * exact);
  }
}

}  // namespace
}  // namespace volspline
