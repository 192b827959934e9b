// Lattices: construction around points, the model-file form and its error messages.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include <Eigen/LU>

#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/deform/lattice.h"

namespace volspline {
namespace {

std::string lattice_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Lattice, ControlPointsOfABezierLatticeAreEquation11) {
  const TriangleMesh cube = test_support::unit_cube();
  const Lattice lattice = undeformed_lattice(cube, {3, 2, 1}, {1, 1, 1}, 0.0);
  EXPECT_EQ(lattice.origin, Eigen::Vector3d::Zero());
  EXPECT_EQ(lattice.axes, Eigen::Matrix3d::Identity());
  for (int k = 0; k <= 1; ++k)
    for (int j = 0; j <= 2; ++j)
      for (int i = 0; i <= 3; ++i) {
        const auto index = static_cast<std::size_t>(lattice.volume.linear_index({i, j, k}));
        EXPECT_DOUBLE_EQ(lattice.volume.points()[3 * index], i / 3.0);
        EXPECT_DOUBLE_EQ(lattice.volume.points()[3 * index + 1], j / 2.0);
        EXPECT_DOUBLE_EQ(lattice.volume.points()[3 * index + 2], k / 1.0);
      }
}

TEST(Lattice, MarginAndDirections) {
  const TriangleMesh cube = test_support::unit_cube();
  const Lattice lattice = undeformed_lattice(cube, {1, 1, 1}, {1, 1, 1}, 0.25);
  EXPECT_TRUE(lattice.origin.isApprox(Eigen::Vector3d::Constant(-0.25)));
  EXPECT_TRUE(lattice.axes.isApprox(1.5 * Eigen::Matrix3d::Identity()));
  // A flat set of points gets a solid box from the margin, and none without it.
  const std::vector<Eigen::Vector3d> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_GT(undeformed_lattice(flat, {1, 1, 1}).axes.determinant(), 0);
  EXPECT_NE(lattice_error_of([&] { undeformed_lattice(flat, {1, 1, 1}, {1, 1, 1}, 0.0); }).find("no extent along W"), std::string::npos);
  EXPECT_THROW(undeformed_lattice(std::vector<Eigen::Vector3d>{}, {1, 1, 1}), InvalidInput);
  EXPECT_THROW(undeformed_lattice(cube, {0, 1, 1}), InvalidInput);
  EXPECT_THROW(undeformed_lattice(cube, {1, 1, 1}, {1, 0, 1}), InvalidInput);
  EXPECT_THROW(undeformed_lattice(cube, {1, 1, 1}, {1, 1, 1}, -1.0), InvalidInput);
  Eigen::Matrix3d coplanar = Eigen::Matrix3d::Identity();
  coplanar.col(2) = Eigen::Vector3d(1, 1, 0);
  EXPECT_THROW(undeformed_lattice(cube, {1, 1, 1}, {1, 1, 1}, 0.1, coplanar), InvalidInput);
}

TEST(Lattice, ModelFileRoundTripIsBitExact) {
  Eigen::Matrix3d directions;
  directions << 1, 0.3, 0, 0.1, 1, 0.2, 0, -0.4, 1;
  const Lattice lattice = undeformed_lattice(test_support::icosphere(1), {2, 3, 1}, {2, 1, 3}, 0.1, directions);
  const Model model = parse_model(model_to_json(lattice_to_model(lattice)), "lattice.json");
  EXPECT_FALSE(model.objects[0].bezier);  // segmented
  const Lattice back = lattice_from_model(model, "lattice.json");
  EXPECT_EQ(back.origin, lattice.origin);
  EXPECT_EQ(back.axes, lattice.axes);
  EXPECT_EQ(back.volume.points(), lattice.volume.points());
  for (int d = 0; d < 3; ++d) EXPECT_EQ(back.volume.knot_vector(d), lattice.volume.knot_vector(d));
  const Lattice bezier = undeformed_lattice(test_support::unit_cube(), {2, 2, 2});
  EXPECT_TRUE(lattice_to_model(bezier).objects[0].bezier);
}

TEST(Lattice, ModelErrorsNameFileAndPath) {
  const Model good = lattice_to_model(undeformed_lattice(test_support::unit_cube(), {1, 1, 1}));
  auto with = [&](const std::function<void(Model&)>& change) {
    Model m = good;
    change(m);
    return lattice_error_of([&] { lattice_from_model(m, "lattice.json"); });
  };
  EXPECT_EQ(with([](Model& m) { m.objects[0].metadata["lattice"]["axes"][2] = {1.0, 1.0, 0.0};
                                m.objects[0].metadata["lattice"]["axes"][0] = {1.0, 0.0, 0.0};
                                m.objects[0].metadata["lattice"]["axes"][1] = {0.0, 1.0, 0.0}; }),
            "lattice.json: objects[0].metadata.lattice.axes: expected three non-coplanar vectors");
  EXPECT_EQ(with([](Model& m) { m.objects[0].metadata["lattice"]["axes"] = {1, 2}; }),
            "lattice.json: objects[0].metadata.lattice.axes: expected three non-coplanar vectors");
  EXPECT_EQ(with([](Model& m) { m.objects[0].metadata["lattice"]["origin"][1] = "x"; }),
            "lattice.json: objects[0].metadata.lattice.origin[1]: expected a number");
  EXPECT_EQ(with([](Model& m) { m.objects[0].metadata = nullptr; }),
            "lattice.json: objects[0].metadata: expected a \"lattice\" entry with \"origin\" and \"axes\"");
  EXPECT_EQ(with([](Model& m) { m.objects[0].metadata["lattice"].erase("origin"); }),
            "lattice.json: objects[0].metadata.lattice: expected an \"origin\": [x, y, z]");
  EXPECT_EQ(with([](Model& m) { m.objects.push_back(m.objects[0]); }),
            "lattice.json: objects: a lattice file holds exactly one object (the lattice volume), got 2");
  EXPECT_EQ(with([](Model& m) {
              const auto& v = std::get<BSplineVolume>(m.objects[0].spline);
              m.objects[0].spline = BSplineCurve({v.knot_vector(0)}, 3, {0, 0, 0, 1, 1, 1});
            }),
            "lattice.json: objects[0].type: expected a bspline_volume or bezier_volume");
  EXPECT_NE(with([](Model& m) {
              const auto& v = std::get<BSplineVolume>(m.objects[0].spline);
              m.objects[0].spline = BSplineVolume({KnotVector::bezier(1, 0, 2), v.knot_vector(1), v.knot_vector(2)}, 3, v.points());
            }).find("lattice.json: objects[0]: a lattice volume's domain must be [0, 1]"),
            std::string::npos);
}

}  // namespace
}  // namespace volspline
