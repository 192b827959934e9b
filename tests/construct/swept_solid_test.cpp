#include "volspline/construct/swept_solid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "support/test_splines.h"
#include "volspline/construct/primitives.h"
#include "volspline/construct/swept_examples.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"

namespace volspline {
namespace {

using test_support::at;

using Eigen::Matrix3d;
using Eigen::Vector3d;
using test_support::random_parameter;
using test_support::random_spline;

Vector3d derivative_at(const BSplineCurve& c, double t) {
  const auto d = c.evaluate_derivatives({t}, 1);
  return {d[3], d[4], d[5]};
}

// A curve near the constant e: a random spline scaled by 0.15 plus e, so that b, n, t stay
// close to an orthonormal frame (det R > 0) while having their own knots, degrees and weights.
BSplineCurve near_constant(std::mt19937& rng, const Vector3d& e, int degree, int spans, bool rational) {
  const BSplineCurve r = random_spline<1>(rng, {degree}, spans, 3, rational);
  std::vector<double> points = r.points();
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = e[static_cast<long>(i % 3)] + 0.15 * points[i];
  return BSplineCurve(r.knot_vectors(), 3, std::move(points), r.weights());
}

SweptSolidFrame curves_frame(std::vector<BSplineCurve> curves) { return SweptSolidFrame::of_curves(std::move(curves)); }
SweptSolidFrame rotation(const Vector3d& axis, double degrees) { return SweptSolidFrame::rotation(axis, degrees); }

// s(u, v, w, t) against c(tau) + R(tau) g(u, v, w) evaluated from the inputs as given, with tau
// the affine image of t in the path's and each frame curve's own domain.
void expect_sweep_identity(const std::vector<BSplineVolume>& generator, const BSplineCurve& path, const std::vector<BSplineCurve>& frame,
                           std::mt19937& rng) {
  const SweptSolid solid = make_swept_solid(generator, path, curves_frame(frame));
  auto on = [](const BSplineCurve& c, double t) { return c.domain_min(0) + t * (c.domain_max(0) - c.domain_min(0)); };
  auto length = [](const BSplineCurve& c) { return c.domain_max(0) - c.domain_min(0); };
  for (std::size_t p = 0; p < generator.size(); ++p) {
    const BSplineHypervolume s = swept_patch(solid, p);
    EXPECT_EQ(s.domain_min(3), 0.0);
    EXPECT_EQ(s.domain_max(3), 1.0);
    for (int trial = 0; trial < 25; ++trial) {
      const auto uvw = random_parameter(rng, generator[p]);
      const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      const auto gd = generator[p].evaluate_derivatives(uvw, 0);
      const Vector3d g(gd[0], gd[1], gd[2]);
      Matrix3d r, dr;
      for (int k = 0; k < 3; ++k) {
        r.col(k) = at(frame[static_cast<std::size_t>(k)], on(frame[static_cast<std::size_t>(k)], t));
        dr.col(k) = derivative_at(frame[static_cast<std::size_t>(k)], on(frame[static_cast<std::size_t>(k)], t)) *
                    length(frame[static_cast<std::size_t>(k)]);
      }
      const Vector3d expected = at(path, on(path, t)) + r * g;
      const Vector3d expected_dt = derivative_at(path, on(path, t)) * length(path) + dr * g;
      const auto sd = s.evaluate_derivatives({uvw[0], uvw[1], uvw[2], t}, 1);
      const Vector3d value(sd[0], sd[1], sd[2]), dt(sd[12], sd[13], sd[14]);  // multi-index (0, 0, 0, 1) is the 5th
      const double scale = 1.0 + expected.norm() + g.norm() * r.norm();
      EXPECT_LE((value - expected).norm(), 1e-12 * scale) << "patch " << p << " t " << t;
      EXPECT_LE((dt - expected_dt).norm(), 1e-10 * (1.0 + expected_dt.norm() + g.norm() * dr.norm())) << "patch " << p << " t " << t;
    }
  }
}

TEST(SweptSolid, PolynomialSweepIsPathPlusFrameTimesGenerator) {
  std::mt19937 rng(11);
  const std::vector<BSplineVolume> generator{random_spline<3>(rng, {2, 1, 3}, 2, 3, false), random_spline<3>(rng, {1, 2, 2}, 1, 3, false)};
  const BSplineCurve path = random_spline<1>(rng, {3}, 3, 3, false);
  // Frame curves with other degrees, knots and domains than the path.
  const std::vector<BSplineCurve> frame{near_constant(rng, Vector3d::UnitX(), 2, 2, false), near_constant(rng, Vector3d::UnitY(), 1, 3, false),
                                        near_constant(rng, Vector3d::UnitZ(), 4, 1, false)};
  expect_sweep_identity(generator, path, frame, rng);
}

TEST(SweptSolid, RationalSweepIsPathPlusFrameTimesGenerator) {
  std::mt19937 rng(12);
  const std::vector<BSplineVolume> generator{random_spline<3>(rng, {2, 2, 1}, 2, 3, true), torus_quarter_patches()[1]};
  const BSplineCurve path = random_spline<1>(rng, {2}, 3, 3, true);
  const std::vector<BSplineCurve> frame{near_constant(rng, Vector3d::UnitX(), 2, 2, true), near_constant(rng, Vector3d::UnitY(), 3, 2, false),
                                        near_constant(rng, Vector3d::UnitZ(), 2, 3, true)};
  expect_sweep_identity(generator, path, frame, rng);
}

TEST(SweptSolid, RotationFrameIsExactRotationWithMonotoneAngle) {
  const Vector3d axis = Vector3d(1.0, 2.0, 2.0) / 3.0;
  for (double degrees : {360.0, 90.0, 200.0, -135.0, 725.0}) {
    SCOPED_TRACE(degrees);
    const SweptSolid solid = make_swept_solid({torus_quarter_patches()[0]}, line_path(Vector3d::Zero(), Vector3d::UnitX()),
                                              rotation(3.0 * axis, degrees));
    EXPECT_EQ(solid.frame_name, "rotate");
    EXPECT_EQ(solid.frame_fit_error, 0.0);
    // A vector normal to the axis and its turned images: the angle from atan2, unwrapped.
    const Vector3d x = axis.unitOrthogonal(), y = axis.cross(x);
    double previous = 0.0;
    for (int i = 0; i <= 400; ++i) {
      const double t = i / 400.0;
      const Matrix3d r = swept_frame_at(solid, t);
      EXPECT_LE((r.transpose() * r - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-12) << t;
      EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
      EXPECT_LE((r * axis - axis).norm(), 1e-12);
      const Vector3d turned = r * x;
      double angle = std::atan2(turned.dot(y), turned.dot(x));
      while (angle < previous - std::numbers::pi) angle += 2.0 * std::numbers::pi;
      while (angle > previous + std::numbers::pi) angle -= 2.0 * std::numbers::pi;
      if (i > 0) {
        if (degrees > 0) EXPECT_GT(angle, previous) << t;
        else EXPECT_LT(angle, previous) << t;
      }
      previous = angle;
    }
    EXPECT_NEAR(previous, degrees * std::numbers::pi / 180.0, 1e-12);
    const Matrix3d expected = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis).toRotationMatrix();
    EXPECT_LE((swept_frame_at(solid, 1.0) - expected).cwiseAbs().maxCoeff(), 1e-12);
    // At arc ends the angle is degrees * t.
    const int arcs = static_cast<int>(std::ceil(std::abs(degrees) / 90.0));
    for (int k = 0; k <= arcs; ++k) {
      const double t = static_cast<double>(k) / arcs;
      const Matrix3d rk = Eigen::AngleAxisd(degrees * t * std::numbers::pi / 180.0, axis).toRotationMatrix();
      EXPECT_LE((swept_frame_at(solid, t) - rk).cwiseAbs().maxCoeff(), 1e-12) << t;
    }
  }
}

TEST(SweptSolid, RotatingBoxTurnsOnceAboutZ) {
  const SweptSolid solid = rotating_box();
  const BSplineHypervolume s = swept_patch(solid, 0);
  std::mt19937 rng(5);
  for (int i = 0; i < 20; ++i) {
    const auto uvw = random_parameter(rng, solid.generator[0]);
    const Vector3d g = solid.generator[0].evaluate(uvw).head<3>();
    EXPECT_LE((s.evaluate({uvw[0], uvw[1], uvw[2], 1.0}).head<3>() - g).norm(), 1e-12);
    const Vector3d half = s.evaluate({uvw[0], uvw[1], uvw[2], 0.5}).head<3>();
    EXPECT_LE((half - Vector3d(-g.x(), -g.y(), g.z())).norm(), 1e-12);
    // Every point stays in the ring 1 <= rho <= sqrt(17) / 2, 0 <= z <= 1.
    const double t = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
    const Vector3d p = s.evaluate({uvw[0], uvw[1], uvw[2], t}).head<3>();
    EXPECT_NEAR(p.head<2>().norm(), g.head<2>().norm(), 1e-12);
    EXPECT_NEAR(p.z(), g.z(), 1e-12);
  }
}

TEST(SweptSolid, TranslationsMoveTheGeneratorAlongTheSegment) {
  const Vector3d d(3.0, -1.0, 2.0);
  for (const SweptSolid& solid : {translated_box(Vector3d(1.0, 2.0, 0.5), d), translated_ball(0.75, d)}) {
    EXPECT_EQ(solid.frame_name, "fixed");
    const BSplineHypervolume s = swept_patch(solid, 0);
    std::mt19937 rng(6);
    for (int i = 0; i < 10; ++i) {
      const auto uvw = random_parameter(rng, solid.generator[0]);
      const double t = i / 9.0;
      const Vector3d expected = solid.generator[0].evaluate(uvw).head<3>() + t * d;
      EXPECT_LE((s.evaluate({uvw[0], uvw[1], uvw[2], t}).head<3>() - expected).norm(), 1e-12 * (1.0 + expected.norm()));
    }
  }
}

TEST(SweptSolid, FittedFramesReportTheirErrorWithinTolerance) {
  for (auto kind : {SweptSolidFrame::Kind::Frenet, SweptSolidFrame::Kind::RotationMinimizing}) {
    SweptSolidFrame frame;
    frame.kind = kind;
    frame.tolerance = 1e-5;
    const SweptSolid solid = make_swept_solid({folded_cube()}, semicircle_path(), frame);
    EXPECT_EQ(solid.frame_name, kind == SweptSolidFrame::Kind::Frenet ? "frenet" : "rmf");
    EXPECT_GT(solid.frame_fit_error, 0.0);
    EXPECT_LE(solid.frame_fit_error, frame.tolerance);
    for (int i = 0; i <= 50; ++i) {
      const Matrix3d r = swept_frame_at(solid, i / 50.0);
      EXPECT_LE((r.transpose() * r - Matrix3d::Identity()).cwiseAbs().maxCoeff(), frame.tolerance);
      // The third column is the path's unit tangent.
      const Vector3d tangent = derivative_at(solid.path, i / 50.0).normalized();
      EXPECT_LE((r.col(2) - tangent).norm(), 10.0 * frame.tolerance);
    }
  }
}

BSplineCurve linear(const Vector3d& a, const Vector3d& b) { return line_path(a, b); }

TEST(SweptSolid, VanishingDeterminantIsRefusedWithItsParameter) {
  // b = (1, 0, 0), n = (1, s - 1/2, 0), t = (0, 0, 1): det R = s - 1/2 changes sign at s = 1/2.
  const std::vector<BSplineCurve> crossing{linear(Vector3d::UnitX(), Vector3d::UnitX()), linear(Vector3d(1, -0.5, 0), Vector3d(1, 0.5, 0)),
                                           linear(Vector3d::UnitZ(), Vector3d::UnitZ())};
  // n = (1, (s - 1/2)^2, 0): det R touches 0 at s = 1/2 without changing sign.
  const std::vector<BSplineCurve> touching{crossing[0],
                                           BSplineCurve({KnotVector::bezier(2)}, 3, {1, 0.25, 0, 1, -0.25, 0, 1, 0.25, 0}), crossing[2]};
  for (const auto& frame : {crossing, touching}) {
    try {
      make_swept_solid({folded_cube()}, line_path(Vector3d::Zero(), Vector3d::UnitX()), curves_frame(frame));
      FAIL() << "no exception";
    } catch (const InvalidInput& e) {
      EXPECT_EQ(e.where(), "frame");
      const std::string m = e.message();
      EXPECT_NE(m.find("t = 0.5"), std::string::npos) << m;
    }
  }
  // A left-handed frame is not singular: its determinant is -1 throughout.
  const std::array<BSplineCurve, 3> mirrored{linear(Vector3d::UnitY(), Vector3d::UnitY()), linear(Vector3d::UnitX(), Vector3d::UnitX()),
                                             linear(Vector3d::UnitZ(), Vector3d::UnitZ())};
  EXPECT_EQ(require_nonsingular_frame(mirrored), -1);
  EXPECT_EQ(require_nonsingular_frame(rotating_box().frame), 1);
}

TEST(SweptSolid, InputsThatAreNot3dAreRefused) {
  std::mt19937 rng(3);
  const BSplineCurve path = line_path(Vector3d::Zero(), Vector3d::UnitX());
  auto where = [&](const std::vector<BSplineVolume>& g, const BSplineCurve& c, const SweptSolidFrame& f) {
    try {
      make_swept_solid(g, c, f);
    } catch (const InvalidInput& e) {
      return e.where();
    }
    return std::string("no exception");
  };
  EXPECT_EQ(where({folded_cube(), random_spline<3>(rng, {1, 1, 1}, 1, 2, false)}, path, {}), "generator[1]");
  EXPECT_EQ(where({}, path, {}), "generator");
  EXPECT_EQ(where({folded_cube()}, random_spline<1>(rng, {2}, 2, 2, false), {}), "path");
  EXPECT_EQ(where({folded_cube()}, path, curves_frame({path, path})), "frame.curves");
  EXPECT_EQ(where({folded_cube()}, path, curves_frame({path, random_spline<1>(rng, {2}, 2, 4, false), path})), "frame.curves[1]");
  EXPECT_EQ(where({folded_cube()}, path, rotation(Vector3d::Zero(), 90.0)), "frame.rotate.axis");
  EXPECT_THROW(swept_patch(translated_box(Vector3d::Ones(), Vector3d::UnitX()), 1), InvalidInput);
  // A generator that is no volume: the box flattened into z = 0 (J = 0 everywhere); a patch
  // whose J vanishes only on a face (the cylinder's axis, a rational patch) and a tiny box are
  // volumes.
  BSplineVolume flat = box(Vector3d::Ones());
  std::vector<double> points = flat.points();
  for (std::size_t i = 2; i < points.size(); i += 3) points[i] = 0;
  const BSplineVolume flattened({flat.knot_vector(0), flat.knot_vector(1), flat.knot_vector(2)}, 3, points);
  EXPECT_EQ(where({folded_cube(), flattened}, path, {}), "generator[1]");
  try {
    make_swept_solid({flattened}, path, {});
    ADD_FAILURE() << "a flat generator was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(e.message().find("Jacobian vanishes identically"), std::string::npos) << e.message();
  }
  EXPECT_NO_THROW(make_swept_solid({cylinder(1, 2)}, path, {}));
  EXPECT_NO_THROW(make_swept_solid({box(Vector3d::Constant(1e-3))}, path, {}));
  // Weights scaled alike leave the solid as it is: a cylinder's weights times 1e-3 (w^4 J about
  // 1e-12 of the unscaled) is still a volume.
  const BSplineVolume c = cylinder(1, 2);
  std::vector<double> light = c.weights();
  for (double& w : light) w *= 1e-3;
  EXPECT_NO_THROW(make_swept_solid({BSplineVolume({c.knot_vector(0), c.knot_vector(1), c.knot_vector(2)}, 3, c.points(), light)}, path, {}));
}

TEST(SweptExamples, GeneratorsHaveTheShapesTheyClaim) {
  // Torus quarters: every point of the u = 1 face lies on the torus surface.
  const auto quarters = torus_quarter_patches(2.0, 0.5);
  ASSERT_EQ(quarters.size(), 4u);
  for (const auto& q : quarters)
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; j <= 4; ++j) {
        const Vector3d p = q.evaluate({1.0, i / 4.0, j / 4.0}).head<3>();
        EXPECT_NEAR(std::hypot(p.head<2>().norm() - 2.0, p.z()), 0.5, 1e-12);
      }
  // The folded generators' Jacobians change sign.
  auto jacobian = [](const BSplineVolume& v, std::array<double, 3> t) {
    const auto d = v.evaluate_derivatives(t, 1);
    Matrix3d m;
    for (int k = 0; k < 3; ++k) m.col(k) = Vector3d(d[3 * (k + 1)], d[3 * (k + 1) + 1], d[3 * (k + 1) + 2]);
    return m.determinant();
  };
  const BSplineVolume cube = folded_cube();
  EXPECT_GT(jacobian(cube, {0.5, 0.5, 0.0}), 0.0);
  EXPECT_LT(jacobian(cube, {0.5, 0.5, 1.0}), 0.0);
  const BSplineVolume cylinder = folded_cylinder();
  double lowest = 0.0, highest = 0.0;
  for (int i = 0; i <= 10; ++i) {
    const double j = jacobian(cylinder, {i / 10.0, 0.5, 0.3});
    lowest = std::min(lowest, j), highest = std::max(highest, j);
  }
  EXPECT_LT(lowest * highest, 0.0);
  // Semicircle: exact half circle of radius 4.
  const BSplineCurve arc = semicircle_path(4.0);
  for (int i = 0; i <= 20; ++i) {
    const Vector3d p = at(arc, i / 20.0);
    EXPECT_NEAR(p.norm(), 4.0, 1e-13);
    EXPECT_GE(p.y(), -1e-15);
  }
}

TEST(SweptExamples, PaperFiguresBuild) {
  for (const SweptSolid& solid : {torus_along_semicircle(), tumbling_cylinder(), folded_cube_along_cubic(), turning_folded_cylinder(),
                                  tumbling_folded_cube()}) {
    const auto patches = swept_patches(solid);
    ASSERT_EQ(patches.size(), solid.generator.size());
    // At t = 0 the solid is the generator placed by R(0) at c(0).
    const Matrix3d r0 = swept_frame_at(solid, 0.0);
    const Vector3d c0 = at(solid.path, 0.0);
    for (std::size_t p = 0; p < patches.size(); ++p) {
      const Vector3d g = solid.generator[p].evaluate({0.5, 0.5, 0.5}).head<3>();
      EXPECT_LE((patches[p].evaluate({0.5, 0.5, 0.5, 0.0}).head<3>() - (c0 + r0 * g)).norm(), 1e-12 * (1.0 + c0.norm() + g.norm()));
    }
  }
}

// The example files are the constructions (written with 17 digits, so equal to rounding).
TEST(SweptExamples, ExampleFilesAreTheConstructions) {
  const std::pair<const char*, SweptSolid> examples[] = {
      {"swept-torus-semicircle.json", torus_along_semicircle()},
      {"swept-tumbling-cylinder.json", tumbling_cylinder()},
      {"swept-folded-cube-cubic.json", folded_cube_along_cubic()},
      {"swept-turning-folded-cylinder.json", turning_folded_cylinder()},
      {"swept-tumbling-folded-cube.json", tumbling_folded_cube()},
      {"swept-rotating-box.json", rotating_box()},
      {"swept-translated-box.json", translated_box(Vector3d(1, 2, 0.5), Vector3d(3, -1, 2))},
      {"swept-translated-ball.json", translated_ball(1.0, Vector3d(3, 0, 0))},
  };
  std::mt19937 rng(8);
  for (const auto& [file, expected] : examples) {
    SCOPED_TRACE(file);
    const Model model = read_model((std::filesystem::path(VOLSPLINE_SOURCE_DIR) / "examples" / file).string());
    ASSERT_EQ(model.objects.size(), 1u);
    const auto& solid = std::get<SweptSolid>(model.objects[0].spline);
    EXPECT_EQ(solid.frame_name, expected.frame_name);
    EXPECT_NEAR(solid.frame_fit_error, expected.frame_fit_error, 1e-9);
    ASSERT_EQ(solid.generator.size(), expected.generator.size());
    for (std::size_t p = 0; p < solid.generator.size(); ++p) {
      const BSplineHypervolume a = swept_patch(solid, p), b = swept_patch(expected, p);
      for (int i = 0; i < 5; ++i) {
        const auto x = random_parameter(rng, b);
        EXPECT_LE((a.evaluate(x) - b.evaluate(x)).norm(), 1e-12 * (1.0 + b.evaluate(x).norm()));
      }
    }
  }
}

}  // namespace
}  // namespace volspline
