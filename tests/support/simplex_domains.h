#pragma once
// Tetrahedral domains and DMS spline volumes that tests and benchmarks share (no GoogleTest).
#include <limits>
#include <random>
#include <vector>

#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline::test_support {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// n! as a double (∫ M over R³ = n!/(n+3)!, Hua–He–Qin §3.1).
inline double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

/// The Delaunay tetrahedralisation of an n x n x n grid over [0, 1]^3 whose interior coordinates
/// are jittered by up to `jitter` of a cell (the corners and the faces' coordinates stay put, so
/// Ω is the unit cube; the jitter makes the Delaunay tetrahedralisation unique).
inline TetrahedralMesh jittered_cube_domain(int n = 3, double jitter = 0.12, unsigned seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<Eigen::Vector3d> points;
  const double h = 1.0 / (n - 1);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Eigen::Vector3d p(i * h, j * h, k * h);
        for (int a = 0; a < 3; ++a)
          if (p[a] > 0 && p[a] < 1) p[a] += offset(rng) * h;
        points.push_back(p);
      }
  return delaunay_tetrahedralization(points);
}

/// A volume over jittered_cube_domain with the identity geometry and one attribute "density" (0).
inline DmsSplineVolume cube_simplex_volume(int degree, DmsControlSharing sharing = DmsControlSharing::Shared, int n = 3) {
  TetrahedralMesh domain = jittered_cube_domain(n);
  KnotClouds clouds = generate_knot_clouds(domain, degree);
  return DmsSplineVolume(std::move(domain), std::move(clouds), sharing, {"density"});
}

}  // namespace volspline::test_support
