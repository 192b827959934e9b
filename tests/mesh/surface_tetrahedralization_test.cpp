#include "volspline/mesh/surface_tetrahedralization.h"

#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "support/test_meshes.h"
#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline {
namespace {

// OFF as the CGAL data files write it: "OFF", counts, vertices, then "3 a b c" faces.
TriangleMesh read_off(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string magic;
  std::size_t vertices = 0, faces = 0, edges = 0;
  in >> magic >> vertices >> faces >> edges;
  TriangleMesh mesh;
  for (std::size_t v = 0; v < vertices; ++v) {
    Eigen::Vector3d p;
    in >> p.x() >> p.y() >> p.z();
    mesh.add_vertex(p, Eigen::Vector3d::Zero());
  }
  for (std::size_t f = 0; f < faces; ++f) {
    int n = 0, a = 0, b = 0, c = 0;
    in >> n >> a >> b >> c;
    mesh.add_triangle(a, b, c, 0);
  }
  if (!in || magic != "OFF") ADD_FAILURE() << "cannot read " << path;
  return mesh;
}

TEST(SurfaceTetrahedralization, CubeIsFilledWithVolumeOne) {
  const TriangleMesh cube = test_support::unit_cube();
  const TetrahedralMesh mesh = tetrahedralize_closed_surface(cube, {.cell_size = 0.4});
  EXPECT_NO_THROW(validate_tetrahedral_mesh(mesh));
  // The cube's sharp edges are protected, so the boundary facets lie in its faces.
  EXPECT_NEAR(tetrahedral_mesh_volume(mesh), 1.0, 1e-9);
  const TriangleMesh boundary = test_support::boundary_surface(mesh);
  EXPECT_TRUE(edge_statistics(boundary).closed_and_oriented());
  EXPECT_NEAR(surface_area(boundary), 6.0, 1e-9);
  for (const auto& p : mesh.points) {
    EXPECT_TRUE((p.array() >= -1e-12).all() && (p.array() <= 1 + 1e-12).all()) << p.transpose();
  }
}

TEST(SurfaceTetrahedralization, SphereVolumeWithinTheFacetDistance) {
  TriangleMesh sphere = test_support::icosphere(3);
  const double surface_volume = enclosed_volume(sphere);
  const SurfaceTetrahedralizationOptions options{.cell_size = 0.5, .facet_distance = 0.02};
  const TetrahedralMesh mesh = tetrahedralize_closed_surface(sphere, options);
  // The boundary facets lie within the facet distance of the surface, so the volumes differ by
  // at most about that times the area.
  EXPECT_NEAR(tetrahedral_mesh_volume(mesh), surface_volume, options.facet_distance * surface_area(sphere));
  // Same options, same mesh.
  const TetrahedralMesh again = tetrahedralize_closed_surface(sphere, options);
  EXPECT_EQ(again.points, mesh.points);
  EXPECT_EQ(again.tetrahedra, mesh.tetrahedra);
}

TEST(SurfaceTetrahedralization, OpenSurfaceIsRejected) {
  TriangleMesh open = test_support::unit_cube();
  open.triangles.pop_back();
  open.parts.pop_back();
  try {
    tetrahedralize_closed_surface(open);
    ADD_FAILURE() << "no InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(e.message().find("not closed"), std::string::npos) << e.what();
  }
  EXPECT_THROW(tetrahedralize_closed_surface(test_support::unit_cube(), {.cell_size = -1}), InvalidInput);
}

TEST(SurfaceTetrahedralization, BunnyDomainHasValidKnotClouds) {
  const auto path = test_support::shared_volume_data() / "bunny00.off";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (see docs/tetrahedral-domains.md)";
  const TriangleMesh bunny = read_off(path);
  ASSERT_TRUE(edge_statistics(bunny).closed_and_oriented());
  const auto [lo, hi] = bunny.bounding_box();
  const double diagonal = (hi - lo).norm();
  const SurfaceTetrahedralizationOptions options{.cell_size = diagonal / 8, .facet_distance = diagonal / 100};
  const TetrahedralMesh domain = tetrahedralize_closed_surface(bunny, options);
  EXPECT_NO_THROW(validate_tetrahedral_mesh(domain));
  const double volume = std::abs(enclosed_volume(bunny));
  EXPECT_NEAR(tetrahedral_mesh_volume(domain), volume, options.facet_distance * surface_area(bunny));
  EXPECT_TRUE(edge_statistics(test_support::boundary_surface(domain)).closed_and_oriented());
  for (int degree = 1; degree <= 4; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    EXPECT_NO_THROW(validate_knot_clouds(domain, generate_knot_clouds(domain, degree)));
  }
}

}  // namespace
}  // namespace volspline
