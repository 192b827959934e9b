#include "volspline/mesh/tetrahedral_mesh.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::kuhn_cube;

// Runs `f`, expects InvalidInput located at `where` whose message contains `part`.
template <class F>
void expect_invalid(F&& f, const std::string& where, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no InvalidInput (expected at " << where << ")";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_NE(e.message().find(part), std::string::npos) << e.what();
  }
}

TEST(TetrahedralMesh, KuhnCubeIsValidWithVolumeOne) {
  const TetrahedralMesh cube = kuhn_cube();
  EXPECT_NO_THROW(validate_tetrahedral_mesh(cube));
  EXPECT_NEAR(tetrahedral_mesh_volume(cube), 1.0, 1e-15);
}

TEST(TetrahedralMesh, OutwardFaceTableMatchesTheOrientation) {
  // Each face of a positively oriented tetrahedron, counter-clockwise from outside, has its
  // normal pointing away from the opposite corner.
  const TetrahedralMesh cube = kuhn_cube();
  for (const auto& t : cube.tetrahedra) {
    for (int f = 0; f < 4; ++f) {
      const auto& face = kOutwardTetrahedronFaces[f];
      const Eigen::Vector3d& a = cube.points[t[face[0]]];
      const Eigen::Vector3d normal = (cube.points[t[face[1]]] - a).cross(cube.points[t[face[2]]] - a);
      EXPECT_LT(normal.dot(cube.points[t[f]] - a), 0);
    }
  }
}

TEST(TetrahedralMesh, BoundaryOfTheCubeIsAClosedOutwardSurfaceOfAreaSix) {
  const TetrahedralMesh cube = kuhn_cube();
  const auto faces = boundary_faces(cube);
  EXPECT_EQ(faces.size(), 12u);  // two triangles per cube face
  const TriangleMesh surface = test_support::boundary_surface(cube);
  EXPECT_TRUE(edge_statistics(surface).closed_and_oriented());
  EXPECT_NEAR(surface_area(surface), 6.0, 1e-14);
  // Outward orientation: the divergence theorem gives +volume.
  EXPECT_NEAR(enclosed_volume(surface), tetrahedral_mesh_volume(cube), 1e-14);
  for (const auto& f : faces) {
    EXPECT_EQ(cube.tetrahedra[f.tetrahedron][f.opposite_corner] != f.vertices[0], true);
  }
  const auto on_boundary = boundary_vertices(cube);
  EXPECT_EQ(std::count(on_boundary.begin(), on_boundary.end(), true), 8);
}

TEST(TetrahedralMesh, BoundaryOfADelaunayCubeMatchesItsVolumeAndArea) {
  const TetrahedralMesh cube = test_support::delaunay_cube(4);
  const TriangleMesh surface = test_support::boundary_surface(cube);
  EXPECT_TRUE(edge_statistics(surface).closed_and_oriented());
  EXPECT_NEAR(surface_area(surface), 6.0, 1e-12);
  EXPECT_NEAR(tetrahedral_mesh_volume(cube), 1.0, 1e-12);
  EXPECT_NEAR(enclosed_volume(surface), 1.0, 1e-12);
}

TEST(TetrahedralMesh, OrientPositivelySwapsNegativeTetrahedra) {
  TetrahedralMesh cube = kuhn_cube();
  std::swap(cube.tetrahedra[2][0], cube.tetrahedra[2][1]);
  std::swap(cube.tetrahedra[5][1], cube.tetrahedra[5][3]);
  expect_invalid([&] { validate_tetrahedral_mesh(cube); }, "tetrahedra[2]", "negatively oriented");
  orient_positively(cube);
  EXPECT_NO_THROW(validate_tetrahedral_mesh(cube));
  EXPECT_NEAR(tetrahedral_mesh_volume(cube), 1.0, 1e-15);
}

TEST(TetrahedralMesh, DegenerateTetrahedronIsNamedByBoth) {
  TetrahedralMesh mesh = kuhn_cube();
  mesh.tetrahedra.push_back({0, 1, 2, 3});  // the cube's bottom face: coplanar
  expect_invalid([&] { orient_positively(mesh); }, "tetrahedra[6]", "degenerate");
  expect_invalid([&] { validate_tetrahedral_mesh(mesh); }, "tetrahedra[6]", "degenerate");
}

TEST(TetrahedralMesh, DegeneracyIsDecidedExactly) {
  // Nearly coplanar: the fourth point 1e-300 off the plane is a valid (tiny) tetrahedron, and
  // exactly on a plane that rounding would blur (coordinates with no exact product) is flat.
  TetrahedralMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.25, 0.25, 1e-300}}, {{0, 1, 2, 3}}};
  EXPECT_NO_THROW(validate_tetrahedral_mesh(mesh));
  const Eigen::Vector3d a(0.1, 0.2, 0.3), d(0.7, 0.11, 0.13);
  mesh.points = {a, a + d, a + 2 * d, {1, 2, 3}};
  if ((mesh.points[2] - mesh.points[1]) == (mesh.points[1] - mesh.points[0])) {
    expect_invalid([&] { validate_tetrahedral_mesh(mesh); }, "tetrahedra[0]", "degenerate");
  }
}

TEST(TetrahedralMesh, ValidationNamesWhatIsWrong) {
  {
    TetrahedralMesh m = kuhn_cube();
    m.tetrahedra[3][2] = 8;
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "tetrahedra[3]", "point 8");
  }
  {
    TetrahedralMesh m = kuhn_cube();
    m.tetrahedra[1][0] = -1;
    expect_invalid([&] { orient_positively(m); }, "tetrahedra[1]", "point -1");
  }
  {
    TetrahedralMesh m = kuhn_cube();
    m.tetrahedra[4][3] = m.tetrahedra[4][0];
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "tetrahedra[4]", "same point");
  }
  {
    TetrahedralMesh m = kuhn_cube();
    m.points.emplace_back(2, 2, 2);
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "points[8]", "no tetrahedron");
  }
  {
    TetrahedralMesh m = kuhn_cube();
    m.points[5].y() = std::numeric_limits<double>::quiet_NaN();
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "points[5]", "not finite");
  }
  {
    // A second copy of tetrahedron 0: its faces are shared on the same side.
    TetrahedralMesh m = kuhn_cube();
    m.tetrahedra.push_back(m.tetrahedra[0]);
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "tetrahedra[0]", "overlaps tetrahedra[6]");
  }
  {
    // Three tetrahedra on one face: the cube's tetrahedron 0 and 1 share the face (0, 1, 7);
    // a third beyond it on the far side folds over tetrahedron 1.
    TetrahedralMesh m = kuhn_cube();
    m.points.emplace_back(0.5, -1, 2);
    m.tetrahedra.push_back({0, 1, 7, 8});
    orient_positively(m);
    expect_invalid([&] { validate_tetrahedral_mesh(m); }, "tetrahedra[0]", "shared by 3 tetrahedra");
  }
  expect_invalid([] { validate_tetrahedral_mesh({}); }, "tetrahedra", "at least one");
}

TEST(TetrahedralMesh, PartsAreTheTetrahedraConnectedThroughSharedPoints) {
  TetrahedralMesh two = test_support::kuhn_cube();
  const std::size_t n = two.points.size();
  for (std::size_t i = 0; i < n; ++i) two.points.push_back(two.points[i] + Eigen::Vector3d(1, 0, 0));  // a touching copy
  const std::size_t tets = two.tetrahedra.size();
  for (std::size_t t = 0; t < tets; ++t) {
    std::array<int, 4> copy = two.tetrahedra[t];
    for (int& v : copy) v += static_cast<int>(n);
    two.tetrahedra.push_back(copy);
  }
  const std::vector<int> parts = tetrahedron_parts(two);
  for (std::size_t t = 0; t < parts.size(); ++t) EXPECT_EQ(parts[t], t < tets ? 0 : 1);
}

}  // namespace
}  // namespace volspline
