// The range of coordinates for every input that is not a model or a scene (issue 16): triangle
// meshes (OBJ, PLY, STL, OFF), tetrahedral meshes (medit, TetGen, legacy VTK), volume data (CSV,
// PLY, legacy VTK), point files and skeleton files all refuse a magnitude beyond 2^200 and an
// extent below 2^-200 at read time, naming the file and the place, and accept the exact ends of
// the range (core/coordinate_range.h). Models and scenes: tests/io/coordinate_range_test.cpp,
// tests/boxspline/scene_file_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "support/cli_runner.h"
#include "support/invalid_input_message.h"
#include "support/temporary_directory.h"
#include "volspline/core/coordinate_range.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/point_file.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/io/volume_data.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/tetrahedral_mesh_reader.h"

namespace volspline {
namespace {

bool says(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void write_input_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

using Corners = std::vector<Eigen::Vector3d>;

std::string xyz_text(const Eigen::Vector3d& p, const char* separator = " ") {
  return format_double(p.x()) + separator + format_double(p.y()) + separator + format_double(p.z());
}

// One reader: the files (name, text) holding a tetrahedron's four corners, the file to read,
// how to read it and the place its first corner's x is named at.
struct RangeReader {
  std::string name;
  std::function<std::vector<std::pair<std::string, std::string>>(const Corners&)> files;
  std::string read_name;
  std::function<void(const std::filesystem::path&)> read;
  std::string place_of_vertex_1_x;  // where corner 1 (the second) x is reported
};

std::vector<RangeReader> range_readers() {
  const auto mesh_read = [](const std::filesystem::path& p) { read_mesh(p); };
  const auto tet_read = [](const std::filesystem::path& p) { read_tetrahedral_mesh(p); };
  const auto volume_read = [](const std::filesystem::path& p) { read_volume_data(p); };
  const auto faces = [](const char* prefix) {
    return std::string(prefix) + "1 2 3\n" + prefix + "1 2 4\n" + prefix + "1 3 4\n" + prefix + "2 3 4\n";
  };
  std::vector<RangeReader> readers;
  readers.push_back({"obj", [faces](const Corners& c) {
                       std::string t;
                       for (const auto& p : c) t += "v " + xyz_text(p) + "\n";
                       return std::vector<std::pair<std::string, std::string>>{{"in.obj", t + faces("f ")}};
                     }, "in.obj", mesh_read, "in.obj: vertex 2 of 4, x"});
  readers.push_back({"ply", [](const Corners& c) {
                       std::string t = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                                       "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
                       for (const auto& p : c) t += xyz_text(p) + "\n";
                       t += "3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";
                       return std::vector<std::pair<std::string, std::string>>{{"in.ply", t}};
                     }, "in.ply", mesh_read, "in.ply: vertex 2 of 4, x"});
  readers.push_back({"stl", [](const Corners& c) {
                       std::string t = "solid s\n";
                       for (const auto& f : std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}) {
                         t += "facet normal 0 0 0\nouter loop\n";
                         for (int v : f) t += "vertex " + xyz_text(c[static_cast<std::size_t>(v)]) + "\n";
                         t += "endloop\nendfacet\n";
                       }
                       return std::vector<std::pair<std::string, std::string>>{{"in.stl", t + "endsolid s\n"}};
                     }, "in.stl", mesh_read, "in.stl: vertex 2 of 4, x"});
  readers.push_back({"off", [](const Corners& c) {
                       std::string t = "OFF\n4 4 0\n";
                       for (const auto& p : c) t += xyz_text(p) + "\n";
                       t += "3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";
                       return std::vector<std::pair<std::string, std::string>>{{"in.off", t}};
                     }, "in.off", mesh_read, "in.off: vertex 2 of 4, x"});
  readers.push_back({"medit", [](const Corners& c) {
                       std::string t = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n";
                       for (const auto& p : c) t += xyz_text(p) + " 0\n";
                       return std::vector<std::pair<std::string, std::string>>{{"in.mesh", t + "Tetrahedra\n1\n1 2 3 4 1\nEnd\n"}};
                     }, "in.mesh", tet_read, "in.mesh: line 6 (point 1), x"});
  readers.push_back({"tetgen", [](const Corners& c) {
                       std::string node = "4 3 0 0\n";
                       for (std::size_t i = 0; i < c.size(); ++i) node += std::to_string(i + 1) + " " + xyz_text(c[i]) + "\n";
                       return std::vector<std::pair<std::string, std::string>>{{"in.node", node}, {"in.ele", "1 4 0\n1 1 2 3 4\n"}};
                     }, "in.ele", tet_read, "in.node: line 3 (point 1), x"});
  const auto legacy_vtk = [](const Corners& c) {
    std::string t = "# vtk DataFile Version 3.0\nrange\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n";
    for (const auto& p : c) t += xyz_text(p) + "\n";
    return t + "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS value double 1\nLOOKUP_TABLE default\n0 1 2 3\n";
  };
  readers.push_back({"vtk tetrahedra", [=](const Corners& c) {
                       return std::vector<std::pair<std::string, std::string>>{{"tet.vtk", legacy_vtk(c)}};
                     }, "tet.vtk", tet_read, "tet.vtk: point 1, x"});
  readers.push_back({"csv volume data", [](const Corners& c) {
                       std::string t = "x,y,z,value\n";
                       for (std::size_t i = 0; i < c.size(); ++i) t += xyz_text(c[i], ",") + "," + std::to_string(i) + "\n";
                       return std::vector<std::pair<std::string, std::string>>{{"data.csv", t}};
                     }, "data.csv", volume_read, "data.csv: point 1, x"});
  readers.push_back({"ply volume data", [](const Corners& c) {
                       std::string t = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                                       "property double value\nend_header\n";
                       for (std::size_t i = 0; i < c.size(); ++i) t += xyz_text(c[i]) + " " + std::to_string(i) + "\n";
                       return std::vector<std::pair<std::string, std::string>>{{"data.ply", t}};
                     }, "data.ply", volume_read, "data.ply: point 1, x"});
  readers.push_back({"vtk volume data", [=](const Corners& c) {
                       return std::vector<std::pair<std::string, std::string>>{{"data.vtk", legacy_vtk(c)}};
                     }, "data.vtk", volume_read, "data.vtk: point 1, x"});
  readers.push_back({"point file", [](const Corners& c) {
                       std::string t = "x y z\n";
                       for (const auto& p : c) t += xyz_text(p, ", ") + "\n";
                       return std::vector<std::pair<std::string, std::string>>{{"points.csv", t}};
                     }, "points.csv", [](const std::filesystem::path& p) { read_points(p); }, "points.csv: line 3, x"});
  readers.push_back({"skeleton file", [](const Corners& c) {
                       std::string t = R"({"volspline_skeleton": 1, "elements": [{"kind": "polyline", "points": [)";
                       for (std::size_t i = 0; i < c.size(); ++i) t += std::string(i ? ", " : "") + "[" + xyz_text(c[i], ", ") + "]";
                       return std::vector<std::pair<std::string, std::string>>{{"skeleton.json", t + "]}]}"}};
                     }, "skeleton.json", [](const std::filesystem::path& p) { read_skeleton(p); }, "skeleton.json: elements[0].points[1][0]"});
  return readers;
}

// A right-angled tetrahedron with legs `size` along +x, -y, +z from `origin`.
Corners range_tetrahedron(double size, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
  return {origin, origin + Eigen::Vector3d(size, 0, 0), origin + Eigen::Vector3d(0, -size, 0), origin + Eigen::Vector3d(0, 0, size)};
}

std::string range_message(const RangeReader& reader, const std::filesystem::path& dir, const Corners& corners) {
  for (const auto& [name, text] : reader.files(corners)) write_input_file(dir / name, text);
  return test_support::invalid_input_message([&] { reader.read(dir / reader.read_name); });
}

void expect_read(const RangeReader& reader, const std::filesystem::path& dir, const Corners& corners) {
  for (const auto& [name, text] : reader.files(corners)) write_input_file(dir / name, text);
  EXPECT_NO_THROW(reader.read(dir / reader.read_name)) << reader.name << " " << xyz_text(corners[1]);
}

TEST(InputCoordinateRange, EveryReaderAcceptsTheEndsOfTheRange) {
  test_support::TemporaryDirectory dir;
  for (const RangeReader& reader : range_readers()) {
    expect_read(reader, dir.path(), range_tetrahedron(kMaxCoordinate));                                        // ±2^200
    expect_read(reader, dir.path(), range_tetrahedron(kMinExtent));                                            // extent 2^-200
    expect_read(reader, dir.path(), range_tetrahedron(0x1p-100, Eigen::Vector3d(-1, 2, 3) * 0x1p-96));  // small, off 0
  }
}

TEST(InputCoordinateRange, EveryReaderRefusesMagnitudesBeyondTheRangeNamingFileAndPlace) {
  test_support::TemporaryDirectory dir;
  for (const RangeReader& reader : range_readers()) {
    for (const double x : {std::nextafter(kMaxCoordinate, HUGE_VAL), -std::nextafter(kMaxCoordinate, HUGE_VAL), 1e300, -1.7e308}) {
      Corners corners = range_tetrahedron(1);
      corners[1].x() = x;
      const std::string message = range_message(reader, dir.path(), corners);
      EXPECT_TRUE(says(message, reader.place_of_vertex_1_x)) << reader.name << " " << x << ": " << message;
      EXPECT_TRUE(says(message, "expected a coordinate of magnitude at most 2^200")) << reader.name << ": " << message;
      EXPECT_TRUE(says(message, "Range of coordinates")) << reader.name << ": " << message;
    }
  }
}

TEST(InputCoordinateRange, EveryReaderRefusesExtentsBelowTheRangeNamingTheFile) {
  test_support::TemporaryDirectory dir;
  for (const RangeReader& reader : range_readers()) {
    for (const double size : {std::nextafter(kMinExtent, 0.0), 1e-250, 4.9e-324}) {
      // (The point file's reader refuses subnormal numbers as numbers: strtod's ERANGE.)
      if (reader.name == "point file" && size < 0x1p-1022) continue;
      for (const Eigen::Vector3d& origin : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-1e-280, 0, 1e-290)}) {
        const std::string message = range_message(reader, dir.path(), range_tetrahedron(size, origin));
        EXPECT_TRUE(says(message, "spanning at least 2^-200"))
            << reader.name << " " << size << ": " << message;
        // The file holding the points (TetGen's .node) is named.
        const std::string file = reader.name == "tetgen" ? "in.node" : reader.read_name;
        EXPECT_TRUE(says(message, file)) << reader.name << ": " << message;
      }
    }
  }
}

TEST(InputCoordinateRange, SkeletonLengthsAndCurvesFollowTheRange) {
  const auto skeleton = [](const std::string& element) {
    return R"({"volspline_skeleton": 1, "elements": [)" + element + "]}";
  };
  const auto ellipsoid = [&](double a) {
    return skeleton(R"({"kind": "ellipsoid", "centre": [0, 0, 0], "semi_axes": [1, )" + format_double(a) + ", 1]}");
  };
  EXPECT_NO_THROW(parse_skeleton(ellipsoid(kMinExtent), "sk.json"));
  EXPECT_NO_THROW(parse_skeleton(ellipsoid(kMaxCoordinate), "sk.json"));
  for (const double a : {std::nextafter(kMinExtent, 0.0), std::nextafter(kMaxCoordinate, HUGE_VAL)}) {
    const std::string message = test_support::invalid_input_message([&] { parse_skeleton(ellipsoid(a), "sk.json"); });
    EXPECT_TRUE(says(message, "sk.json: elements[0].semi_axes[1]: expected a semi-axis between 2^-200 and 2^200")) << message;
  }
  const auto falloff = [&](const std::string& f) {
    return skeleton(R"({"kind": "point", "points": [[0, 0, 0]], "falloff": )" + f + "}");
  };
  EXPECT_TRUE(says(test_support::invalid_input_message([&] { parse_skeleton(falloff(R"({"kind": "inverse_square", "scale": 1e-250})"), "sk.json"); }),
                   "elements[0].falloff.scale: expected a scale between 2^-200 and 2^200"));
  EXPECT_TRUE(says(test_support::invalid_input_message([&] { parse_skeleton(falloff(R"({"kind": "polynomial", "coefficients": [1], "radius": 1e250})"), "sk.json"); }),
                   "elements[0].falloff.radius: expected a radius between 2^-200 and 2^200"));
  const std::string curve = skeleton(R"({"kind": "curve", "curve": {"type": "bezier_curve", "degree": [1], "control_points": [[0, 0, 0], [1e61, 0, 0]]}})");
  EXPECT_TRUE(says(test_support::invalid_input_message([&] { parse_skeleton(curve, "sk.json"); }),
                   "sk.json: elements[0].curve.control_points[1][0]: expected a coordinate of magnitude at most 2^200"));
  const std::string centre = skeleton(R"({"kind": "ellipsoid", "centre": [0, -1e200, 0], "semi_axes": [1, 1, 1]})");
  EXPECT_TRUE(says(test_support::invalid_input_message([&] { parse_skeleton(centre, "sk.json"); }),
                   "sk.json: elements[0].centre[1]: expected a coordinate of magnitude at most 2^200"));
}

TEST(InputCoordinateRange, CommandsReadingMeshesDataPointsAndSkeletonsExitTwoAndWriteNothing) {
  test_support::TemporaryDirectory dir;
  const auto at = [&](const char* name) { return (dir.path() / name).string(); };
  Corners huge = range_tetrahedron(1);
  huge[1].x() = 1e250;
  const auto readers = range_readers();
  const auto reader_named = [&](const std::string& name) -> const RangeReader& {
    for (const RangeReader& r : readers) if (r.name == name) return r;
    throw std::logic_error(name);
  };
  const auto write_for = [&](const std::string& reader, const Corners& corners, const std::string& as) {
    write_input_file(dir.path() / as, reader_named(reader).files(corners).front().second);
  };
  write_for("obj", range_tetrahedron(1), "ok.obj");
  write_for("obj", huge, "huge.obj");
  write_for("off", huge, "huge.off");
  write_for("point file", huge, "huge_points.csv");
  write_for("medit", huge, "huge.mesh");
  write_for("medit", range_tetrahedron(1), "ok.mesh");
  write_for("csv volume data", huge, "huge_data.csv");
  write_for("skeleton file", huge, "huge_skeleton.json");
  ASSERT_EQ(test_support::run_cli("lattice " + at("ok.obj") + " --degree 1,1,1 -o " + at("lattice.json"), dir.path()).code, 0);
  struct Case {
    std::string command, file, output;
  };
  const std::vector<Case> cases{
      {"lattice " + at("huge.obj") + " --degree 1,1,1 -o " + at("out1.json"), "huge.obj: vertex 2 of 4, x", "out1.json"},
      {"ffd " + at("lattice.json") + " " + at("huge.obj") + " -o " + at("out2.obj"), "huge.obj: vertex 2 of 4, x", "out2.obj"},
      {"make simplex-spline --surface " + at("huge.off") + " --degree 1 -o " + at("out3.json"), "huge.off: vertex 2 of 4, x", "out3.json"},
      {"make simplex-spline --points " + at("huge_points.csv") + " --degree 1 -o " + at("out4.json"), "huge_points.csv: line 3, x", "out4.json"},
      {"make simplex-spline --tetrahedra " + at("huge.mesh") + " --degree 1 -o " + at("out5.json"), "huge.mesh: line 6 (point 1), x", "out5.json"},
      {"fit " + at("huge_data.csv") + " --degree 1 -o " + at("out6.json"), "huge_data.csv: point 1, x", "out6.json"},
      {"make simplex-spline --tetrahedra " + at("ok.mesh") + " --degree 1 --skeleton " + at("huge_skeleton.json") + " -o " + at("out7.json"),
       "huge_skeleton.json: elements[0].points[1][0]", "out7.json"},
  };
  for (const Case& c : cases) {
    const auto result = test_support::run_cli(c.command, dir.path());
    EXPECT_EQ(result.code, 2) << c.command << ": " << result.err;
    EXPECT_TRUE(says(result.err, c.file)) << c.command << ": " << result.err;
    EXPECT_TRUE(says(result.err, "at most 2^200")) << c.command << ": " << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / c.output)) << c.command;
  }
}

}  // namespace
}  // namespace volspline
