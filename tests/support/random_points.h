#pragma once
// Scattered data sites for fitting tests: uniform random points in a box, deterministic for a
// seed (x, then y, then z drawn in that order).
#include <cstddef>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace volspline::test_support {

inline std::vector<Eigen::Vector3d> random_points_in_box(std::size_t n, unsigned seed, const Eigen::Vector3d& low = Eigen::Vector3d::Zero(),
                                                         const Eigen::Vector3d& high = Eigen::Vector3d::Ones()) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points(n);
  for (auto& p : points)
    for (int d = 0; d < 3; ++d) p[d] = low[d] + (high[d] - low[d]) * u(random);
  return points;
}

}  // namespace volspline::test_support
