// The 7-direction box spline and fields built from it: partition of unity, reproduction of every
// cubic by quasi-interpolation (§6), C² joins across all nine knot-plane families, refinement
// (§7) that leaves the function unchanged, exact point values, and the O(h⁴) error on a torus.
#include "volspline/boxspline/lattice_field.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "volspline/boxspline/bezier_form.h"
#include "boxspline/quartic_tables.h"
#include "volspline/boxspline/seven_direction_box_spline.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

Eigen::Vector3d random_in(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& box, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Vector3d x;
  for (int d = 0; d < 3; ++d) x[d] = box.first[d] + u(rng) * (box.second[d] - box.first[d]);
  return x;
}

LatticeField random_field(std::array<int, 3> size, double h, const Eigen::Vector3d& origin, unsigned seed) {
  LatticeField f(origin, h, size);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double& c : f.coefficients) c = u(rng);
  return f;
}

TEST(SevenDirectionBoxSpline, SupportVolumeAndMaskSums) {
  const auto& m = seven_direction_box_spline();
  // Each tetrahedron has volume 1/24, so the pieces cover the zonotope Σ[0, ξ], whose volume is
  // the sum of |det| over all triples of directions.
  double zonotope = 0.0;
  const auto& xi = kBoxSplineDirections;
  for (int a = 0; a < 7; ++a)
    for (int b = a + 1; b < 7; ++b)
      for (int c = b + 1; c < 7; ++c) {
        const Eigen::Vector3d u(xi[a][0], xi[a][1], xi[a][2]), v(xi[b][0], xi[b][1], xi[b][2]), w(xi[c][0], xi[c][1], xi[c][2]);
        zonotope += std::abs(u.dot(v.cross(w)));
      }
  EXPECT_DOUBLE_EQ(static_cast<double>(m.pieces.size()) / 24.0, zonotope);
  // Each coset of 2Z³ in the mask sums to 1 (constants are refined to constants).
  double cosets[8] = {};
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) cosets[((x + 2) % 2) + 2 * ((y + 2) % 2) + 4 * (z % 2)] += m.mask[x + 6 * (y + 6 * z)];
  for (double s : cosets) EXPECT_NEAR(s, 1.0, 1e-15);
}

TEST(SevenDirectionBoxSpline, PartitionOfUnityOnEveryTetrahedron) {
  const auto& m = seven_direction_box_spline();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d y(u(rng), u(rng), u(rng));
    const CubeLocation at = locate_in_cube(y);
    // The located barycentric coordinates reproduce the point.
    const auto v = cube_tetrahedron_vertices(at.tetrahedron);
    Eigen::Vector3d back = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      EXPECT_GE(at.barycentric[i], -1e-15);
      back += at.barycentric[i] * v[i];
    }
    EXPECT_LT((back - y).norm(), 1e-15);
    double sum = 0.0;
    Eigen::Vector3d gradient_sum = Eigen::Vector3d::Zero();
    for (const int p : m.pieces_on_tetrahedron[at.tetrahedron]) {
      Eigen::Vector3d g;
      sum += evaluate_cube_quartic(m.pieces[p].bb.data(), at.tetrahedron, at.barycentric, &g, nullptr);
      gradient_sum += g;
    }
    EXPECT_NEAR(sum, 1.0, 1e-13);
    EXPECT_LT(gradient_sum.norm(), 1e-12);
  }
  // M is nonnegative and symmetric about the centre of its support.
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d x(-2 + 5 * u(rng), -2 + 5 * u(rng), 5 * u(rng));
    const double value = m.value(x);
    EXPECT_GE(value, -1e-15);
    EXPECT_NEAR(value, m.value(Eigen::Vector3d(1, 1, 5) - x), 1e-14);
  }
}

TEST(LatticeField, PartitionOfUnity) {
  LatticeField f(Eigen::Vector3d(0.3, -1.2, 2.0), 0.7, {9, 8, 10});
  for (double& c : f.coefficients) c = 1.0;
  std::mt19937 rng(2);
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Vector3d g;
    Eigen::Matrix3d hessian;
    EXPECT_NEAR(f.evaluate(random_in(f.domain(), rng), &g, &hessian), 1.0, 1e-13);
    EXPECT_LT(g.norm(), 1e-12);
    EXPECT_LT(hessian.norm(), 1e-11);
  }
}

TEST(LatticeField, QuasiInterpolationReproducesEveryCubicMonomial) {
  const Eigen::Vector3d centre(0.2, -0.1, 0.3);
  LatticeField f = lattice_covering(Eigen::Vector3d(-0.8, -1.1, -0.7), Eigen::Vector3d(1.2, 0.9, 1.3), 0.23);
  std::mt19937 rng(3);
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; a + b <= 3; ++b)
      for (int c = 0; a + b + c <= 3; ++c) {
        const auto p = [&](const Eigen::Vector3d& x) {
          const Eigen::Vector3d y = x - centre;
          return std::pow(y.x(), a) * std::pow(y.y(), b) * std::pow(y.z(), c);
        };
        quasi_interpolate(f, p);
        for (int trial = 0; trial < 100; ++trial) {
          const Eigen::Vector3d x = random_in(f.domain(), rng);
          Eigen::Vector3d g;
          const double value = f.evaluate(x, &g);
          EXPECT_NEAR(value, p(x), 1e-12) << "x^" << a << " y^" << b << " z^" << c;
          // The gradient is reproduced too: compare with the exact partial derivatives.
          const Eigen::Vector3d y = x - centre;
          const Eigen::Vector3d exact(a ? a * std::pow(y.x(), a - 1) * std::pow(y.y(), b) * std::pow(y.z(), c) : 0.0,
                                      b ? b * std::pow(y.x(), a) * std::pow(y.y(), b - 1) * std::pow(y.z(), c) : 0.0,
                                      c ? c * std::pow(y.x(), a) * std::pow(y.y(), b) * std::pow(y.z(), c - 1) : 0.0);
          EXPECT_LT((g - exact).norm(), 1e-11);
        }
      }
}

TEST(LatticeField, PaperCylinderCoefficientsGiveTheCylinder) {
  // §6: with the uncentred M, c_ijk = i² + j² − 2ij + k² + 5k + 4 represents (x − y)² + z² − 1.
  // Our field places c_j at o + j with o = (1/2, 1/2, 5/2) + J0 for the first index J0.
  const int first = -6, n = 13;
  LatticeField f(Eigen::Vector3d(0.5 + first, 0.5 + first, 2.5 + first), 1.0, {n, n, n});
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double I = i + first, J = j + first, K = k + first;
        f.at(i, j, k) = I * I + J * J - 2 * I * J + K * K + 5 * K + 4;
      }
  std::mt19937 rng(4);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d x = random_in(f.domain(), rng);
    EXPECT_NEAR(f.value(x), (x.x() - x.y()) * (x.x() - x.y()) + x.z() * x.z() - 1.0, 1e-11);
  }
}

// Points on one plane of each of the nine knot-plane families, in lattice units u = (x − o)/h:
// u_i ∈ Z + 1/2 (cube faces), u_i − u_j ∈ Z and u_i + u_j ∈ Z (the diagonal planes).
TEST(LatticeField, SecondDerivativesAreContinuousAcrossEveryKnotPlaneFamily) {
  const LatticeField f = random_field({12, 12, 12}, 1.0, Eigen::Vector3d::Zero(), 5);
  std::mt19937 rng(6);
  const auto [lo, hi] = f.domain();
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> inner{lo + Eigen::Vector3d::Constant(1.0), hi - Eigen::Vector3d::Constant(1.0)};
  for (int family = 0; family < 9; ++family) {
    double worst_value = 0, worst_gradient = 0, worst_hessian = 0, largest_third = 0;
    for (int trial = 0; trial < 100; ++trial) {
      Eigen::Vector3d x = random_in(inner, rng);
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      if (family < 3) {
        x[family] = std::floor(x[family]) + 0.5;
        normal[family] = 1.0;
      } else {
        const int pair = (family - 3) / 2, i = pair, j = (pair + 1) % 3;
        if (family % 2 == 1) {  // u_i − u_j ∈ Z
          x[j] = x[i] - std::round(x[i] - x[j]);
          normal[i] = 1.0, normal[j] = -1.0;
        } else {  // u_i + u_j ∈ Z
          x[j] = std::round(x[i] + x[j]) - x[i];
          normal[i] = 1.0, normal[j] = 1.0;
        }
        normal.normalize();
      }
      const double eps = 1e-11;
      Eigen::Vector3d g0, g1;
      Eigen::Matrix3d h0, h1;
      const double v0 = f.evaluate(x - eps * normal, &g0, &h0), v1 = f.evaluate(x + eps * normal, &g1, &h1);
      // Values and gradients move by O(eps) between the two points; take that out first.
      worst_value = std::max(worst_value, std::abs(v1 - v0 - eps * normal.dot(g0 + g1)));
      worst_gradient = std::max(worst_gradient, (g1 - g0 - eps * (h0 + h1) * normal).norm());
      worst_hessian = std::max(worst_hessian, (h1 - h0).cwiseAbs().maxCoeff());
      // The pieces really differ: third derivatives jump (measured a little off the plane).
      Eigen::Matrix3d ha, hb;
      f.evaluate(x - 1e-3 * normal, nullptr, &ha);
      f.evaluate(x + 1e-3 * normal, nullptr, &hb);
      largest_third = std::max(largest_third, ((hb - h1) - (h0 - ha)).cwiseAbs().maxCoeff() / 1e-3);
    }
    EXPECT_LE(worst_value, 1e-12) << "family " << family;
    EXPECT_LE(worst_gradient, 1e-11) << "family " << family;
    EXPECT_LE(worst_hessian, 1e-9) << "family " << family;
    EXPECT_GT(largest_third, 1e-3) << "family " << family << ": the planes should carry third-derivative jumps";
  }
}

TEST(LatticeField, RefinementLeavesTheFunctionUnchanged) {
  const LatticeField coarse = random_field({9, 10, 11}, 0.4, Eigen::Vector3d(-1.0, 0.5, 0.25), 7);
  const LatticeField once = refine(coarse), twice = refine(coarse, 2);
  EXPECT_EQ(once.size[0], 14);
  EXPECT_DOUBLE_EQ(once.spacing, 0.2);
  for (const LatticeField* fine : {&once, &twice}) {
    EXPECT_LT((fine->domain().first - coarse.domain().first).norm(), 1e-14);
    EXPECT_LT((fine->domain().second - coarse.domain().second).norm(), 1e-14);
  }
  std::mt19937 rng(8);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d x = random_in(coarse.domain(), rng);
    const double value = coarse.value(x);
    EXPECT_NEAR(once.value(x), value, 1e-13);
    EXPECT_NEAR(twice.value(x), value, 1e-13);
  }
}

TEST(LatticeField, PointValuesAtLatticePointsFaceAndCubeCentres) {
  const LatticeField f = random_field({9, 9, 9}, 0.5, Eigen::Vector3d(0.1, 0.2, 0.3), 9);
  const Eigen::Vector3d offsets[] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}, {0.5, 0.5, 0.5}};
  for (const Eigen::Vector3d& offset : offsets) {
    const std::vector<double> values = point_values(f, offset);
    int checked = 0;
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
          const Eigen::Vector3d x = f.origin + f.spacing * (Eigen::Vector3d(i, j, k) + offset);
          const double v = values[f.index(i, j, k)];
          EXPECT_EQ(std::isnan(v), !f.in_domain(x));
          if (std::isnan(v)) continue;
          EXPECT_NEAR(v, f.value(x), 1e-13);
          ++checked;
        }
    EXPECT_GT(checked, 20);
  }
  EXPECT_THROW(point_value_stencil(Eigen::Vector3d(0.25, 0, 0)), InvalidInput);
}

TEST(LatticeField, TorusIsApproximatedToFourthOrder) {
  // A torus is quartic, one degree beyond what quasi-interpolation reproduces: the error falls
  // by 2⁴ with every halving of h.
  const double R = 1.0, r = 0.4;
  const auto torus = [&](const Eigen::Vector3d& x) {
    const double q = x.squaredNorm() + R * R - r * r;
    return (q * q - 4 * R * R * (x.x() * x.x() + x.y() * x.y())) / (8 * R * R * r);
  };
  std::mt19937 rng(10);
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> box{Eigen::Vector3d(-1.5, -1.5, -0.5), Eigen::Vector3d(1.5, 1.5, 0.5)};
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) points.push_back(random_in(box, rng));
  std::vector<double> errors;
  for (double h : {0.2, 0.1, 0.05}) {
    LatticeField f = lattice_covering(box.first, box.second, h);
    quasi_interpolate(f, torus);
    double worst = 0.0;
    for (const auto& x : points) worst = std::max(worst, std::abs(f.value(x) - torus(x)));
    errors.push_back(worst);
  }
  for (int i = 0; i + 1 < 3; ++i) {
    const double ratio = errors[i] / errors[i + 1];
    EXPECT_GT(ratio, 14.0) << "h ratio step " << i << " errors " << errors[i] << " " << errors[i + 1];
    EXPECT_LT(ratio, 18.0);
  }
  EXPECT_LT(errors.back(), 1e-4);
}

TEST(LatticeField, SymmetricEvaluationEqualsEachTetrahedronsOwnPieces) {
  // LatticeField::evaluate uses one table of pieces (tetrahedron 0) for all 24 tetrahedra via the
  // signed-permutation symmetry of M_c; evaluate_by_own_pieces uses each tetrahedron's own pieces.
  const LatticeField f = random_field({9, 11, 10}, 0.4, Eigen::Vector3d(-0.7, 0.2, 1.1), 21);
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::array<int, 24> seen{};
  const auto compare = [&](const Eigen::Vector3d& x) {
    Eigen::Vector3d g1;
    Eigen::Matrix3d h1;
    const double v1 = evaluate_by_own_pieces(f, x, &g1, &h1);
    // Every code path this processor runs (the vector widths differ, the arithmetic does not).
    for (const EvaluationCode code : {EvaluationCode::Best, EvaluationCode::Avx512, EvaluationCode::Avx2, EvaluationCode::Portable}) {
      if (!evaluation_code_available(code)) continue;
      Eigen::Vector3d g0;
      Eigen::Matrix3d h0;
      const double v0 = evaluate_with_code(f, code, x, &g0, &h0);
      EXPECT_NEAR(v0, v1, 1e-12);
      EXPECT_LT((g0 - g1).norm(), 1e-12 / f.spacing);
      EXPECT_LT((h0 - h1).norm(), 1e-11 / (f.spacing * f.spacing));
      EXPECT_EQ(v0, evaluate_with_code(f, code, x));  // derivatives requested or not, the same value
    }
    EXPECT_EQ(f.evaluate(x), evaluate_with_code(f, EvaluationCode::Best, x));
  };
  for (int trial = 0; trial < 3000; ++trial) {
    // A random knot cube and a random point of it, so every tetrahedron is hit many times.
    Eigen::Vector3d d(u(rng), u(rng), u(rng));
    const Eigen::Vector3d m(2 + rng() % 5, 2 + rng() % 7, 2 + rng() % 6);
    if (trial % 3 == 1) d[rng() % 3] = (rng() % 2 ? 0.5 : -0.5);  // on a cube face
    if (trial % 3 == 2) d[1] = (rng() % 2 ? 1.0 : -1.0) * std::abs(d[0]);  // on a diagonal knot plane
    ++seen[static_cast<std::size_t>(quartic::locate_canonical(d[0], d[1], d[2]).tetrahedron)];
    compare(f.origin + f.spacing * (m + d));
  }
  for (int t = 0; t < 24; ++t) EXPECT_GT(seen[static_cast<std::size_t>(t)], 50) << t;
  EXPECT_TRUE(evaluation_code_available(EvaluationCode::Portable));
  // The corners of the domain.
  const auto [lo, hi] = f.domain();
  for (int corner = 0; corner < 8; ++corner)
    compare(Eigen::Vector3d(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(), corner & 4 ? hi.z() : lo.z()));
}

TEST(LatticeField, RejectsBadLatticesAndPointsOutsideTheDomain) {
  EXPECT_THROW(LatticeField(Eigen::Vector3d::Zero(), 0.0, {6, 6, 6}), InvalidInput);
  EXPECT_THROW(LatticeField(Eigen::Vector3d::Zero(), 1.0, {4, 6, 6}), InvalidInput);
  EXPECT_THROW(lattice_covering(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.1), InvalidInput);
  EXPECT_THROW(lattice_covering(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1e-9), InvalidInput);
  const LatticeField f(Eigen::Vector3d::Zero(), 1.0, {6, 6, 6});
  EXPECT_THROW(f.value(Eigen::Vector3d(0.5, 2, 2)), InvalidInput);
  EXPECT_THROW(f.value(Eigen::Vector3d(2, 2, 3.6)), InvalidInput);
  EXPECT_THROW(f.value(Eigen::Vector3d(2, std::nan(""), 2)), InvalidInput);
  EXPECT_THROW(evaluate_by_own_pieces(f, Eigen::Vector3d(0.5, 2, 2)), InvalidInput);
  EXPECT_NO_THROW(f.value(Eigen::Vector3d(1.5, 3.5, 2)));
}

}  // namespace
}  // namespace volspline

namespace volspline {
namespace {

TEST(BezierFormField, EqualsTheFieldWithDerivatives) {
  const LatticeField f = random_field({10, 9, 11}, 0.3, Eigen::Vector3d(1.0, -2.0, 0.5), 11);
  const BezierFormField form(f);
  std::mt19937 rng(12);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Vector3d x = random_in(f.domain(), rng);
    EXPECT_TRUE(form.in_domain(x));
    Eigen::Vector3d g0, g1;
    Eigen::Matrix3d h0, h1;
    const double v0 = f.evaluate(x, &g0, &h0), v1 = form.evaluate(x, &g1, &h1);
    EXPECT_NEAR(v0, v1, 1e-13);
    EXPECT_LT((g0 - g1).norm(), 1e-12);
    EXPECT_LT((h0 - h1).norm(), 1e-10);
    // Derivatives against central differences of the values.
    const double e = 1e-6;
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d step = e * Eigen::Vector3d::Unit(d);
      if (!f.in_domain(x + step) || !f.in_domain(x - step)) continue;
      EXPECT_NEAR((form.evaluate(x + step) - form.evaluate(x - step)) / (2 * e), g1[d], 1e-7);
      Eigen::Vector3d gp, gm;
      form.evaluate(x + step, &gp);
      form.evaluate(x - step, &gm);
      EXPECT_LT(((gp - gm) / (2 * e) - h1.col(d)).norm(), 1e-6);
    }
  }
}

}  // namespace
}  // namespace volspline
