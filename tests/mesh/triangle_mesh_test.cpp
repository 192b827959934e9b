// triangles_of_part: the triangles of one part, nothing else, each with the corners it had.
#include "volspline/mesh/triangle_mesh.h"

#include <gtest/gtest.h>

namespace volspline {
namespace {

TEST(TrianglesOfPart, KeepsExactlyThePartsTrianglesWithTheirCorners) {
  // Two triangles of part IsoU and one of JacobianZero sharing an edge with the first.
  TriangleMesh mesh;
  for (int i = 0; i < 6; ++i) mesh.add_vertex(Eigen::Vector3d(i, i * i, -i), Eigen::Vector3d(0.1 * i, 0, 0));
  mesh.add_triangle(0, 1, 2, Part::IsoU);
  mesh.add_triangle(1, 2, 3, Part::JacobianZero);
  mesh.add_triangle(5, 4, 2, Part::IsoU);
  const TriangleMesh iso = triangles_of_part(mesh, Part::IsoU);
  ASSERT_EQ(iso.num_triangles(), 2u);
  EXPECT_EQ(iso.num_vertices(), 5u);  // vertex 3 belongs to the other part only
  const std::size_t kept[] = {0, 2};
  for (std::size_t t = 0; t < 2; ++t) {
    EXPECT_EQ(iso.parts[t], part_number(Part::IsoU));
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(iso.triangles[t][static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(mesh.triangles[kept[t]][static_cast<std::size_t>(k)]);
      EXPECT_EQ(iso.positions[a], mesh.positions[b]);
      EXPECT_EQ(iso.parameters[a], mesh.parameters[b]);
    }
  }
  EXPECT_EQ(triangles_of_part(mesh, Part::JacobianZero).num_triangles(), 1u);
  EXPECT_EQ(triangles_of_part(mesh, 99).num_triangles(), 0u);
  EXPECT_EQ(triangles_of_part(mesh, 99).num_vertices(), 0u);
}

}  // namespace
}  // namespace volspline
