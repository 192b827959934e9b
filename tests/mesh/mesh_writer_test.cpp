#include "volspline/mesh/mesh_writer.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <locale>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"
#include "support/test_meshes.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline {
namespace {

using test_support::TemporaryDirectory;

// A reader for exactly the PLY layout volspline writes, independent of the writer's code, so a
// round trip checks the bytes against the format rather than against themselves.
TriangleMesh parse_ply(const std::string& bytes) {
  const std::string end = "end_header\n";
  const std::size_t body = bytes.find(end);
  if (body == std::string::npos) throw std::runtime_error("no end_header");
  std::istringstream header(bytes.substr(0, body));
  std::string line, format;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> properties;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> format;
    } else if (word == "element") {
      std::string name;
      std::size_t count;
      words >> name >> count;
      (name == "vertex" ? vertices : faces) = count;
    } else if (word == "property") {
      properties.push_back(line);
    }
  }
  const std::vector<std::string> expected = {"property double x",
                                             "property double y",
                                             "property double z",
                                             "property double u",
                                             "property double v",
                                             "property double w",
                                             "property list uchar int vertex_indices",
                                             "property int part"};
  if (properties != expected) throw std::runtime_error("unexpected properties");

  TriangleMesh mesh;
  mesh.positions.resize(vertices);
  mesh.parameters.resize(vertices);
  mesh.triangles.resize(faces);
  mesh.parts.resize(faces);
  const std::size_t start = body + end.size();
  if (format == "ascii") {
    std::istringstream in(bytes.substr(start));
    std::string token;
    // strtod rather than operator>>: libstdc++ streams reject subnormal numbers.
    const auto number = [&] {
      in >> token;
      return std::strtod(token.c_str(), nullptr);
    };
    for (std::size_t v = 0; v < vertices; ++v) {
      for (int i = 0; i < 3; ++i) mesh.positions[v][i] = number();
      for (int i = 0; i < 3; ++i) mesh.parameters[v][i] = number();
    }
    for (std::size_t f = 0; f < faces; ++f) {
      int n = 0;
      in >> n;
      if (n != 3) throw std::runtime_error("not a triangle");
      in >> mesh.triangles[f][0] >> mesh.triangles[f][1] >> mesh.triangles[f][2] >> mesh.parts[f];
    }
    if (!in) throw std::runtime_error("truncated ascii body");
    in >> token;
    if (in) throw std::runtime_error("trailing data");
    return mesh;
  }
  if (format != "binary_little_endian") throw std::runtime_error("unexpected format " + format);
  static_assert(std::endian::native == std::endian::little, "the test reads host-endian bytes");
  if (bytes.size() != start + 48 * vertices + 17 * faces) throw std::runtime_error("bad size");
  const char* p = bytes.data() + start;
  const auto take = [&p](auto& value) {
    std::memcpy(&value, p, sizeof value);
    p += sizeof value;
  };
  for (std::size_t v = 0; v < vertices; ++v) {
    for (int i = 0; i < 3; ++i) take(mesh.positions[v][i]);
    for (int i = 0; i < 3; ++i) take(mesh.parameters[v][i]);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    std::uint8_t n = 0;
    take(n);
    if (n != 3) throw std::runtime_error("not a triangle");
    for (int i = 0; i < 3; ++i) {
      std::int32_t index;
      take(index);
      mesh.triangles[f][i] = index;
    }
    std::int32_t part;
    take(part);
    mesh.parts[f] = part;
  }
  return mesh;
}

// Numbers that break careless formatting: too many digits for %g, subnormal, huge, negative
// zero, and values that are not short decimals.
TriangleMesh awkward_mesh() {
  TriangleMesh mesh = test_support::unit_tetrahedron();
  std::mt19937_64 random(20240611);
  std::uniform_real_distribution<double> uniform(-1, 1);
  const double specials[] = {0.1,
                             1.0 / 3,
                             -0.0,
                             5e-324,
                             2.2250738585072014e-308,
                             1.7976931348623157e308,
                             -123456789.123456789,
                             1e-17};
  std::size_t next = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) {
      mesh.positions[v][i] = next < std::size(specials) ? specials[next++] : uniform(random);
      mesh.parameters[v][i] = uniform(random) * 1e3;
    }
  }
  mesh.parts = {0, 6, 3, 5};
  return mesh;
}

void expect_same_mesh(const TriangleMesh& expected, const TriangleMesh& actual) {
  ASSERT_EQ(expected.num_vertices(), actual.num_vertices());
  ASSERT_EQ(expected.num_triangles(), actual.num_triangles());
  for (std::size_t v = 0; v < expected.num_vertices(); ++v) {
    for (int i = 0; i < 3; ++i) {
      // Bitwise, so that -0.0 versus 0.0 would count as a difference.
      EXPECT_EQ(std::bit_cast<std::uint64_t>(expected.positions[v][i]),
                std::bit_cast<std::uint64_t>(actual.positions[v][i]))
          << "position " << v << "." << i << ": " << expected.positions[v][i] << " vs "
          << actual.positions[v][i];
      EXPECT_EQ(expected.parameters[v][i], actual.parameters[v][i]);
    }
  }
  EXPECT_EQ(expected.triangles, actual.triangles);
  EXPECT_EQ(expected.parts, actual.parts);
}

std::size_t count_lines_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) n += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

TEST(MeshFormat, IsTakenFromTheExtensionInAnyCase) {
  EXPECT_EQ(mesh_format_from_path("a/b/solid.ply"), MeshFormat::Ply);
  EXPECT_EQ(mesh_format_from_path("solid.PLY"), MeshFormat::Ply);
  EXPECT_EQ(mesh_format_from_path("solid.Obj"), MeshFormat::Obj);
  EXPECT_EQ(mesh_format_from_path("x.y.stl"), MeshFormat::Stl);
}

TEST(MeshFormat, UnknownExtensionNamesThePathAndTheAlternatives) {
  for (const char* path : {"solid.off", "solid", "dir.ply/solid", ".ply"}) {
    try {
      mesh_format_from_path(path);
      ADD_FAILURE() << "no exception for " << path;
    } catch (const InvalidInput& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      for (const char* extension : {".ply", ".obj", ".stl"}) {
        EXPECT_NE(message.find(extension), std::string::npos) << message;
      }
    }
  }
}

TEST(Ply, BinaryRoundTripsEveryBitOfPositionsParametersAndParts) {
  const TriangleMesh mesh = awkward_mesh();
  const std::string bytes = ply_bytes(mesh);
  EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  expect_same_mesh(mesh, parse_ply(bytes));
}

TEST(Ply, AsciiRoundTripsEveryBitOfPositionsParametersAndParts) {
  const TriangleMesh mesh = awkward_mesh();
  const std::string bytes = ply_bytes(mesh, true);
  EXPECT_EQ(bytes.rfind("ply\nformat ascii 1.0\n", 0), 0u);
  expect_same_mesh(mesh, parse_ply(bytes));
}

struct DecimalComma : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
};

TEST(Ply, AsciiDoesNotDependOnTheGlobalLocale) {
  // A global locale with a decimal comma (as in German) must not leak into the file.
  const std::locale previous =
      std::locale::global(std::locale(std::locale::classic(), new DecimalComma));
  std::string bytes;
  try {
    bytes = ply_bytes(awkward_mesh(), true);
  } catch (...) {
    std::locale::global(previous);
    throw;
  }
  std::locale::global(previous);
  EXPECT_EQ(bytes, ply_bytes(awkward_mesh(), true));
  EXPECT_EQ(bytes.find(',', bytes.find("end_header")), std::string::npos);
}

TEST(Ply, EmptyMeshIsAValidFile) {
  for (const bool ascii : {false, true}) {
    const std::string bytes = ply_bytes(TriangleMesh{}, ascii);
    EXPECT_NE(bytes.find("element vertex 0\n"), std::string::npos);
    EXPECT_NE(bytes.find("element face 0\n"), std::string::npos);
    expect_same_mesh(TriangleMesh{}, parse_ply(bytes));
  }
}

TEST(Obj, HasOneBasedFacesGroupedByPartAndExactPositions) {
  TriangleMesh mesh = test_support::unit_cube();
  mesh.positions[7] = {1.0 / 3, 0.1, 1e-300};
  // Interleave parts so grouping has something to do.
  std::reverse(mesh.parts.begin(), mesh.parts.end());
  const std::string text = obj_bytes(mesh);

  std::istringstream in(text);
  std::string line;
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::tuple<int, int, int, int>> faces;
  std::vector<int> groups;
  int group = -1;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      std::string x, y, z;
      words >> x >> y >> z;
      positions.emplace_back(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                             std::strtod(z.c_str(), nullptr));
    } else if (tag == "g") {
      std::string name;
      words >> name;
      ASSERT_EQ(name.rfind("part_", 0), 0u) << name;
      group = std::stoi(name.substr(5));
      groups.push_back(group);
    } else if (tag == "f") {
      int a, b, c;
      words >> a >> b >> c;
      faces.emplace_back(a - 1, b - 1, c - 1, group);
    } else {
      EXPECT_TRUE(tag.empty() || tag[0] == '#') << line;
    }
  }
  EXPECT_EQ(positions, mesh.positions);
  EXPECT_EQ(groups, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  std::vector<std::tuple<int, int, int, int>> expected;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto& tri = mesh.triangles[t];
    expected.emplace_back(tri[0], tri[1], tri[2], mesh.parts[t]);
  }
  std::sort(expected.begin(), expected.end());
  std::sort(faces.begin(), faces.end());
  EXPECT_EQ(faces, expected);
}

TEST(Stl, BinaryHas84PlusFiftyBytesPerTriangleAndOutwardNormals) {
  const TriangleMesh cube = test_support::unit_cube();
  const std::string bytes = stl_bytes(cube);
  ASSERT_EQ(bytes.size(), 84 + 50 * cube.num_triangles());
  EXPECT_NE(bytes.rfind("solid", 0), 0u) << "binary STL must not look like ASCII STL";
  std::uint32_t count;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, cube.num_triangles());
  for (std::size_t t = 0; t < cube.num_triangles(); ++t) {
    float record[12];
    std::memcpy(record, bytes.data() + 84 + 50 * t, sizeof record);
    const Eigen::Vector3f normal(record[0], record[1], record[2]);
    // The outward normal of a unit cube face points away from the centre (0.5, 0.5, 0.5).
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3f corner(record[3 + 3 * i], record[4 + 3 * i], record[5 + 3 * i]);
      EXPECT_EQ(corner, cube.positions[cube.triangles[t][i]].cast<float>());
      centroid += corner / 3;
    }
    EXPECT_FLOAT_EQ(normal.norm(), 1.0f);
    EXPECT_GT(normal.dot(centroid - Eigen::Vector3f::Constant(0.5f)), 0.0f);
  }
}

TEST(Stl, AsciiListsOneFacetPerTriangle) {
  const TriangleMesh sphere = test_support::icosphere(1);
  const std::string text = stl_bytes(sphere, true);
  EXPECT_EQ(text.rfind("solid volspline\n", 0), 0u);
  EXPECT_TRUE(text.ends_with("endsolid volspline\n"));
  EXPECT_EQ(count_lines_starting(text, "  facet normal "), sphere.num_triangles());
  EXPECT_EQ(count_lines_starting(text, "      vertex "), 3 * sphere.num_triangles());
  EXPECT_EQ(count_lines_starting(text, "  endfacet"), sphere.num_triangles());
}

TEST(Stl, DegenerateTriangleGetsAZeroNormal) {
  TriangleMesh mesh;
  mesh.add_vertex({0, 0, 0}, {0, 0, 0});
  mesh.add_vertex({1, 1, 1}, {0, 0, 0});
  mesh.add_triangle(0, 1, 1, 0);
  const std::string bytes = stl_bytes(mesh);
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof normal);
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], 0.0f);
}

TEST(WriteMesh, DispatchesOnTheExtensionAndWritesTheSameBytes) {
  const TemporaryDirectory dir;
  const TriangleMesh cube = test_support::unit_cube();
  write_mesh(cube, dir / "cube.PLY");
  EXPECT_EQ(read_file(dir / "cube.PLY"), ply_bytes(cube));
  write_mesh(cube, dir / "cube.ply", {.ascii = true});
  EXPECT_EQ(read_file(dir / "cube.ply"), ply_bytes(cube, true));
  write_mesh(cube, dir / "cube.obj");
  EXPECT_EQ(read_file(dir / "cube.obj"), obj_bytes(cube));
  write_mesh(cube, dir / "cube.stl");
  EXPECT_EQ(read_file(dir / "cube.stl"), stl_bytes(cube));
  write_stl(cube, dir / "cube_ascii.stl", true);
  EXPECT_EQ(read_file(dir / "cube_ascii.stl"), stl_bytes(cube, true));
  EXPECT_EQ(dir.entries(), 5u);
}

TEST(WriteMesh, ReplacesAnExistingFile) {
  const TemporaryDirectory dir;
  write_file_atomically(dir / "out.ply", "old contents that are longer than nothing");
  write_ply(TriangleMesh{}, dir / "out.ply");
  EXPECT_EQ(read_file(dir / "out.ply"), ply_bytes(TriangleMesh{}));
  EXPECT_EQ(dir.entries(), 1u);
}

TEST(WriteMesh, MissingDirectoryThrowsIoErrorAndLeavesNothing) {
  const TemporaryDirectory dir;
  for (const char* name : {"missing/cube.ply", "missing/cube.obj", "missing/cube.stl"}) {
    EXPECT_THROW(write_mesh(test_support::unit_cube(), dir / name), IoError) << name;
  }
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(WriteMesh, UnknownExtensionThrowsInvalidInputBeforeCreatingAFile) {
  const TemporaryDirectory dir;
  EXPECT_THROW(write_mesh(test_support::unit_cube(), dir / "cube.off"), InvalidInput);
  EXPECT_EQ(dir.entries(), 0u);
}

TEST(WriteMesh, MalformedMeshIsRejectedWithoutWriting) {
  const TemporaryDirectory dir;
  TriangleMesh bad_index = test_support::unit_cube();
  bad_index.triangles[3][1] = 8;
  TriangleMesh missing_parts = test_support::unit_cube();
  missing_parts.parts.pop_back();
  TriangleMesh missing_parameters = test_support::unit_cube();
  missing_parameters.parameters.pop_back();
  TriangleMesh not_finite = test_support::unit_cube();
  not_finite.positions[2].y() = std::numeric_limits<double>::quiet_NaN();
  for (const TriangleMesh* mesh : {&bad_index, &missing_parts, &missing_parameters, &not_finite}) {
    for (const char* name : {"bad.ply", "bad.obj", "bad.stl"}) {
      EXPECT_THROW(write_mesh(*mesh, dir / name), InvalidInput) << name;
    }
  }
  EXPECT_EQ(dir.entries(), 0u);
}

}  // namespace
}  // namespace volspline
