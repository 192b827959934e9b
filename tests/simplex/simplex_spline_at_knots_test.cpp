// Simplex splines and the DMS basis at points that coincide with knots: the domain's vertices
// (each the knot t_0 of its cloud) and the sub-knots inside Ω. The clouds of odd degree >= 3 hold
// four knots that are coplanar up to the rounding of their coordinates (the vertex and three
// sub-knots whose directions are linearly dependent), so these points lie on (near) knot planes
// of flat fours as well: the half-open rule within rounding (docs/simplex-splines.md) must make
// every value there the limit from the side of the perturbation x + ε e_x + ε² e_y + ε³ e_z.
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "support/simplex_domains.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/dms_tetrahedron_basis.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

// The volumes of degree 1..4, built once for all tests.
const DmsSplineVolume& knot_test_volume(int degree) {
  static const std::array<DmsSplineVolume, 4> volumes = {
      test_support::cube_simplex_volume(1), test_support::cube_simplex_volume(2),
      test_support::cube_simplex_volume(3), test_support::cube_simplex_volume(4)};
  return volumes[static_cast<std::size_t>(degree - 1)];
}

// The domain's vertices and the knots inside [0, 1]^3; from degree 4 on (where an evaluation at a
// knot takes about 14 ms) only those inside the open cube: the interior vertex and its sub-knots.
std::vector<Eigen::Vector3d> knot_points(const DmsSplineVolume& volume) {
  const bool closed = volume.degree() <= 3;
  std::vector<Eigen::Vector3d> points;
  for (const auto& k : volume.knots().knots) {
    if (closed ? (k.array() >= 0).all() && (k.array() <= 1).all() : (k.array() > 0).all() && (k.array() < 1).all()) {
      points.push_back(k);
    }
  }
  return points;
}

std::map<int, double> basis_values(DmsSplineEvaluator& evaluator, const Eigen::Vector3d& x) {
  std::map<int, double> values;
  evaluator.for_each_basis_function(x, [&](int row, double value) { values[row] += value; });
  return values;
}

// The perturbed side of x at a distance far above the rounding of the knots and far below the
// size of any polynomial piece.
Eigen::Vector3d beside(const Eigen::Vector3d& x) { return x + 1e-13 * Eigen::Vector3d(1, 1e-3, 1e-6); }

TEST(SimplexSplineAtKnots, DmsBasisSumsToOneAndReproducesTheIdentity) {
  for (int degree = 1; degree <= 4; ++degree) {
    const DmsSplineVolume& volume = knot_test_volume(degree);
    DmsSplineEvaluator evaluator(volume);
    double worst_sum = 0;
    double worst_identity = 0;
    for (const Eigen::Vector3d& x : knot_points(volume)) {
      double sum = 0;
      for (const auto& [row, value] : basis_values(evaluator, x)) sum += value;
      worst_sum = std::max(worst_sum, std::abs(sum - 1));
      worst_identity = std::max(worst_identity, (evaluator.evaluate(x).value.head<3>() - x).norm());
    }
    // Measured: 1.5e-14, 4.3e-13, 1.2e-13, 7e-14 (sum) and 1.8e-14, 3.8e-13, 1.7e-13, 6e-14
    // (identity) for degrees 1..4 with barycentric coordinates from faces relative to one of their
    // knots (face_barycentric); 3e-14..8.9e-12 with g·(x - a). Before the knots' flat fours were
    // recognised, degree 3 gave a sum of 106 and an error of 93 at the interior vertex; with them
    // but with the compiled plan's W at knots, 3e-11..3e-10 (degrees 2..4).
    EXPECT_LT(worst_sum, 1e-12) << "degree " << degree;
    EXPECT_LT(worst_identity, 1e-12) << "degree " << degree;
  }
}

TEST(SimplexSplineAtKnots, DmsBasisIsTheLimitFromThePerturbedSide) {
  for (int degree = 1; degree <= 4; ++degree) {
    const DmsSplineVolume& volume = knot_test_volume(degree);
    DmsSplineEvaluator evaluator(volume);
    double worst = 0;
    for (const Eigen::Vector3d& x : knot_points(volume)) {
      if ((beside(x).array() > 1).any()) continue;  // the perturbed side is outside Ω
      const auto at = basis_values(evaluator, x);
      auto near = basis_values(evaluator, beside(x));
      for (const auto& [row, value] : at) worst = std::max(worst, std::abs(value - near[row]));
      for (const auto& [row, value] : near) worst = std::max(worst, std::abs(value - (at.count(row) ? at.at(row) : 0.0)));
    }
    // Measured: 2.3e-13, 6.9e-13, 2.7e-12, 1.1e-12 for degrees 1..4 (the plan's rounding beside
    // the knots; 2e-12..2.6e-11 before the plan took barycentric coordinates from faces relative
    // to one of their knots); basis functions jump by up to 1 across the planes of flat fours, so
    // a value from the wrong side would show.
    EXPECT_LT(worst, 1e-11) << "degree " << degree;
  }
}

// The largest |N_β(x) - |d|·simplex_spline_value(x, V_β)| over the basis of one tetrahedron.
double largest_difference_from_reference(DmsTetrahedronBasis& basis, const std::array<const Eigen::Vector3d*, 4>& clouds,
                                         const std::vector<std::array<int, 4>>& betas, const Eigen::Vector3d& x) {
  DmsBasisValues out;
  basis.evaluate(x, clouds, 0, out);
  double largest = 0;
  for (std::size_t b = 0; b < betas.size(); ++b) {
    // V_β = the first β_c + 1 knots of each cloud; |d| of its last knots (eq. 5).
    std::vector<Eigen::Vector3d> knots;
    std::array<Eigen::Vector3d, 4> last;
    for (int c = 0; c < 4; ++c) {
      for (int m = 0; m <= betas[b][c]; ++m) knots.push_back(clouds[c][m]);
      last[c] = clouds[c][betas[b][c]];
    }
    const double d = std::abs((last[1] - last[0]).dot((last[2] - last[0]).cross(last[3] - last[0])));
    largest = std::max(largest, std::abs(out.values[b] - d * simplex_spline_value(x, knots)));
  }
  return largest;
}

TEST(SimplexSplineAtKnots, CompiledPlanEqualsScaledReferenceSplines) {
  // Degrees 1..3: the unmemoised reference at degree 4 would take most of the suite's time here.
  for (int degree = 1; degree <= 3; ++degree) {
    const DmsSplineVolume& volume = knot_test_volume(degree);
    const auto betas = dms_multi_indices(degree);
    DmsTetrahedronBasis basis(degree);
    double worst_at = 0;
    double worst_beside = 0;
    for (const auto& tet : volume.domain().tetrahedra) {
      const std::array<const Eigen::Vector3d*, 4> clouds = {volume.knots().cloud(tet[0]), volume.knots().cloud(tet[1]),
                                                            volume.knots().cloud(tet[2]), volume.knots().cloud(tet[3])};
      // Every knot of the tetrahedron's clouds inside Ω's box (evaluated by the memoised
      // recurrence with W containing the point), and beside it (by the compiled plan).
      for (int cloud = 0; cloud < 4; ++cloud) {
        for (int k = 0; k <= degree; ++k) {
          const Eigen::Vector3d& x = clouds[cloud][k];
          if ((x.array() < 0).any() || (x.array() > 1).any()) continue;
          worst_at = std::max(worst_at, largest_difference_from_reference(basis, clouds, betas, x));
          worst_beside = std::max(worst_beside, largest_difference_from_reference(basis, clouds, betas, beside(x)));
        }
      }
    }
    // Measured: 0 at the knots (the same recurrence; 138 for degree 3 before), 9.3e-13, 2.7e-12,
    // 3.8e-13 beside them for degrees 1..3 (the plan's fixed W near a cloud's small tetrahedra;
    // 9.9e-11, 2.6e-11, 3.3e-11 with barycentric coordinates g·(x - a) instead of from faces).
    EXPECT_LT(worst_at, 1e-12) << "degree " << degree;
    EXPECT_LT(worst_beside, 1e-11) << "degree " << degree;
  }
}

}  // namespace
}  // namespace volspline
