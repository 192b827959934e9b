#include "volspline/mesh/tetrahedral_mesh_reader.h"

#include <fstream>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"
#include "support/tetrahedral_domains.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using test_support::TemporaryDirectory;

std::filesystem::path write(const TemporaryDirectory& dir, const std::string& name, const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Expects InvalidInput located exactly at `where` whose message contains `part`.
void expect_invalid(const std::filesystem::path& path, const std::string& where, const std::string& part) {
  try {
    read_tetrahedral_mesh(path);
    ADD_FAILURE() << "no InvalidInput for " << path;
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), where) << e.what();
    EXPECT_NE(e.message().find(part), std::string::npos) << e.message();
  }
}

// The Kuhn cube written in each format, with the corners of tetrahedron 2 swapped to a negative
// orientation, which the reader must repair.
std::string medit_cube(const std::string& extra = "", bool unused_vertex = false) {
  const TetrahedralMesh cube = test_support::kuhn_cube();
  std::string text = "MeshVersionFormatted 2\nDimension 3\n# the unit cube\nVertices\n";
  text += unused_vertex ? "9\n" : "8\n";
  for (const auto& p : cube.points) text += std::to_string(int(p.x())) + " " + std::to_string(int(p.y())) + " " + std::to_string(int(p.z())) + " 0\n";
  if (unused_vertex) text += "5 5 5 0\n";
  text += extra;
  text += "Tetrahedra\n6\n";
  for (std::size_t t = 0; t < cube.tetrahedra.size(); ++t) {
    auto tet = cube.tetrahedra[t];
    if (t == 2) std::swap(tet[0], tet[1]);
    for (int v : tet) text += std::to_string(v + 1) + " ";
    text += "1\n";
  }
  return text + "End\n";
}

void expect_unit_cube(const TetrahedralMesh& mesh) {
  EXPECT_NO_THROW(validate_tetrahedral_mesh(mesh));
  EXPECT_EQ(mesh.points.size(), 8u);
  EXPECT_EQ(mesh.tetrahedra.size(), 6u);
  EXPECT_NEAR(tetrahedral_mesh_volume(mesh), 1.0, 1e-15);
}

TEST(TetrahedralMeshReader, MeditCubeWithBoundaryTrianglesSkipped) {
  TemporaryDirectory dir;
  expect_unit_cube(read_tetrahedral_mesh(write(dir, "cube.mesh", medit_cube("Triangles\n1\n1 2 3 7\nCorners\n1\n1\n"))));
}

std::string at(const TemporaryDirectory& dir, const std::string& name, const std::string& place) {
  return (dir / name).string() + ": " + place;
}

TEST(TetrahedralMeshReader, MeditErrorsNameTheLine) {
  TemporaryDirectory dir;
  const std::string text = medit_cube();
  // Lines: 1-3 header, 4 "Vertices", 5 "8", 6-13 the vertices, 14 "Tetrahedra", 15 "6", 16-21
  // the tetrahedra.
  const std::size_t first_tetrahedron = text.find("Tetrahedra\n6\n") + 13;
  std::string bad_index = text;
  bad_index.replace(first_tetrahedron, 1, "9");
  expect_invalid(write(dir, "index.mesh", bad_index), at(dir, "index.mesh", "line 16"), "names vertex 9");
  std::string degenerate = text;
  degenerate.replace(first_tetrahedron, 7, "1 2 3 4");
  expect_invalid(write(dir, "flat.mesh", degenerate), at(dir, "flat.mesh", "line 16"), "degenerate");
  expect_invalid(write(dir, "truncated.mesh", text.substr(0, first_tetrahedron + 7)), at(dir, "truncated.mesh", "line 15"),
                 "room for at most");
  std::string count = text;
  count.replace(count.find("Vertices\n8"), 10, "Vertices\nx");
  expect_invalid(write(dir, "count.mesh", count), at(dir, "count.mesh", "line 5"), "the number of vertices");
  expect_invalid(write(dir, "hex.mesh", medit_cube("Hexahedra\n1\n1 2 3 4 5 6 7 8 0\n")), at(dir, "hex.mesh", "line 14"),
                 "Hexahedra");
  expect_invalid(write(dir, "unknown.mesh", medit_cube("Colours\n0\n")), at(dir, "unknown.mesh", "line 14"),
                 "unknown keyword");
  expect_invalid(write(dir, "unused.mesh", medit_cube("", true)), at(dir, "unused.mesh", "line 14"), "no tetrahedron uses");
}

TEST(TetrahedralMeshReader, TetgenNodeAndEleFromEitherPath) {
  TemporaryDirectory dir;
  const TetrahedralMesh cube = test_support::kuhn_cube();
  std::string node = "# cube\n8 3 1 1\n";
  for (std::size_t i = 0; i < 8; ++i) {
    const auto& p = cube.points[i];
    node += std::to_string(i + 1) + " " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + " 0.5 1\n";
  }
  std::string ele = "6 4 1\n";
  for (std::size_t t = 0; t < 6; ++t) {
    auto tet = cube.tetrahedra[t];
    if (t == 4) std::swap(tet[2], tet[3]);
    ele += std::to_string(t + 1) + "  " + std::to_string(tet[0] + 1) + " " + std::to_string(tet[1] + 1) + " " +
           std::to_string(tet[2] + 1) + " " + std::to_string(tet[3] + 1) + " 7\n";
  }
  write(dir, "cube.node", node);
  write(dir, "cube.ele", ele);
  expect_unit_cube(read_tetrahedral_mesh(dir / "cube.node"));
  expect_unit_cube(read_tetrahedral_mesh(dir / "cube.ele"));

  // Errors: ele line 3 is tetrahedron 2.
  std::string bad = ele;
  bad.replace(bad.find("\n2  ") + 4, 1, "0");  // point 0 with numbering from 1
  write(dir, "index.node", node);
  write(dir, "index.ele", bad);
  expect_invalid(dir / "index.ele", (dir / "index.ele").string() + ": line 3", "point 0");
  write(dir, "short.node", node.substr(0, node.rfind("8 ")));
  write(dir, "short.ele", ele);
  expect_invalid(dir / "short.node", (dir / "short.node").string() + ": line 10", "ends after 7");
  write(dir, "quadratic.node", node);
  write(dir, "quadratic.ele", "1 10 0\n1 1 2 3 4 5 6 7 8 1 2\n");
  expect_invalid(dir / "quadratic.ele", (dir / "quadratic.ele").string() + ": line 1", "10 nodes");
  write(dir, "flat.node", node);
  write(dir, "flat.ele", "1 4 0\n1 1 2 3 4\n");
  expect_invalid(dir / "flat.ele", (dir / "flat.ele").string() + ": line 2", "degenerate");
  EXPECT_THROW(read_tetrahedral_mesh(dir / "missing.node"), IoError);
}

std::string vtu_text(const std::string& types) {
  return R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">
  <UnstructuredGrid>
    <Piece NumberOfPoints="5" NumberOfCells="3">
      <Points>
        <DataArray type="Float64" NumberOfComponents="3" format="ascii">
          0 0 0  1 0 0  0 1 0  0 0 1  1 1 1
        </DataArray>
      </Points>
      <Cells>
        <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3  2 1 3 4  0 1 2</DataArray>
        <DataArray type="Int64" Name="offsets" format="ascii">4 8 11</DataArray>
        <DataArray type="UInt8" Name="types" format="ascii">)" +
         types + R"(</DataArray>
      </Cells>
    </Piece>
  </UnstructuredGrid>
</VTKFile>
)";
}

TEST(TetrahedralMeshReader, VtuTetrahedraWithATriangleSkipped) {
  TemporaryDirectory dir;
  // Tetrahedron 1 (2, 1, 3, 4) is negatively oriented as written; cell 2 is a triangle.
  const TetrahedralMesh mesh = read_tetrahedral_mesh(write(dir, "two.vtu", vtu_text("10 10 5")));
  EXPECT_EQ(mesh.tetrahedra.size(), 2u);
  EXPECT_NEAR(tetrahedral_mesh_volume(mesh), 1.0 / 6 + 1.0 / 3, 1e-15);
  const TriangleMesh boundary = test_support::boundary_surface(mesh);
  EXPECT_TRUE(edge_statistics(boundary).closed_and_oriented());
}

TEST(TetrahedralMeshReader, VtuErrorsNameTheCell) {
  TemporaryDirectory dir;
  expect_invalid(write(dir, "wedge.vtu", vtu_text("10 13 5")), (dir / "wedge.vtu").string() + ": cell 1", "VTK_WEDGE");
  const std::string text = vtu_text("10 10 5");
  expect_invalid(write(dir, "truncated.vtu", text.substr(0, text.size() / 2)), (dir / "truncated.vtu").string(), "parsing XML");
  std::string index = text;
  index.replace(index.find("2 1 3 4"), 7, "2 1 3 9");
  expect_invalid(write(dir, "index.vtu", index), (dir / "index.vtu").string() + ": cell 1", "point 9");
  std::string flat = text;
  flat.replace(flat.find("1 1 1"), 5, "1 1 0");  // point 4 onto the plane z = 0 of points 0, 1, 2
  flat.replace(flat.find("2 1 3 4"), 7, "0 1 2 4");
  expect_invalid(write(dir, "flat.vtu", flat), (dir / "flat.vtu").string() + ": cell 1", "degenerate");
}

TEST(TetrahedralMeshReader, LegacyVtkTetrahedra) {
  TemporaryDirectory dir;
  const std::string header = "# vtk DataFile Version 3.0\ntwo tetrahedra\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                             "POINTS 5 double\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
  const std::string cells = "CELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\n";
  const TetrahedralMesh mesh = read_tetrahedral_mesh(write(dir, "two.vtk", header + cells + "CELL_TYPES 2\n10\n10\n"));
  EXPECT_EQ(mesh.tetrahedra.size(), 2u);
  EXPECT_NEAR(tetrahedral_mesh_volume(mesh), 1.0 / 6 + 1.0 / 3, 1e-15);
  expect_invalid(write(dir, "hex.vtk", header + cells + "CELL_TYPES 2\n10\n12\n"), (dir / "hex.vtk").string() + ": cell 1",
                 "VTK_HEXAHEDRON");
  expect_invalid(write(dir, "poly.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 0 double\n"),
                 (dir / "poly.vtk").string(), "UNSTRUCTURED_GRID");
  // A truncated file: what VTK says, located at the file.
  expect_invalid(write(dir, "truncated.vtk", header + "CELLS 2 10\n4 0 1 2 3\n"), (dir / "truncated.vtk").string(),
                 "Error reading");
  EXPECT_THROW(read_tetrahedral_mesh(dir / "missing.vtk"), IoError);
  expect_invalid(write(dir, "cube.stl", "solid\n"), (dir / "cube.stl").string(), "unknown tetrahedral mesh format");
  // Fewer point coordinates than declared, or one that is not a number: VTK warns and reads
  // zeros (a point at the origin); refused instead.
  const std::string short_points = "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n0 0 0 1 0 0 0 1 0 0 0 1\n";
  expect_invalid(write(dir, "short.vtk", short_points + cells + "CELL_TYPES 2\n10\n10\n"), (dir / "short.vtk").string(), "Error reading");
  const std::string word = "# vtk DataFile Version 3.0\nx\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n0 0 0 1 0 0 0 1 0 0 0 1 1 one 1\n";
  expect_invalid(write(dir, "word.vtk", word + cells + "CELL_TYPES 2\n10\n10\n"), (dir / "word.vtk").string(), "one");
  // The output window is the process's own again after a refused read: a good file still reads.
  EXPECT_EQ(read_tetrahedral_mesh(dir / "two.vtk").tetrahedra.size(), 2u);
}

TEST(TetrahedralMeshReader, FireGridFromMayaviIsHexahedral) {
  const auto path = test_support::shared_volume_data() / "fire_ug.vtu";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (see docs/tetrahedral-domains.md)";
  // The room-fire grid (12,323 points, 10,462 cells) is made of hexahedra only: the reader
  // refuses the first cell rather than leave holes.
  expect_invalid(path, path.string() + ": cell 0", "VTK_HEXAHEDRON");
}

}  // namespace
}  // namespace volspline
