// Mesh import: what the writers write reads back, hand-written files of every flavour parse,
// and bad files are rejected with the file and the place named.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <set>
#include <tuple>

#include "support/temporary_directory.h"
#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"

namespace volspline {
namespace {

std::string mesh_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}

// The sphere with varied parts and parameters that differ from the positions.
TriangleMesh sample_mesh() {
  TriangleMesh mesh = test_support::icosphere(2);
  for (std::size_t i = 0; i < mesh.parameters.size(); ++i) mesh.parameters[i] = Eigen::Vector3d(0.1 * i, 1.0 / (i + 3), -0.5);
  for (std::size_t t = 0; t < mesh.parts.size(); ++t) mesh.parts[t] = static_cast<int>(t % 7);
  return mesh;
}

// Triangles with their parts as a sorted list, for formats that regroup triangles by part.
std::multiset<std::tuple<int, int, int, int>> triangle_set(const TriangleMesh& mesh, bool with_parts) {
  std::multiset<std::tuple<int, int, int, int>> s;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& x = mesh.triangles[t];
    s.insert({x[0], x[1], x[2], with_parts ? mesh.parts[t] : 0});
  }
  return s;
}

TEST(MeshReader, PlyRoundTripIsExactInBothEncodings) {
  const TriangleMesh mesh = sample_mesh();
  for (const bool ascii : {false, true}) {
    const TriangleMesh back = parse_ply(ply_bytes(mesh, ascii), "m.ply");
    EXPECT_EQ(back.positions, mesh.positions) << ascii;
    EXPECT_EQ(back.parameters, mesh.parameters) << ascii;
    EXPECT_EQ(back.triangles, mesh.triangles) << ascii;
    EXPECT_EQ(back.parts, mesh.parts) << ascii;
  }
}

TEST(MeshReader, ObjRoundTripKeepsPositionsTrianglesAndParts) {
  const TriangleMesh mesh = sample_mesh();
  const TriangleMesh back = parse_obj(obj_bytes(mesh), "m.obj");
  EXPECT_EQ(back.positions, mesh.positions);  // 17 digits
  EXPECT_EQ(triangle_set(back, true), triangle_set(mesh, true));
  for (const auto& p : back.parameters) EXPECT_EQ(p, Eigen::Vector3d::Zero());
}

TEST(MeshReader, StlRoundTripWeldsBackToTheSameVertices) {
  const TriangleMesh mesh = sample_mesh();
  for (const bool ascii : {false, true}) {
    const TriangleMesh back = parse_stl(stl_bytes(mesh, ascii), "m.stl");
    ASSERT_EQ(back.num_triangles(), mesh.num_triangles());
    EXPECT_EQ(back.num_vertices(), mesh.num_vertices()) << ascii;  // welded: every corner shared again
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::Vector3d& original = mesh.positions[mesh.triangles[t][c]];
        Eigen::Vector3d expected = original;
        for (int i = 0; i < 3; ++i) {
          // Binary STL holds floats; volatile keeps the compiler from eliding the round trip.
          volatile float single = static_cast<float>(original[i]);
          if (!ascii) expected[i] = single;
        }
        const Eigen::Vector3d got = back.positions[back.triangles[t][c]];
        for (int i = 0; i < 3; ++i) EXPECT_EQ(got[i], expected[i]) << ascii << " triangle " << t << " corner " << c;
      }
    }
    EXPECT_TRUE(edge_statistics(back).closed_and_oriented());
  }
}

TEST(MeshReader, FilesRoundTripThroughWriteMesh) {
  test_support::TemporaryDirectory tmp;
  const TriangleMesh mesh = sample_mesh();
  for (const char* name : {"a.ply", "b.PLY", "c.obj", "d.stl"}) {
    write_mesh(mesh, tmp / name);
    const TriangleMesh back = read_mesh(tmp / name);
    EXPECT_EQ(back.num_vertices(), mesh.num_vertices()) << name;
    EXPECT_EQ(back.num_triangles(), mesh.num_triangles()) << name;
  }
  EXPECT_THROW(read_mesh(tmp / "missing.ply"), IoError);
  EXPECT_THROW(read_mesh(tmp / "a.3ds"), InvalidInput);
}

TEST(MeshReader, HandWrittenObj) {
  const std::string text =
      "# a quad and a triangle\n"
      "mtllib x.mtl\n"
      "v 0 0 0\r\n"
      "v 1 0 0 1.0\n"
      "v +1 1 0\n"
      "v 0 1 0 0.5 0.5 0.5   # colour\n"
      "vt 0 0\nvn 0 0 1\n"
      "g part_3\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\n"
      "g other\n"
      "f -4//1 -2//1 -1//1\n"
      "o name\ns off\n";
  const TriangleMesh mesh = parse_obj(text, "hand.obj");
  ASSERT_EQ(mesh.num_vertices(), 4u);
  EXPECT_EQ(mesh.positions[2], Eigen::Vector3d(1, 1, 0));
  const std::vector<std::array<int, 3>> triangles{{0, 1, 2}, {0, 2, 3}, {0, 2, 3}};
  EXPECT_EQ(mesh.triangles, triangles);
  EXPECT_EQ(mesh.parts, (std::vector<int>{3, 3, 0}));
}

TEST(MeshReader, ObjErrorsNameFileAndLine) {
  std::string text;
  for (int i = 0; i < 10; ++i) text += "v 0 0 " + std::to_string(i) + "\n";
  EXPECT_EQ(mesh_error_of([&] { parse_obj(text + "\nf 1 2 40\n", "model.obj"); }),
            "model.obj: line 12: face index 40 out of range (the file has 10 vertices)");
  EXPECT_EQ(mesh_error_of([&] { parse_obj(text + "f 1 2\n", "model.obj"); }), "model.obj: line 11: a face needs at least 3 vertices, got 2");
  EXPECT_EQ(mesh_error_of([&] { parse_obj(text + "f 1 0 2\n", "model.obj"); }), "model.obj: line 11: face index 0 (OBJ indices start at 1)");
  EXPECT_EQ(mesh_error_of([&] { parse_obj(text + "f 1 2 -11\n", "model.obj"); }),
            "model.obj: line 11: relative face index -11 reaches before the first vertex (10 vertices so far)");
  EXPECT_EQ(mesh_error_of([&] { parse_obj("v 1 nan 2\n", "model.obj"); }), "model.obj: line 1: expected a finite number, got 'nan'");
  EXPECT_EQ(mesh_error_of([&] { parse_obj("v 1 2\n", "model.obj"); }), "model.obj: line 1: expected three coordinates after 'v'");
  EXPECT_EQ(mesh_error_of([&] { parse_obj("v 1 2 3\nf 1 1 x\n", "model.obj"); }), "model.obj: line 2: expected a vertex index, got 'x'");
  // Forward references are resolved at the end of the file.
  EXPECT_EQ(parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "f.obj").num_triangles(), 1u);
}

// Binary PLY written by hand, big-endian, with float coordinates, an unknown element between
// vertex and face, int32 indices with a ushort count, a pentagon, and an extra face property.
std::string big_endian_ply() {
  std::string s =
      "ply\nformat binary_big_endian 1.0\ncomment hand made\n"
      "element vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
      "element edge 1\nproperty int a\nproperty int b\n"
      "element face 2\nproperty ushort flags\nproperty list ushort int vertex_indices\nproperty char part\n"
      "end_header\n";
  auto put = [&s](auto value) {
    char b[sizeof value];
    std::memcpy(b, &value, sizeof value);
    if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof value);
    s.append(b, sizeof value);
  };
  const float xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1.5f, 1, 0}, {0.5f, 2, 0}, {-0.5f, 1, 0}};
  for (const auto& p : xyz) {
    for (const float c : p) put(c);
    put(std::uint8_t{200});
  }
  put(std::int32_t{0});
  put(std::int32_t{1});
  put(std::uint16_t{7});
  put(std::uint16_t{5});
  for (int i = 0; i < 5; ++i) put(std::int32_t{i});
  put(std::int8_t{-2});
  put(std::uint16_t{7});
  put(std::uint16_t{3});
  for (const int i : {4, 3, 2}) put(std::int32_t{i});
  put(std::int8_t{6});
  return s;
}

TEST(MeshReader, HandWrittenBinaryBigEndianPly) {
  const TriangleMesh mesh = parse_ply(big_endian_ply(), "be.ply");
  ASSERT_EQ(mesh.num_vertices(), 5u);
  EXPECT_EQ(mesh.positions[2], Eigen::Vector3d(1.5, 1, 0));
  const std::vector<std::array<int, 3>> triangles{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {4, 3, 2}};
  EXPECT_EQ(mesh.triangles, triangles);
  EXPECT_EQ(mesh.parts, (std::vector<int>{-2, -2, -2, 6}));
}

TEST(MeshReader, HandWrittenAsciiPlyWithIntegerCoordinatesAndNoParts) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nelement vertex 4\r\nproperty int x\r\nproperty short y\r\nproperty double z\r\n"
      "property float u\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\nend_header\r\n"
      "0 0 0 0.5\r\n1 0 0 0\r\n1 1 0 0\r\n0 1 0.25 0\r\n4 0 1 2 3\r\n";
  const TriangleMesh mesh = parse_ply(text, "a.ply");
  ASSERT_EQ(mesh.num_vertices(), 4u);
  EXPECT_EQ(mesh.positions[3], Eigen::Vector3d(0, 1, 0.25));
  EXPECT_EQ(mesh.parameters[0], Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(mesh.num_triangles(), 2u);
  EXPECT_EQ(mesh.parts, (std::vector<int>{0, 0}));
}

TEST(MeshReader, PlyErrorsNamePlaceAndNeverTrustCounts) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(mesh_error_of([&] { parse_ply(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 40\n", "m.ply"); }),
            "m.ply: line 13 (face 0): vertex index 40 out of range (the file has 3 vertices)");
  EXPECT_EQ(mesh_error_of([&] { parse_ply(header + "0 0 0\n1 0 x\n", "m.ply"); }),
            "m.ply: line 11 (vertex 1): expected a finite number, got 'x'");
  EXPECT_EQ(mesh_error_of([&] { parse_ply(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "m.ply"); }),
            "m.ply: line 13 (face 0): unexpected end of file");
  EXPECT_EQ(mesh_error_of([&] { parse_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n", "m.ply"); }),
            "m.ply: line 3: element vertex has no scalar property y");
  EXPECT_EQ(mesh_error_of([&] { parse_ply("PLY\n", "m.ply"); }), "m.ply: line 1: not a PLY file (the first line must be 'ply')");
  EXPECT_EQ(mesh_error_of([&] { parse_ply("ply\nformat ascii 1.0\n", "m.ply"); }),
            "m.ply: line 3: unexpected end of file in the header (no end_header)");
  // A binary file claiming 10^8 vertices in 48 bytes is rejected before anything is allocated.
  const std::string huge = "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty double x\n"
                           "property double y\nproperty double z\nend_header\n" + std::string(48, '\0');
  EXPECT_NE(mesh_error_of([&] { parse_ply(huge, "m.ply"); }).find("m.ply: line 3: element vertex declares 100000000 items"), std::string::npos);
  // A list length that the remaining bytes cannot hold.
  std::string binary = ply_bytes(test_support::unit_tetrahedron());
  const std::size_t face_start = binary.size() - 4 * 17;
  binary[face_start] = static_cast<char>(250);
  EXPECT_EQ(mesh_error_of([&] { parse_ply(binary, "t.ply"); }),
            "t.ply: byte " + std::to_string(face_start + 1) + " (face 0): unexpected end of file: a list of 250 values does not fit");
  // Truncated binary data names the byte offset.
  const std::string whole = ply_bytes(test_support::unit_tetrahedron());
  EXPECT_NE(mesh_error_of([&] { parse_ply(whole.substr(0, whole.size() - 3), "t.ply"); }).find("t.ply: byte "), std::string::npos);
}

TEST(MeshReader, AsciiStlWithSeveralSolids) {
  const std::string text =
      "solid one\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
      "endsolid one\nsolid two\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 -0\n"
      "  endloop\n endfacet\nendsolid two\n";
  const TriangleMesh mesh = parse_stl(text, "two.stl");
  EXPECT_EQ(mesh.num_vertices(), 4u);  // (0,0,0) and (1,1,0) shared; -0 welds with 0
  EXPECT_EQ(mesh.triangles, (std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(mesh_error_of([&] { parse_stl("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0\n", "bad.stl"); }),
            "bad.stl: line 4: unexpected end of file, expected a number");
  EXPECT_EQ(mesh_error_of([&] { parse_stl("solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n endloop\n", "bad.stl"); }),
            "bad.stl: line 5: a facet needs at least 3 vertices, got 1");
}

TEST(MeshReader, BinaryStlCountsAreCheckedAgainstTheSize) {
  std::string bytes = stl_bytes(test_support::unit_cube());
  EXPECT_EQ(parse_stl(bytes, "c.stl").num_vertices(), 8u);
  EXPECT_EQ(mesh_error_of([&] { parse_stl(bytes.substr(0, bytes.size() - 1), "c.stl"); }),
            "c.stl: byte 80: the header declares 12 triangles (684 bytes), the file has only 683 bytes");
  EXPECT_EQ(mesh_error_of([&] { parse_stl("abc", "c.stl"); }), "c.stl: byte 3: a binary STL file needs an 84-byte header, the file has 3 bytes");
  // A binary file whose header begins with "solid" is still read as binary when its size fits.
  bytes.replace(0, 5, "solid");
  EXPECT_EQ(parse_stl(bytes, "c.stl").num_triangles(), 12u);
}

}  // namespace
}  // namespace volspline

namespace volspline {
namespace {

// OFF, as CGAL's data files and Debian's mesh packages ship it: a closed tetrahedron with a
// quad-free face list, comments and colours after the indices; polygons become fans.
TEST(MeshReader, OffGivesTheTrianglesOfItsFacesAndLocatedErrors) {
  const TriangleMesh tet = parse_off("OFF\n# a tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3 255 0 0\n3 0 3 2\n3 1 2 3\n", "t.off");
  ASSERT_EQ(tet.num_vertices(), 4u);
  ASSERT_EQ(tet.num_triangles(), 4u);
  EXPECT_TRUE(edge_statistics(tet).closed_and_oriented());
  EXPECT_NEAR(enclosed_volume(tet), 1.0 / 6.0, 1e-15);
  const TriangleMesh quad = parse_off("OFF 4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", "q.off");
  EXPECT_EQ(quad.num_triangles(), 2u);
  EXPECT_NEAR(surface_area(quad), 1.0, 1e-15);
  const auto error = [](std::string_view text) {
    try {
      parse_off(text, "e.off");
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(error("PLY\n").find("e.off: line 1: expected the header OFF"), std::string::npos);
  EXPECT_NE(error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").find("e.off: line 6: expected a vertex index"), std::string::npos);
  EXPECT_NE(error("OFF\n3 1 0\n0 0 0\n1 0 x\n").find("e.off: line 4: expected a vertex coordinate"), std::string::npos);
  EXPECT_NE(error("OFF\n99999999 0 0\n").find("line 2: expected the vertex count"), std::string::npos);
  EXPECT_NE(error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n").find("line 6: expected a face of 3 or more vertices"), std::string::npos);
}

}  // namespace
}  // namespace volspline
