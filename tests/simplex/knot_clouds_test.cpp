#include "volspline/simplex/knot_clouds.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/tetrahedron_locator.h"

namespace volspline {
namespace {

template <class F>
InvalidInput expect_invalid(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e;
  }
  ADD_FAILURE() << "no InvalidInput";
  return InvalidInput("none");
}

bool inside_closed_unit_cube(const Eigen::Vector3d& x) {
  return (x.array() >= 0).all() && (x.array() <= 1).all();
}

// The independent checks of generated clouds on a cube domain: t_0 is the vertex, sub-knots
// are within the spread of it, and those of boundary vertices lie outside [0, 1]^3.
void expect_cloud_geometry(const TetrahedralMesh& domain, const KnotClouds& clouds, double spread) {
  const auto on_boundary = boundary_vertices(domain);
  std::vector<double> shortest(domain.points.size(), 1e300);
  for (const auto& t : domain.tetrahedra)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) shortest[t[a]] = std::min(shortest[t[a]], (domain.points[t[a]] - domain.points[t[b]]).norm());
  for (std::size_t v = 0; v < domain.points.size(); ++v) {
    const Eigen::Vector3d* cloud = clouds.cloud(static_cast<int>(v));
    EXPECT_EQ(cloud[0], domain.points[v]);
    for (int l = 1; l <= clouds.degree; ++l) {
      const double distance = (cloud[l] - cloud[0]).norm();
      EXPECT_GT(distance, 0);
      EXPECT_LE(distance, spread * shortest[v] * (1 + 1e-12));
      if (on_boundary[v]) {
        EXPECT_FALSE(inside_closed_unit_cube(cloud[l])) << "vertex " << v << " knot " << l;
      }
      for (int m = 1; m < l; ++m) EXPECT_NE(cloud[l], cloud[m]);
    }
  }
}

TEST(KnotClouds, GeneratedCloudsAreValidForDegreesOneToFourOnADelaunayCube) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4);
  for (int degree = 1; degree <= 4; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    const KnotClouds clouds = generate_knot_clouds(cube, degree);
    EXPECT_EQ(clouds.degree, degree);
    ASSERT_EQ(clouds.knots.size(), cube.points.size() * (degree + 1));
    EXPECT_NO_THROW(validate_knot_clouds(cube, clouds));
    expect_cloud_geometry(cube, clouds, KnotCloudOptions{}.spread);
  }
}

TEST(KnotClouds, GeneratedCloudsAreValidOnTheKuhnCubeWhereEveryVertexIsOnTheBoundary) {
  const TetrahedralMesh cube = test_support::kuhn_cube();
  for (int degree = 0; degree <= kMaxKnotCloudDegree; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    const KnotClouds clouds = generate_knot_clouds(cube, degree, {.spread = 0.3});
    EXPECT_NO_THROW(validate_knot_clouds(cube, clouds));
    expect_cloud_geometry(cube, clouds, 0.3);
  }
}

TEST(KnotClouds, GenerationIsDeterministic) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4);
  EXPECT_EQ(generate_knot_clouds(cube, 3).knots, generate_knot_clouds(cube, 3).knots);
}

TEST(KnotClouds, SliversShrinkTheirCloudsUntilValid) {
  // Random points: the Delaunay hull has flat tetrahedra, where the default spread flips knot
  // tetrahedra and generation has to shrink it locally.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 80; ++i) points.emplace_back(u(random), u(random), u(random));
  const TetrahedralMesh domain = delaunay_tetrahedralization(points);
  const KnotClouds clouds = generate_knot_clouds(domain, 3, {.spread = 0.45});
  EXPECT_NO_THROW(validate_knot_clouds(domain, clouds));
  const TetrahedronLocator locator(domain);
  const auto on_boundary = boundary_vertices(domain);
  for (std::size_t v = 0; v < domain.points.size(); ++v) {
    if (!on_boundary[v]) continue;
    for (int l = 1; l <= 3; ++l) EXPECT_EQ(locator.locate(clouds.cloud(static_cast<int>(v))[l]), -1);
  }
}

TEST(KnotClouds, GenerationGivesUpNamingTheTetrahedronWhereNoSpreadWorks) {
  // Tetrahedron 1 touches the bottom face of tetrahedron 0 with its apex (a T-junction, which
  // validate_tetrahedral_mesh does not look for) and shares point 0 with it, so both are one
  // part: every sub-knot of the apex, along its outward pseudo-normal (up), lies in tetrahedron
  // 0, however small the spread.
  TetrahedralMesh domain{{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 1}, {0.3, 0.3, 0}, {0, 0, -1}, {1, 0, -1}},
                         {{0, 1, 2, 3}, {4, 5, 6, 0}}};
  orient_positively(domain);
  ASSERT_NO_THROW(validate_tetrahedral_mesh(domain));
  // Parts that share no point are separate splines (docs/simplex-splines.md, "Parts"): there a
  // sub-knot in the other part is allowed.
  TetrahedralMesh apart{{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 1}, {0.3, 0.3, 0}, {0, 0, -1}, {1, 0, -1}, {0, 1, -1}},
                        {{0, 1, 2, 3}, {4, 5, 6, 7}}};
  orient_positively(apart);
  EXPECT_NO_THROW(validate_knot_clouds(apart, generate_knot_clouds(apart, 2)));
  const InvalidInput e = expect_invalid([&] { generate_knot_clouds(domain, 2); });
  EXPECT_EQ(e.where(), "tetrahedra[1]") << e.what();
  EXPECT_NE(e.message().find("of point 4 inside Ω (in tetrahedra[0])"), std::string::npos) << e.what();
}

TEST(KnotClouds, SubKnotInsideTheDomainOnABoundaryVertexIsNamed) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4);
  KnotClouds clouds = generate_knot_clouds(cube, 2);
  // Point 0 is the corner (0, 0, 0); move its t_2 a little into the cube.
  ASSERT_EQ(cube.points[0], Eigen::Vector3d::Zero());
  clouds.knots[0 * 3 + 2] = Eigen::Vector3d(0.01, 0.02, 0.015);
  const InvalidInput e = expect_invalid([&] { validate_knot_clouds(cube, clouds); });
  EXPECT_NE(e.message().find("t_2"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("outside"), std::string::npos) << e.what();
  ASSERT_EQ(e.where().rfind("tetrahedra[", 0), 0u) << e.what();
  const int t = std::stoi(e.where().substr(11));
  const auto& tet = cube.tetrahedra.at(t);
  EXPECT_NE(std::find(tet.begin(), tet.end(), 0), tet.end()) << e.what();
}

TEST(KnotClouds, FlatKnotTetrahedronIsNamed) {
  const TetrahedralMesh cube = test_support::kuhn_cube();
  KnotClouds clouds = generate_knot_clouds(cube, 2, {.spread = 0.3});
  // Tetrahedron 0 is (0, 1, 3, 7); points 1, 3, 7 lie on the plane x = 1, so [p_1, q_0, r_0, s_0]
  // with p_1 on that plane is flat.
  ASSERT_EQ(cube.tetrahedra[0], (std::array<int, 4>{0, 1, 3, 7}));
  clouds.knots[0 * 3 + 1] = Eigen::Vector3d(1, 0.5, 0.25);
  const InvalidInput e = expect_invalid([&] { validate_knot_clouds(cube, clouds); });
  EXPECT_EQ(e.where(), "tetrahedra[0]");
  EXPECT_NE(e.message().find("degenerate"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("p_1 = (1, 0.5, 0.25)"), std::string::npos) << e.what();
}

// One tetrahedron (p, q, r, s) with faces qrs on z = 0 and prs on y = 0, meeting at the edge rs
// (the x axis) at a right angle.
TetrahedralMesh right_angled_tetrahedron() {
  return {{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}}, {{0, 1, 2, 3}}};
}

TEST(KnotClouds, EmptyCommonInteriorIsDecidedExactlyAndNamed) {
  const TetrahedralMesh domain = right_angled_tetrahedron();
  ASSERT_NO_THROW(validate_tetrahedral_mesh(domain));
  // p_1 just above face qrs and q_1 just beside face prs: [p_1, q, r, s] and [p, q_1, r, s] are
  // thin wedges on the two faces at the edge rs and meet only on it. Every knot tetrahedron is
  // positively oriented, the centroid certificate fails, and the linear programme decides.
  KnotClouds clouds{1, {domain.points[0], {0.25, 0.25, 1e-3}, domain.points[1], {0.25, 1e-3, 0.25},
                        domain.points[2], {1.1, -0.1, -0.1}, domain.points[3], {-0.1, -0.1, -0.1}}};
  const InvalidInput e = expect_invalid([&] { validate_knot_clouds(domain, clouds); });
  EXPECT_EQ(e.where(), "tetrahedra[0]");
  EXPECT_NE(e.message().find("eq. 3"), std::string::npos) << e.what();
  // With q_1 moved outside, only the thin wedge [p_1, q, r, s] is left over the common part:
  // eq. 3 holds (the linear programme finds its interior, the centroid is not in it), and what
  // remains wrong is that p_1 lies inside Ω.
  clouds.knots[3] = Eigen::Vector3d(-0.1, 1.1, -0.1);
  const InvalidInput inside = expect_invalid([&] { validate_knot_clouds(domain, clouds); });
  EXPECT_EQ(inside.where(), "tetrahedra[0]");
  EXPECT_NE(inside.message().find("inside Ω"), std::string::npos) << inside.what();
  EXPECT_NE(inside.message().find("t_1 = (0.25, 0.25, 0.001)"), std::string::npos) << inside.what();
  // A wedge a millionth of a radian wide: still a common interior.
  clouds.knots[1] = Eigen::Vector3d(0.25, 0.25, 1e-7);
  const InvalidInput thin = expect_invalid([&] { validate_knot_clouds(domain, clouds); });
  EXPECT_NE(thin.message().find("inside Ω"), std::string::npos) << thin.what();
}

TEST(KnotClouds, KnotTetrahedronIndicesAreTheMultiIndicesUpToTheDegree) {
  for (int n = 0; n <= kMaxKnotCloudDegree; ++n) {
    const auto indices = knot_tetrahedron_indices(n);
    // C(n + 4, 4) quadruples of non-negative integers with sum <= n, all distinct.
    EXPECT_EQ(indices.size(), static_cast<std::size_t>((n + 1) * (n + 2) * (n + 3) * (n + 4) / 24));
    for (const auto& b : indices) {
      EXPECT_TRUE(std::all_of(b.begin(), b.end(), [](int x) { return x >= 0; }));
      EXPECT_LE(b[0] + b[1] + b[2] + b[3], n);
    }
    EXPECT_TRUE(std::is_sorted(indices.begin(), indices.end()));
    EXPECT_EQ(std::adjacent_find(indices.begin(), indices.end()), indices.end());
  }
}

TEST(KnotClouds, EquationThreeVerdictsAgreeWithSampling) {
  // Random clouds on one tetrahedron: wherever random points of I find one strictly inside all
  // knot tetrahedra (by barycentric coordinates in doubles, with a margin), validation must not
  // report eq. 3; and both verdicts must occur, so the comparison is not vacuous.
  const TetrahedralMesh domain = right_angled_tetrahedron();
  const int n = 2;
  std::mt19937 random(17);
  std::uniform_real_distribution<double> u(-1, 1), unit(0, 1);
  int empty = 0, nonempty = 0, confirmed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    KnotClouds clouds{n, {}};
    for (int v = 0; v < 4; ++v) {
      clouds.knots.push_back(domain.points[v]);
      for (int l = 1; l <= n; ++l) clouds.knots.push_back(domain.points[v] + 0.45 * Eigen::Vector3d(u(random), u(random), u(random)));
    }
    std::string verdict = "valid";
    try {
      validate_knot_clouds(domain, clouds);
    } catch (const InvalidInput& e) {
      verdict = e.message();
    }
    if (verdict.find("degenerate") != std::string::npos || verdict.find("opposite") != std::string::npos) continue;
    const bool reported_empty = verdict.find("eq. 3") != std::string::npos;
    (reported_empty ? empty : nonempty) += 1;
    bool sampled_inside = false;
    for (int s = 0; s < 400 && !sampled_inside; ++s) {
      double w[4], sum = 0;
      for (double& x : w) sum += (x = -std::log(1 - unit(random)));
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int c = 0; c < 4; ++c) x += w[c] / sum * domain.points[c];
      bool inside_all = true;
      for (const auto& sub : knot_tetrahedron_indices(n)) {
        Eigen::Matrix3d m;
        const Eigen::Vector3d a = clouds.cloud(0)[sub[0]];
        for (int c = 1; c < 4; ++c) m.col(c - 1) = clouds.cloud(c)[sub[c]] - a;
        const Eigen::Vector3d b = m.inverse() * (x - a);
        if (!((b.array() > 1e-9).all() && b.sum() < 1 - 1e-9)) {
          inside_all = false;
          break;
        }
      }
      sampled_inside = inside_all;
    }
    if (sampled_inside) {
      EXPECT_FALSE(reported_empty) << "trial " << trial << ": " << verdict;
      ++confirmed;
    }
  }
  EXPECT_GT(empty, 5);
  EXPECT_GT(nonempty, 5);
  EXPECT_GT(confirmed, 5);
}

TEST(KnotClouds, MalformedCloudsAreRejected) {
  const TetrahedralMesh cube = test_support::kuhn_cube();
  KnotClouds clouds = generate_knot_clouds(cube, 1, {.spread = 0.3});
  KnotClouds short_clouds = clouds;
  short_clouds.knots.pop_back();
  EXPECT_EQ(expect_invalid([&] { validate_knot_clouds(cube, short_clouds); }).where(), "knots");
  KnotClouds moved = clouds;
  moved.knots[2 * 2] += Eigen::Vector3d(1e-9, 0, 0);
  EXPECT_EQ(expect_invalid([&] { validate_knot_clouds(cube, moved); }).where(), "knots[4]");
  KnotClouds high = clouds;
  high.degree = kMaxKnotCloudDegree + 1;
  EXPECT_EQ(expect_invalid([&] { validate_knot_clouds(cube, high); }).where(), "degree");
  EXPECT_EQ(expect_invalid([&] { generate_knot_clouds(cube, -1); }).where(), "degree");
  EXPECT_EQ(expect_invalid([&] { generate_knot_clouds(cube, 2, {.spread = 0.5}); }).where(), "spread");
}

}  // namespace
}  // namespace volspline
