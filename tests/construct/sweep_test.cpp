#include "volspline/construct/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "support/test_splines.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"

namespace volspline {
namespace {

using test_support::at;

using Eigen::Matrix3d;
using Eigen::Vector3d;
using test_support::random_spline;


// The same curve with its knots mapped affinely onto [a, b], so that curves made independently
// share one parameter domain.
BSplineCurve on_domain(const BSplineCurve& c, double a = 0.0, double b = 1.0) {
  const KnotVector& kv = c.knot_vector(0);
  const double lo = kv.domain_min(), hi = kv.domain_max();
  std::vector<double> knots;
  for (double t : kv.knots()) knots.push_back(a + (t - lo) / (hi - lo) * (b - a));
  return BSplineCurve({KnotVector(kv.degree(), knots)}, c.dimension(), c.points(), c.weights());
}

// A constant curve e of the given degree on [0, 1].
BSplineCurve constant_curve(const Vector3d& e, int degree) {
  std::vector<double> p;
  for (int i = 0; i <= degree; ++i) p.insert(p.end(), {e.x(), e.y(), e.z()});
  return BSplineCurve({KnotVector::bezier(degree)}, 3, p);
}

// Interpolates f at the Greville abscissae of a clamped uniform knot vector: a path that is
// close to an analytic curve, with parameter t meaning the analytic parameter.
template <class F>
BSplineCurve interpolate(F f, int degree, int spans, double a, double b) {
  const KnotVector kv = KnotVector::uniform_clamped(degree, spans, a, b);
  const int n = kv.num_basis();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n), rhs(n, 3);
  std::vector<double> basis(static_cast<std::size_t>(degree + 1));
  const std::vector<double> sites = kv.greville_abscissae();
  for (int j = 0; j < n; ++j) {
    const double g = sites[static_cast<std::size_t>(j)];
    const int span = kv.find_span(g);
    kv.basis(span, g, basis.data());
    for (int r = 0; r <= degree; ++r) m(j, span - degree + r) = basis[static_cast<std::size_t>(r)];
    rhs.row(j) = f(g).transpose();
  }
  const Eigen::MatrixXd x = m.partialPivLu().solve(rhs);
  std::vector<double> p;
  for (int i = 0; i < n; ++i) p.insert(p.end(), {x(i, 0), x(i, 1), x(i, 2)});
  return BSplineCurve({kv}, 3, p);
}

// Helix (a cos t, a sin t, b t): speed c = sqrt(a^2 + b^2), torsion b / c^2.
constexpr double kHelixA = 1.0, kHelixB = 0.3;
Vector3d helix(double t) { return {kHelixA * std::cos(t), kHelixA * std::sin(t), kHelixB * t}; }
Matrix3d helix_frenet(double t) {
  const double c = std::hypot(kHelixA, kHelixB);
  Matrix3d r;
  r.col(2) = Vector3d(-kHelixA * std::sin(t), kHelixA * std::cos(t), kHelixB) / c;  // tangent
  r.col(0) = Vector3d(-std::cos(t), -std::sin(t), 0.0);                             // normal
  r.col(1) = Vector3d(kHelixB * std::sin(t), -kHelixB * std::cos(t), kHelixA) / c;  // binormal
  return r;
}
BSplineCurve helix_path() { return interpolate(helix, 5, 48, 0.0, 2.0 * std::numbers::pi); }

Matrix3d frame_at(const std::array<BSplineCurve, 3>& f, double t) {
  Matrix3d r;
  for (int a = 0; a < 3; ++a) r.col(a) = at(f[static_cast<std::size_t>(a)], t);
  return r;
}

// ---- sweep_with_frame_curves ---------------------------------------------------------------

TEST(SweepWithFrameCurves, ConstantFramesGiveTheTranslationByThePath) {
  std::mt19937 rng(301);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (bool rational : {false, true}) {
    const auto profile = random_spline<2>(rng, {2, 3}, 2, 3, rational);
    const auto path = on_domain(random_spline<1>(rng, {3}, 3, 3, rational, true, 2, rational));
    const std::array<BSplineCurve, 3> frame{constant_curve(Vector3d::UnitX(), 2), constant_curve(Vector3d::UnitY(), 1),
                                            constant_curve(Vector3d::UnitZ(), 3)};
    const auto v = sweep_with_frame_curves(profile, path, frame);
    for (int i = 0; i < 200; ++i) {
      const double u = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
      const double s = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
      const double w = unit(rng);
      const Vector3d expected = at(profile, u, s) + at(path, w);
      EXPECT_LT((at(v, u, s, w) - expected).norm(), 1e-12 * (1.0 + expected.norm()));
    }
  }
}

TEST(SweepWithFrameCurves, ExactRationalRotationKeepsDistancesFromTheAxis) {
  // R(w) = rotation by theta(w) about z, its columns exact rational quarter circles sharing one
  // weight function; the path climbs the axis. Every point keeps its distance from the axis
  // and turns by exactly the angle of the first column.
  std::mt19937 rng(302);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Vector3d o = Vector3d::Zero(), z = Vector3d::UnitZ();
  const std::array<BSplineCurve, 3> frame{conic_arc(Vector3d::UnitX(), 90, 1, o, z), conic_arc(Vector3d::UnitY(), 90, 1, o, z),
                                          constant_curve(z, 1)};
  const BSplineCurve path({KnotVector::bezier(1)}, 3, {0, 0, 0, 0, 0, 3});
  for (bool rational : {false, true}) {
    const auto profile = random_spline<2>(rng, {3, 2}, 2, 3, rational);
    const auto v = sweep_with_frame_curves(profile, path, frame);
    EXPECT_TRUE(v.is_rational());
    for (int i = 0; i < 200; ++i) {
      const double u = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
      const double s = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
      const double w = unit(rng);
      const Vector3d f = at(profile, u, s), x = at(v, u, s, w), r0 = at(frame[0], w);
      const double scale = 1.0 + f.norm();
      EXPECT_NEAR(std::hypot(x.x(), x.y()), std::hypot(f.x(), f.y()), 1e-12 * scale);
      EXPECT_NEAR(x.z(), f.z() + 3.0 * w, 1e-12 * scale);
      const double theta = std::atan2(r0.y(), r0.x());
      const Vector3d turned = Eigen::AngleAxisd(theta, z) * f;
      EXPECT_LT((x - turned - Vector3d(0, 0, 3.0 * w)).norm(), 1e-12 * scale);
    }
  }
}

// V(u, v, w) = c(w) + R(w) F(u, v) against c, R and F evaluated on their own.
void expect_sweep_formula(const BSplineSurface& profile, const BSplineCurve& path, const std::array<BSplineCurve, 3>& frame,
                          std::mt19937& rng) {
  const auto v = sweep_with_frame_curves(profile, path, frame);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const double u = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
    const double s = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
    const double w = path.domain_min(0) + unit(rng) * (path.domain_max(0) - path.domain_min(0));
    const Vector3d f = at(profile, u, s), c = at(path, w);
    const Matrix3d r = frame_at(frame, w);
    const Vector3d expected = c + r * f;
    const double scale = 1.0 + c.norm() + r.norm() * f.norm();
    ASSERT_LT((at(v, u, s, w) - expected).norm(), 1e-12 * scale) << "at " << u << ", " << s << ", " << w;
  }
}

TEST(SweepWithFrameCurves, EqualsPathPlusFrameTimesProfileAtRandomPoints) {
  std::mt19937 rng(303);
  for (int trial = 0; trial < 6; ++trial) {
    const bool rational = trial % 2 == 1;
    const auto profile = random_spline<2>(rng, {2, 3}, 3, 3, rational, trial < 4);
    // Different degrees, knot vectors and weights for the path and each frame curve; interior
    // knots of multiplicity up to 2 and, in rational trials, points at infinity on the path.
    const auto path = on_domain(random_spline<1>(rng, {2 + trial % 2}, 3, 3, rational, true, 2, rational));
    const std::array<BSplineCurve, 3> frame{on_domain(random_spline<1>(rng, {1}, 2, 3, rational)),
                                            on_domain(random_spline<1>(rng, {3}, 2, 3, rational, true, 3)),
                                            on_domain(random_spline<1>(rng, {2}, 4, 3, false))};
    expect_sweep_formula(profile, path, frame, rng);
  }
}

TEST(SweepWithFrameCurves, SharedWeightsKeepThePathDegree) {
  std::mt19937 rng(304);
  const auto path = on_domain(random_spline<1>(rng, {3}, 4, 3, true));
  // Frame curves on the path's knots with the path's weights: one denominator class.
  std::array<BSplineCurve, 3> frame{path, path, path};
  for (auto& f : frame) {
    std::vector<double> p = f.points();
    for (auto& x : p) x = std::uniform_real_distribution<double>(-1, 1)(rng);
    f = BSplineCurve({path.knot_vector(0)}, 3, p, path.weights());
  }
  const auto profile = random_spline<2>(rng, {2, 2}, 2, 3, false);
  const auto v = sweep_with_frame_curves(profile, path, frame);
  EXPECT_EQ(v.degrees()[2], 3);
  EXPECT_EQ(v.knot_vector(2), path.knot_vector(0));
  expect_sweep_formula(profile, path, frame, rng);
}

TEST(SweepWithFrameCurves, RejectsBadInput) {
  const auto profile = BSplineSurface({KnotVector::bezier(1), KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  const BSplineCurve path({KnotVector::bezier(1)}, 3, {0, 0, 0, 0, 0, 1});
  std::array<BSplineCurve, 3> frame{constant_curve(Vector3d::UnitX(), 1), constant_curve(Vector3d::UnitY(), 1),
                                    constant_curve(Vector3d::UnitZ(), 1)};
  EXPECT_NO_THROW(sweep_with_frame_curves(profile, path, frame));
  frame[1] = on_domain(frame[1], 0.0, 2.0);
  EXPECT_THROW(sweep_with_frame_curves(profile, path, frame), InvalidInput);
  const BSplineCurve flat({KnotVector::bezier(1)}, 2, {0, 0, 1, 1});
  EXPECT_THROW(sweep(profile, flat, SweepFrame::Fixed), InvalidInput);
}

// ---- frames ----------------------------------------------------------------------------------

TEST(Frames, FrenetFrameOfAHelixIsTheAnalyticOne) {
  const auto path = helix_path();
  std::mt19937 rng(305);
  std::uniform_real_distribution<double> t(0.0, 2.0 * std::numbers::pi);
  for (int i = 0; i < 100; ++i) {
    const double s = t(rng);
    EXPECT_LT((frenet_frame(path, s) - helix_frenet(s)).cwiseAbs().maxCoeff(), 1e-6) << s;
  }
  const auto fit = fit_sweep_frame(path, SweepFrame::Frenet);
  EXPECT_LE(fit.orthonormality_error, kSweepFrameTolerance);
  for (int i = 0; i < 100; ++i) {
    const double s = t(rng);
    EXPECT_LT((frame_at(fit.curves, s) - helix_frenet(s)).cwiseAbs().maxCoeff(), 1e-5) << s;
  }
}

TEST(Frames, RotationMinimizingFrameIsOrthonormalAndDoesNotSpin) {
  const auto path = helix_path();
  const auto fit = fit_sweep_frame(path, SweepFrame::RotationMinimizing);
  EXPECT_LE(fit.orthonormality_error, kSweepFrameTolerance);
  EXPECT_LE(fit.frame_error, 1e-6);
  std::mt19937 rng(306);
  std::uniform_real_distribution<double> t(0.0, 2.0 * std::numbers::pi);
  double spin_rmf = 0.0, spin_frenet = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double s = t(rng);
    const Matrix3d r = frame_at(fit.curves, s);
    EXPECT_LT((r.transpose() * r - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 2 * kSweepFrameTolerance);
    // The angular velocity's component along the tangent is r' . s (per unit parameter);
    // divided by the speed it is per unit length. For the Frenet frame it is the torsion.
    const auto d = fit.curves[0].evaluate_derivatives({s}, 1);
    const Vector3d r_prime(d[3], d[4], d[5]);
    const auto pd = path.evaluate_derivatives({s}, 1);
    const double speed = Vector3d(pd[3], pd[4], pd[5]).norm();
    spin_rmf = std::max(spin_rmf, std::abs(r_prime.dot(r.col(1))) / speed);
    const Matrix3d f = helix_frenet(s), f2 = helix_frenet(s + 1e-6);
    spin_frenet = std::max(spin_frenet, std::abs(((f2.col(0) - f.col(0)) / 1e-6).dot(f.col(1))) / speed);
    // Against the analytic RMF of the helix: the Frenet normal turned back by the torsion,
    // r = cos(tau s) N - sin(tau s) B with tau s = b t / c (arc length s = c t).
    const double phi = kHelixB * s / std::hypot(kHelixA, kHelixB);
    const Vector3d expected = std::cos(phi) * f.col(0) - std::sin(phi) * f.col(1);
    EXPECT_LT((r.col(0) - expected).norm(), 1e-5) << s;
  }
  EXPECT_LT(spin_rmf, 1e-5);
  EXPECT_NEAR(spin_frenet, kHelixB / (kHelixA * kHelixA + kHelixB * kHelixB), 1e-4);
}

// The RMF ODE r' = -(r . t') t integrated by classical Runge-Kutta with a small step: an
// independent reference for the double reflection march on the same path.
std::vector<Vector3d> rmf_by_runge_kutta(const BSplineCurve& path, Vector3d r, const std::vector<double>& params) {
  auto rhs = [&](double t, const Vector3d& x) {
    const auto d = path.evaluate_derivatives({t}, 2);
    const Vector3d c1(d[3], d[4], d[5]), c2(d[6], d[7], d[8]);
    const Vector3d tan = c1.normalized(), tan_prime = (c2 - c2.dot(tan) * tan) / c1.norm();
    return Vector3d(-x.dot(tan_prime) * tan);
  };
  std::vector<Vector3d> out{r};
  for (std::size_t i = 1; i < params.size(); ++i) {
    const int steps = 400;
    const double h = (params[i] - params[i - 1]) / steps;
    for (int k = 0; k < steps; ++k) {
      const double t = params[i - 1] + k * h;
      const Vector3d k1 = rhs(t, r), k2 = rhs(t + h / 2, r + h / 2 * k1), k3 = rhs(t + h / 2, r + h / 2 * k2),
                     k4 = rhs(t + h, r + h * k3);
      r += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    out.push_back(r);
  }
  return out;
}

TEST(Frames, DoubleReflectionAgreesWithTheIntegratedRotationMinimizingFrame) {
  const BSplineCurve path({KnotVector(3, {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1})}, 3,
                          {0, 0, 0, 1, 0, 0.5, 1.5, 1, 1, 1, 2, 0, 0, 1.5, -1, -0.5, 2.5, 0.5});
  std::vector<double> params;
  for (int i = 0; i <= 50; ++i) params.push_back(i / 50.0);
  const auto frames = rotation_minimizing_frames(path, params);
  const auto reference = rmf_by_runge_kutta(path, frames.front().col(0), params);
  for (std::size_t i = 0; i < params.size(); ++i) {
    EXPECT_LT((frames[i].col(0) - reference[i]).norm(), 1e-10) << params[i];
    EXPECT_LT((frames[i].transpose() * frames[i] - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(Frames, RotationMinimizingFrameOfAPlanarPathIsThePlanarFrame) {
  // A planar cubic with an inflection, tilted out of the xy plane: the RMF's binormal column
  // stays the plane's normal and the normal column stays in the plane.
  const Matrix3d tilt = (Eigen::AngleAxisd(0.7, Vector3d(1, 2, 0.5).normalized())).toRotationMatrix();
  const BSplineCurve flat({KnotVector(3, {0, 0, 0, 0, 0.4, 1, 1, 1, 1})}, 3, {0, 0, 0, 1, 1.5, 0, 2.5, -1, 0, 3.5, 1, 0, 5, 0.5, 0});
  const auto path = transform_affine(flat, tilt, Vector3d(1, -2, 3));
  const Vector3d normal = tilt.col(2);
  const auto fit = fit_sweep_frame(path, SweepFrame::RotationMinimizing);
  EXPECT_LE(fit.orthonormality_error, kSweepFrameTolerance);
  std::vector<double> params;
  for (int i = 0; i <= 100; ++i) params.push_back(i / 100.0);
  const auto exact = rotation_minimizing_frames(path, params);
  const double sign = exact.front().col(1).dot(normal) > 0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < params.size(); ++i) {
    EXPECT_LT((exact[i].col(1) - sign * normal).norm(), 1e-12);
    EXPECT_LT(std::abs(exact[i].col(0).dot(normal)), 1e-12);
    EXPECT_LT((frame_at(fit.curves, params[i]).col(1) - sign * normal).norm(), 1e-6);
  }
}

TEST(Frames, BadPathsAreRejected) {
  const BSplineCurve point({KnotVector::bezier(2)}, 3, {1, 2, 3, 1, 2, 3, 1, 2, 3});
  const auto profile = BSplineSurface({KnotVector::bezier(1), KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  for (auto f : {SweepFrame::Fixed, SweepFrame::Frenet, SweepFrame::RotationMinimizing})
    EXPECT_THROW(sweep(profile, point, f), InvalidInput);
  // An S-curve: the curvature vanishes at t = 1/2 (and at t = 0.499..., off any sample).
  const BSplineCurve s_curve({KnotVector::bezier(3)}, 3, {0, 0, 0, 1, 1, 0, 2, -1, 0, 3, 0, 0});
  EXPECT_THROW(sweep(profile, s_curve, SweepFrame::Frenet), InvalidInput);
  EXPECT_THROW(frenet_frame(s_curve, 0.5), InvalidInput);
  const BSplineCurve lopsided({KnotVector::bezier(3)}, 3, {0, 0, 0, 1, 1, 0, 2.3, -1.2, 0, 3, 0, 0});
  EXPECT_THROW(fit_sweep_frame(lopsided, SweepFrame::Frenet), InvalidInput);
  EXPECT_NO_THROW(fit_sweep_frame(lopsided, SweepFrame::RotationMinimizing));
  const BSplineCurve line({KnotVector::bezier(1)}, 3, {0, 0, 0, 1, 1, 1});
  EXPECT_THROW(sweep(profile, line, SweepFrame::Frenet), InvalidInput);
  EXPECT_NO_THROW(sweep(profile, line, SweepFrame::RotationMinimizing));
  // A polyline corner: the tangent jumps, so no moving frame; translation is fine.
  const BSplineCurve corner({KnotVector(1, {0, 0, 0.5, 1, 1})}, 3, {0, 0, 0, 1, 0, 0, 1, 1, 0});
  EXPECT_THROW(sweep(profile, corner, SweepFrame::RotationMinimizing), InvalidInput);
  EXPECT_NO_THROW(sweep(profile, corner, SweepFrame::Fixed));
  // A cusp: the tangent vanishes.
  const BSplineCurve cusp({KnotVector::bezier(3)}, 3, {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 0});
  EXPECT_THROW(sweep(profile, cusp, SweepFrame::RotationMinimizing), InvalidInput);
}

// ---- sweep -------------------------------------------------------------------------------------

TEST(Sweep, StartsAtTheProfileAndMovesItRigidly) {
  std::mt19937 rng(307);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto profile = random_spline<2>(rng, {3, 2}, 2, 3, true);
  const auto path = helix_path();
  for (auto kind : {SweepFrame::Fixed, SweepFrame::Frenet, SweepFrame::RotationMinimizing}) {
    const auto v = sweep(profile, path, kind);
    for (int i = 0; i < 100; ++i) {
      const double u1 = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
      const double v1 = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
      const double u2 = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
      const double v2 = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
      const double w = unit(rng) * 2.0 * std::numbers::pi;
      const Vector3d f1 = at(profile, u1, v1), f2 = at(profile, u2, v2);
      EXPECT_LT((at(v, u1, v1, 0.0) - f1).norm(), 1e-12 * (1 + f1.norm()));
      // Every section is a rigid copy: distances within the frame's orthonormality error.
      const double d = (at(v, u1, v1, w) - at(v, u2, v2, w)).norm();
      EXPECT_NEAR(d, (f1 - f2).norm(), (kind == SweepFrame::Fixed ? 1e-12 : 4 * kSweepFrameTolerance) * (1 + (f1 - f2).norm()));
    }
  }
}

TEST(Sweep, FixedFrameAlongARationalConicIsLassersTranslationVolume) {
  std::mt19937 rng(308);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto profile = random_spline<2>(rng, {2, 3}, 2, 3, true);
  for (double s2 : {1.0, 0.6, 1.0 / std::cos(std::numbers::pi / 3), 4.0}) {
    const Vector3d start(2, 0.5, 1), axis_point(0.5, 0, 0), axis(0.2, 0.1, 1);
    const auto k = conic_arc(start, 120, s2, axis_point, axis);
    const auto v = translation_along_conic(profile, start, 120, s2, axis_point, axis);
    EXPECT_EQ(v.degrees()[2], 2);
    for (int i = 0; i < 100; ++i) {
      const double u = profile.domain_min(0) + unit(rng) * (profile.domain_max(0) - profile.domain_min(0));
      const double s = profile.domain_min(1) + unit(rng) * (profile.domain_max(1) - profile.domain_min(1));
      const double w = unit(rng);
      // Theorem 1: V(u, v, 0) = F and every w line is the directrix moved along.
      const Vector3d f = at(profile, u, s), expected = f + at(k, w) - start;
      EXPECT_LT((at(v, u, s, w) - expected).norm(), 1e-12 * (1 + expected.norm()));
      EXPECT_LT((at(v, u, s, 0.0) - f).norm(), 1e-12 * (1 + f.norm()));
    }
  }
  // A half circle: its middle control point is at infinity, which the homogeneous form carries.
  const auto half = translation_along_conic(profile, Vector3d(1, 0, 0), 180, 1, Vector3d::Zero(), Vector3d::UnitZ());
  const Vector3d f = at(profile, profile.domain_min(0), profile.domain_min(1));
  EXPECT_LT((at(half, profile.domain_min(0), profile.domain_min(1), 0.5) - (f + Vector3d(-1, 1, 0))).norm(), 1e-12 * (1 + f.norm()));
}

// ---- conic_arc -------------------------------------------------------------------------------

// The conic through the samples (a null vector of [x^2, xy, y^2, x, y, 1]) in the arc's plane;
// returns the discriminant B^2 - 4AC of the normalised coefficients and the largest residual.
struct ConicFit {
  double discriminant;
  double residual;
  double off_plane;
};
ConicFit fit_conic(const BSplineCurve& arc, const Vector3d& origin, const Vector3d& e1, const Vector3d& e2) {
  const int n = 60;
  Eigen::MatrixXd rows(n, 6);
  double off_plane = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vector3d p = at(arc, (i + 0.5) / n) - origin;
    off_plane = std::max(off_plane, std::abs(p.dot(e1.cross(e2))));
    const double x = p.dot(e1), y = p.dot(e2);
    rows.row(i) << x * x, x * y, y * y, x, y, 1.0;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(rows, Eigen::ComputeFullV);
  const Eigen::VectorXd c = svd.matrixV().col(5);
  const double scale = c.head<3>().norm();
  return {(c(1) * c(1) - 4 * c(0) * c(2)) / (scale * scale), (rows * c).cwiseAbs().maxCoeff() / c.norm(), off_plane};
}

TEST(ConicArc, LassersEquation9GivesEveryConic) {
  const Vector3d axis_point(1, 2, -1), axis = Vector3d(1, 1, 0.5).normalized();
  const Vector3d start = axis_point + 0.3 * axis + 2.0 * Vector3d(1, -1, 0).normalized();
  const Vector3d origin = axis_point + 0.3 * axis, e1 = (start - origin).normalized(), e2 = axis.cross(e1);
  for (double angle : {120.0, -90.0, 60.0, 180.0}) {
    const double s_star = std::abs(angle) == 180 ? std::numeric_limits<double>::infinity() : 1.0 / std::cos(angle * std::numbers::pi / 360);
    for (double factor : {0.3, 1.0 / s_star, 0.8, 1.0, 1.5, 3.0}) {
      const double s2 = std::isinf(s_star) ? 1.0 + factor : factor * s_star;
      if (!std::isfinite(s2)) continue;
      const auto arc = conic_arc(start, angle, s2, axis_point, axis);
      EXPECT_LT((at(arc, 0.0) - start).norm(), 1e-14);
      const Vector3d end = origin + Eigen::AngleAxisd(angle * std::numbers::pi / 180, axis) * (start - origin);
      EXPECT_LT((at(arc, 1.0) - end).norm(), 1e-14);
      const auto conic = fit_conic(arc, origin, e1, e2);
      EXPECT_LT(conic.off_plane, 1e-12);
      EXPECT_LT(conic.residual, 1e-12) << angle << " " << s2;
      if (std::abs(s2 - 1.0) < 1e-15) {  // a circle about the axis
        for (int i = 0; i <= 50; ++i) EXPECT_NEAR((at(arc, i / 50.0) - origin).norm(), 2.0, 1e-12);
        EXPECT_NEAR(conic.discriminant, -4.0 / 2.0, 1e-9);  // A = C, B = 0: B^2 - 4AC = -4A^2, A^2 = 1/2
      } else if (s2 < s_star * (1 - 1e-12)) {
        EXPECT_LT(conic.discriminant, -1e-3) << "an ellipse for s2 < s*: " << angle << " " << s2;
      } else if (s2 > s_star * (1 + 1e-12)) {
        EXPECT_GT(conic.discriminant, 1e-3) << "a hyperbola for s2 > s*: " << angle << " " << s2;
      } else {
        EXPECT_NEAR(conic.discriminant, 0.0, 1e-9) << "a parabola for s2 = s*: " << angle;
        for (double w : arc.weights()) EXPECT_NEAR(w, 1.0, 1e-15);  // polynomial
      }
    }
  }
}

TEST(ConicArc, RejectsBadInput) {
  const Vector3d p(1, 0, 0), o = Vector3d::Zero(), z = Vector3d::UnitZ();
  EXPECT_NO_THROW(conic_arc(p, 90, 1, o, z));
  EXPECT_THROW(conic_arc(p, 90, 1, o, Vector3d::Zero()), InvalidInput);
  EXPECT_THROW(conic_arc(Vector3d(0, 0, 3), 90, 1, o, z), InvalidInput);
  EXPECT_THROW(conic_arc(p, 0, 1, o, z), InvalidInput);
  EXPECT_THROW(conic_arc(p, 181, 1, o, z), InvalidInput);
  EXPECT_THROW(conic_arc(p, 90, 0, o, z), InvalidInput);
  EXPECT_THROW(conic_arc(p, 90, -1, o, z), InvalidInput);
  EXPECT_THROW(conic_arc(p, std::nan(""), 1, o, z), InvalidInput);
}

}  // namespace
}  // namespace volspline
