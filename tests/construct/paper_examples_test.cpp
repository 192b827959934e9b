#include "volspline/construct/paper_examples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "support/test_splines.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::at;

using Eigen::Vector3d;


// det(V_u, V_v, V_w) from the first derivatives (derivative_multi_indices order: value, u, v, w).
double jacobian(const BSplineVolume& v, double a, double b, double c) {
  const auto d = v.evaluate_derivatives({a, b, c}, 1);
  Eigen::Matrix3d j;
  for (int k = 0; k < 3; ++k) j.col(k) = Vector3d(d[3 * (k + 1)], d[3 * (k + 1) + 1], d[3 * (k + 1) + 2]);
  return j.determinant();
}

TEST(PaperExamples, PatchIsTheDocumentedBicubic) {
  const auto f = paper_example_patch();
  EXPECT_EQ(f.degrees()[0], 3);
  EXPECT_EQ(f.degrees()[1], 3);
  std::mt19937 rng(401);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    const double u = unit(rng), v = unit(rng);
    const Vector3d x = at(f, u, v);
    EXPECT_NEAR(x.x(), 3 * u - 1.5, 1e-14);
    // y = sum of y_j B_j^3(v) with y = (-0.75, 0.75, 0.75, 0.375)
    const double y = -0.75 * std::pow(1 - v, 3) + 0.75 * 3 * v * (1 - v) + 0.375 * std::pow(v, 3);
    EXPECT_NEAR(x.y(), y, 1e-14);
  }
}

TEST(PaperExamples, SweptPatchHasTheJacobianZeroPlaneVTwoThirds) {
  const auto v = swept_patch();
  EXPECT_EQ(v.degrees()[2], 1);
  const auto f = paper_example_patch();
  std::mt19937 rng(402);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double a = unit(rng), b = unit(rng), c = unit(rng);
    // Fig. 10: V = F + w d, so J = det(F_u, F_v, d) = 6.75 (2 - 3v)(2 - v), independent of u, w.
    EXPECT_NEAR(jacobian(v, a, b, c), 6.75 * (2 - 3 * b) * (2 - b), 1e-12 * 27);
    EXPECT_NEAR(jacobian(v, a, 2.0 / 3.0, c), 0.0, 1e-12 * 27);
    EXPECT_GT(jacobian(v, a, 2.0 / 3.0 - 1e-3, c), 0.0);
    EXPECT_LT(jacobian(v, a, 2.0 / 3.0 + 1e-3, c), 0.0);
    EXPECT_LT((at(v, a, b, 0.0) - at(f, a, b)).norm(), 1e-14);
    EXPECT_LT((at(v, a, b, c) - at(f, a, b) - Vector3d(0, 0, 2 * c)).norm(), 1e-14);
  }
}

TEST(PaperExamples, TwistedLoftInterpolatesItsFourSections) {
  const auto v = twisted_loft();
  EXPECT_EQ(v.degrees()[2], 3);
  const auto sections = twisted_loft_sections();
  const auto f = paper_example_patch();
  std::mt19937 rng(403);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int m = 0; m < 4; ++m) {
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(35.0 * m / 3 * std::numbers::pi / 180, Vector3d::UnitZ()).toRotationMatrix();
    for (int i = 0; i < 100; ++i) {
      const double a = unit(rng), b = unit(rng);
      const Vector3d expected = rotation * at(f, a, b) + Vector3d(0, 0, 2.0 * m / 3);
      EXPECT_LT((at(sections[static_cast<std::size_t>(m)], a, b) - expected).norm(), 1e-14);
      EXPECT_LT((at(v, a, b, m / 3.0) - expected).norm(), 1e-12);
    }
  }
  // The last section is the patch turned by 35 degrees: points keep their distance to the axis.
  const Vector3d p = at(v, 0.0, 0.0, 1.0), q = at(f, 0.0, 0.0);
  EXPECT_NEAR(std::atan2(p.y(), p.x()) - std::atan2(q.y(), q.x()), 35.0 * std::numbers::pi / 180, 1e-12);
}

TEST(PaperExamples, CurvedLoftInterpolatesRigidCopiesAlongItsPath) {
  const auto v = curved_loft();
  const auto sections = curved_loft_sections();
  const auto path = curved_loft_path();
  const auto f = paper_example_patch();
  std::mt19937 rng(404);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int m = 0; m < 5; ++m) {
    const auto& s = sections[static_cast<std::size_t>(m)];
    for (int i = 0; i < 100; ++i) {
      const double a = unit(rng), b = unit(rng), a2 = unit(rng), b2 = unit(rng);
      EXPECT_LT((at(v, a, b, m / 4.0) - at(s, a, b)).norm(), 1e-12);
      EXPECT_NEAR((at(s, a, b) - at(s, a2, b2)).norm(), (at(f, a, b) - at(f, a2, b2)).norm(), 1e-12);
    }
    // A rigid motion taking c(0) = 0 to c(t_m): distances from the path point are kept.
    const auto c = path.evaluate({m / 4.0});
    for (int i = 0; i < 20; ++i) {
      const double a = unit(rng), b = unit(rng);
      EXPECT_NEAR((at(s, a, b) - Vector3d(c[0], c[1], c[2])).norm(), at(f, a, b).norm(), 1e-12);
    }
  }
  EXPECT_LT((at(sections[0], 0.3, 0.6) - at(f, 0.3, 0.6)).norm(), 1e-14);
}

TEST(PaperExamples, BoundariesAreClosed) {
  for (const auto& v : {swept_patch(), twisted_loft(), curved_loft()}) {
    const auto mesh = tessellate_faces(v, {.resolution = 8});
    EXPECT_TRUE(edge_statistics(mesh).closed());
  }
}

}  // namespace
}  // namespace volspline
