// Exact primitives: every boundary face lies on its analytic surface, interior points satisfy
// the analytic inequalities, and the tessellated boundary encloses the analytic volume.
#include "volspline/construct/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "volspline/core/error.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using Residual = std::function<double(const Eigen::Vector3d&)>;
constexpr double kPi = std::numbers::pi;

// Largest |residual| over an n x n grid on face `face` (core/conventions.h numbering).
double max_on_face(const BSplineVolume& v, int face, const Residual& residual, int n = 41) {
  const int d = face / 2;
  const double fixed = face % 2 == 0 ? v.domain_min(d) : v.domain_max(d);
  const int d1 = (d + 1) % 3, d2 = (d + 2) % 3;
  double worst = 0.0;
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      std::array<double, 3> t{};
      t[static_cast<std::size_t>(d)] = fixed;
      t[static_cast<std::size_t>(d1)] = v.domain_min(d1) + (v.domain_max(d1) - v.domain_min(d1)) * a / n;
      t[static_cast<std::size_t>(d2)] = v.domain_min(d2) + (v.domain_max(d2) - v.domain_min(d2)) * b / n;
      worst = std::max(worst, std::abs(residual(v.evaluate(t))));
    }
  return worst;
}

// Every face on its surface (relative to `scale`), then `inside` at random interior points.
void expect_faces_and_interior(const BSplineVolume& v, const std::array<Residual, 6>& faces,
                               const std::function<bool(const Eigen::Vector3d&)>& inside, double scale) {
  for (int f = 0; f < 6; ++f) EXPECT_LE(max_on_face(v, f, faces[static_cast<std::size_t>(f)]), 1e-12 * scale) << "face " << f;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const auto p = v.evaluate({unit(rng), unit(rng), unit(rng)});
    ASSERT_TRUE(inside(p)) << p.transpose();
  }
}

double rho(const Eigen::Vector3d& p, const Eigen::Vector3d& c) { return std::hypot(p.x() - c.x(), p.y() - c.y()); }

// Enclosed volume of the tessellated faces at two resolutions: close to `exact`, and closer at
// the finer one (the flat triangles converge quadratically).
void expect_volume_converges(const BSplineVolume& v, double exact) {
  const double coarse = enclosed_volume(tessellate_faces(v, {.resolution = 12}));
  const double fine = enclosed_volume(tessellate_faces(v, {.resolution = 48}));
  EXPECT_NEAR(fine, exact, 1e-2 * exact);
  EXPECT_LT(std::abs(fine - exact), 0.25 * std::abs(coarse - exact) + 1e-12 * exact);
}

const Eigen::Vector3d kCenter(0.3, -0.2, 1.1);

TEST(Primitives, BoxFacesArePlanes) {
  const Eigen::Vector3d size(1.0, 2.0, 3.0);
  const auto v = box(size, kCenter);
  std::array<Residual, 6> faces;
  for (int f = 0; f < 6; ++f)
    faces[static_cast<std::size_t>(f)] = [f, size](const Eigen::Vector3d& p) {
      const int d = f / 2;
      return p[d] - (kCenter[d] + (f % 2 == 0 ? -0.5 : 0.5) * size[d]);
    };
  expect_faces_and_interior(v, faces, [&](const Eigen::Vector3d& p) { return ((p - kCenter).cwiseAbs() - size / 2).maxCoeff() <= 1e-12; }, 3.0);
  expect_volume_converges(v, 6.0);
}

TEST(Primitives, BallIsASphereWithDegenerateFaces) {
  const double R = 1.5;
  const auto v = ball(R, kCenter);
  EXPECT_EQ(v.degrees(), (std::array<int, 3>{1, 2, 2}));
  const Residual center = [](const Eigen::Vector3d& p) { return (p - kCenter).norm(); };
  const Residual axis = [](const Eigen::Vector3d& p) { return rho(p, kCenter); };
  const Residual seam = [](const Eigen::Vector3d& p) { return p.y() - kCenter.y(); };
  expect_faces_and_interior(v, {center, [&](const Eigen::Vector3d& p) { return (p - kCenter).norm() - R; }, axis, axis, seam, seam},
                            [&](const Eigen::Vector3d& p) { return (p - kCenter).norm() <= R * (1 + 1e-12); }, R);
  expect_volume_converges(v, 4.0 / 3.0 * kPi * R * R * R);
}

TEST(Primitives, SolidAndHollowCylinders) {
  for (double inner : {0.0, 0.5}) {
    const double R = 2.0, H = 3.0;
    const auto v = cylinder(R, H, inner, kCenter);
    EXPECT_EQ(v.degrees(), (std::array<int, 3>{1, 1, 2}));
    const Residual seam = [](const Eigen::Vector3d& p) { return p.y() - kCenter.y(); };
    expect_faces_and_interior(
        v,
        {[&](const Eigen::Vector3d& p) { return rho(p, kCenter) - inner; }, [&](const Eigen::Vector3d& p) { return rho(p, kCenter) - R; },
         [&](const Eigen::Vector3d& p) { return p.z() - (kCenter.z() - H / 2); }, [&](const Eigen::Vector3d& p) { return p.z() - (kCenter.z() + H / 2); },
         seam, seam},
        [&](const Eigen::Vector3d& p) {
          const double r = rho(p, kCenter);
          return r <= R * (1 + 1e-12) && r >= inner * (1 - 1e-12) && std::abs(p.z() - kCenter.z()) <= H / 2 * (1 + 1e-12);
        },
        R);
    expect_volume_converges(v, kPi * (R * R - inner * inner) * H);
  }
}

TEST(Primitives, ConesAndFrustums) {
  for (double r2 : {0.0, 0.5, 3.0}) {
    const double r1 = 2.0, H = 3.0;
    const auto v = cone(r1, r2, H, kCenter);
    auto radius_at = [&](double z) { return r1 + (r2 - r1) * (z - kCenter.z() + H / 2) / H; };
    const Residual seam = [](const Eigen::Vector3d& p) { return p.y() - kCenter.y(); };
    expect_faces_and_interior(
        v,
        {[&](const Eigen::Vector3d& p) { return rho(p, kCenter); }, [&](const Eigen::Vector3d& p) { return rho(p, kCenter) - radius_at(p.z()); },
         [&](const Eigen::Vector3d& p) { return p.z() - (kCenter.z() - H / 2); }, [&](const Eigen::Vector3d& p) { return p.z() - (kCenter.z() + H / 2); },
         seam, seam},
        [&](const Eigen::Vector3d& p) {
          return rho(p, kCenter) <= radius_at(p.z()) + 1e-12 * r1 && std::abs(p.z() - kCenter.z()) <= H / 2 * (1 + 1e-12);
        },
        3.0);
    expect_volume_converges(v, kPi * H * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0);
  }
}

TEST(Primitives, TorusFullAndSegment) {
  const double R = 3.0, r = 1.0;
  for (double angle : {360.0, 135.0}) {
    const auto v = torus(R, r, angle, kCenter);
    EXPECT_EQ(v.degrees(), (std::array<int, 3>{1, 2, 2}));
    auto tube = [&](const Eigen::Vector3d& p) { return std::hypot(rho(p, kCenter) - R, p.z() - kCenter.z()); };
    const double a = angle * kPi / 180;
    const Residual start = [](const Eigen::Vector3d& p) { return p.y() - kCenter.y(); };
    const Residual end = [&](const Eigen::Vector3d& p) { return -std::sin(a) * (p.x() - kCenter.x()) + std::cos(a) * (p.y() - kCenter.y()); };
    const Residual equator = [](const Eigen::Vector3d& p) { return p.z() - kCenter.z(); };
    expect_faces_and_interior(
        v, {tube, [&](const Eigen::Vector3d& p) { return tube(p) - r; }, equator, equator, start, end},
        [&](const Eigen::Vector3d& p) {
          double phi = std::atan2(p.y() - kCenter.y(), p.x() - kCenter.x());
          if (phi < -1e-12) phi += 2 * kPi;
          return tube(p) <= r * (1 + 1e-12) && phi <= a + 1e-12;
        },
        R + r);
    expect_volume_converges(v, 2 * kPi * kPi * R * r * r * angle / 360.0);
  }
}

TEST(Primitives, HalfTorusIsLasserFigure2) {
  const double R = 2.0, r = 1.0;
  const auto v = half_torus(R, r, kCenter);
  EXPECT_EQ(v.degrees(), (std::array<int, 3>{1, 2, 2}));
  EXPECT_EQ(v.num_control_points(), (std::array<int, 3>{2, 3, 3}));
  int at_infinity = 0;
  for (double w : v.weights()) at_infinity += w == 0.0;
  EXPECT_EQ(at_infinity, 2 * 3 + 2 * 2);  // the middle w layer, and the profile's middle row
  auto tube = [&](const Eigen::Vector3d& p) { return std::hypot(rho(p, kCenter) - R, p.z() - kCenter.z()); };
  const Residual surface = [&](const Eigen::Vector3d& p) { return tube(p) - r; };
  const Residual seam = [](const Eigen::Vector3d& p) { return p.y() - kCenter.y(); };
  expect_faces_and_interior(
      v,
      {surface, surface, [&](const Eigen::Vector3d& p) { return std::hypot(rho(p, kCenter) - (R + r), p.z() - kCenter.z()); },
       [&](const Eigen::Vector3d& p) { return std::hypot(rho(p, kCenter) - (R - r), p.z() - kCenter.z()); }, seam, seam},
      [&](const Eigen::Vector3d& p) { return tube(p) <= r * (1 + 1e-12) && p.y() >= kCenter.y() - 1e-12; }, R + r);
  expect_volume_converges(v, kPi * kPi * R * r * r);
}

TEST(Primitives, HyperboloidIsLasserFigure3) {
  const double a = 1.0, h = 1.0;
  const auto v = hyperboloid_segment(a, h, kCenter);
  EXPECT_EQ(v.degrees(), (std::array<int, 3>{1, 1, 2}));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(v.weights()[static_cast<std::size_t>(4 + i)], 0.0);  // middle layer at infinity
  const Residual saddle = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = p - kCenter;
    return q.y() * a - q.x() * q.z();
  };
  expect_faces_and_interior(
      v,
      {[&](const Eigen::Vector3d& p) { return rho(p, kCenter); },
       [&](const Eigen::Vector3d& p) { return rho(p, kCenter) - std::hypot(a, p.z() - kCenter.z()); },
       [&](const Eigen::Vector3d& p) { return p.z() - kCenter.z() + h; }, [&](const Eigen::Vector3d& p) { return p.z() - kCenter.z() - h; },
       saddle, saddle},
      [&](const Eigen::Vector3d& p) {
        return rho(p, kCenter) <= std::hypot(a, p.z() - kCenter.z()) * (1 + 1e-12) && std::abs(p.z() - kCenter.z()) <= h * (1 + 1e-12);
      },
      2.0);
  // a half of the solid of revolution: pi/2 * integral of (a^2 + z^2) over [-h, h]
  expect_volume_converges(v, kPi / 2 * (2 * a * a * h + 2 * h * h * h / 3));
}

TEST(Primitives, HalfCylinderSweepIsJoyDuchaineauFigure1) {
  const auto v = half_cylinder_sweep();
  // The point set of p(u,v,w) = (cos pi u' + 3w, sin pi u', v), u' = (2/pi) atan(u / (1 - u)).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const double u = unit(rng), s = unit(rng), w = unit(rng);
    const double theta = 2 * std::atan2(u, 1 - u);
    const Eigen::Vector3d expected(std::cos(theta) + 3 * w, std::sin(theta), s);
    EXPECT_LT((v.evaluate({u, s, w}) - expected).norm(), 1e-14);
  }
  for (double u : {0.0, 0.5, 1.0}) {  // where u' = u
    const Eigen::Vector3d expected(std::cos(kPi * u) + 0.6, std::sin(kPi * u), 0.4);
    EXPECT_LT((v.evaluate({u, 0.4, 0.2}) - expected).norm(), 1e-15);
  }
  const Residual y = [](const Eigen::Vector3d& p) { return p.y(); };
  expect_faces_and_interior(
      v,
      {y, y, [](const Eigen::Vector3d& p) { return p.z(); }, [](const Eigen::Vector3d& p) { return p.z() - 1; },
       [](const Eigen::Vector3d& p) { return std::hypot(p.x(), p.y()) - 1; }, [](const Eigen::Vector3d& p) { return std::hypot(p.x() - 3, p.y()) - 1; }},
      [](const Eigen::Vector3d& p) { return p.y() >= 0 && p.y() <= 1 + 1e-15 && p.z() >= 0 && p.z() <= 1; }, 4.0);
}

TEST(Primitives, BadInput) {
  auto where = [](auto f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return e.where();
    }
    return std::string("no error");
  };
  EXPECT_EQ(where([] { box({1, 0, 1}); }), "size");
  EXPECT_EQ(where([] { ball(0.0); }), "radius");
  EXPECT_EQ(where([] { ball(-1.0); }), "radius");
  EXPECT_EQ(where([] { ball(std::nan("")); }), "radius");
  EXPECT_EQ(where([] { ball(1.0, {0, std::numeric_limits<double>::infinity(), 0}); }), "center");
  EXPECT_EQ(where([] { cylinder(1.0, 0.0); }), "height");
  EXPECT_EQ(where([] { cylinder(1.0, 1.0, 1.0); }), "inner");
  EXPECT_EQ(where([] { cylinder(1.0, 1.0, -0.1); }), "inner");
  EXPECT_EQ(where([] { cone(0.0, 0.0, 1.0); }), "radius1");
  EXPECT_EQ(where([] { cone(1.0, -1.0, 1.0); }), "radius2");
  EXPECT_EQ(where([] { torus(1.0, 1.0); }), "major");
  EXPECT_EQ(where([] { torus(2.0, 0.0); }), "minor");
  EXPECT_EQ(where([] { torus(2.0, 1.0, 0.0); }), "angle");
  EXPECT_EQ(where([] { torus(2.0, 1.0, 360.5); }), "angle");
  EXPECT_EQ(where([] { half_torus(1.0, 2.0); }), "major");
  EXPECT_EQ(where([] { hyperboloid_segment(0.0); }), "throat_radius");
  EXPECT_EQ(where([] { hyperboloid_segment(1.0, -1.0); }), "half_height");
}

}  // namespace
}  // namespace volspline
