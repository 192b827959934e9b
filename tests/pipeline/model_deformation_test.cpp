// A model deformed object by object: each curve and surface is the lattice's map of the
// original, point for point (deform_point, an independent evaluation), and volumes are refused
// with their place in the file.
#include <gtest/gtest.h>

#include <random>

#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"
#include "volspline/pipeline/model_deformation.h"

namespace volspline {
namespace {

// A degree (2, 2, 2) lattice around the unit cube with its top control points pushed sideways.
Lattice bent_lattice() {
  Lattice lattice = undeformed_lattice(std::vector<Eigen::Vector3d>{Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(2, 2, 2)}, {2, 2, 2});
  std::vector<double> points = lattice.volume.points();
  for (std::size_t i = 0; i < points.size() / 3; ++i)
    if (i >= 18) points[3 * i] += 0.5;  // the layer k = 2
  lattice.volume = BSplineVolume(lattice.volume.knot_vectors(), 3, points, lattice.volume.weights());
  return lattice;
}

TEST(ModelDeformation, EveryCurveAndSurfaceIsTheMapOfTheOriginal) {
  const Lattice lattice = bent_lattice();
  Model model;
  const BSplineCurve curve(std::array<KnotVector, 1>{KnotVector::bezier(2)}, 3, {0, 0, 0, 0.5, 1, 0.2, 1, 0.3, 1});
  const BSplineSurface surface(std::array<KnotVector, 2>{KnotVector::bezier(1), KnotVector::bezier(1)}, 3,
                               {0, 0, 0.5, 1, 0, 0.5, 0, 1, 0.5, 1, 1, 0.9});
  model.objects.push_back({"path", true, curve, {{"kept", true}}});
  model.objects.push_back({"sheet", true, surface, nullptr});
  const Model deformed = deform_model(lattice, model, "m.json");
  ASSERT_EQ(deformed.objects.size(), 2u);
  EXPECT_EQ(deformed.objects[0].name, "path");
  EXPECT_EQ(deformed.objects[0].metadata, model.objects[0].metadata);
  EXPECT_FALSE(deformed.objects[0].bezier);
  const auto& c = std::get<BSplineCurve>(deformed.objects[0].spline);
  const auto& s = std::get<BSplineSurface>(deformed.objects[1].spline);
  for (const double t : {0.0, 0.2, 0.55, 1.0}) {
    const Eigen::Vector3d expected = deform_point(lattice, curve.evaluate({t}));
    EXPECT_LT((c.evaluate({t}) - expected).norm(), 1e-12) << t;
    for (const double u : {0.0, 0.4, 1.0}) {
      const Eigen::Vector3d on_surface = deform_point(lattice, surface.evaluate({t, u}));
      EXPECT_LT((s.evaluate({t, u}) - on_surface).norm(), 1e-12) << t << ", " << u;
    }
  }
}

TEST(ModelDeformation, RefusesVolumesWithTheirPlace) {
  Model model;
  const BSplineCurve curve(std::array<KnotVector, 1>{KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 1, 1});
  model.objects.push_back({"", false, curve, nullptr});
  model.objects.push_back({"", false, box(Eigen::Vector3d(1, 1, 1)), nullptr});
  try {
    deform_model(bent_lattice(), model, "m.json");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "m.json: objects[1].type");
  }
}

}  // namespace
}  // namespace volspline
