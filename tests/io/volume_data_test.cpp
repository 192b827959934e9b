#include "volspline/io/volume_data.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"
#include "support/tetrahedral_domains.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using test_support::TemporaryDirectory;

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no InvalidInput)";
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

template <class T>
void append(std::string& bytes, T value, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  bytes.append(b, sizeof(T));
}

TEST(VolumeData, CsvColumnsInAnyOrderBecomePointsAndAttributes) {
  const VolumeData d = parse_volume_csv("# comment\n density, z ,x,y,temperature\n1.5,3,1,2,-4\n\n2.5,6,4,5,1e-3\n", "a.csv");
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d.points[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(d.points[1], Eigen::Vector3d(4, 5, 6));
  ASSERT_EQ(d.attribute_names, (std::vector<std::string>{"density", "temperature"}));
  EXPECT_EQ(d.attributes(0, 0), 1.5);
  EXPECT_EQ(d.attributes(1, 1), 1e-3);
  EXPECT_EQ(d.attribute_column("temperature"), 1);
  const VolumeData t = select_attributes(d, {"temperature"});
  EXPECT_EQ(t.attribute_names, std::vector<std::string>{"temperature"});
  EXPECT_EQ(t.attributes(0, 0), -4);
  // A spreadsheet's export: a UTF-8 byte order mark before the header, quoted names and numbers.
  const VolumeData q = parse_volume_csv("\xEF\xBB\xBF\"x\",\"y\",\"z\",\"t\"\n\"1\",\" 2 \",3,\"4.5\"\n", "q.csv");
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q.points[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(q.attribute_names, std::vector<std::string>{"t"});
  EXPECT_EQ(q.attributes(0, 0), 4.5);
  EXPECT_NE(error_of([] { parse_volume_csv("x,y,z\n\"1\",\"two\",3\n", "w.csv"); }).find("column 'y'"), std::string::npos);
}

TEST(VolumeData, CsvErrorsNameTheLineAndTheColumn) {
  EXPECT_NE(error_of([] { parse_volume_csv("x,y,d\n1,2,3\n", "a.csv"); }).find("a.csv: line 1: the header has no column z"), std::string::npos);
  EXPECT_NE(error_of([] { parse_volume_csv("x,y,z,d\n1,2,3,4\n1,2,3\n", "a.csv"); }).find("a.csv: line 3: expected 4 fields"), std::string::npos);
  const std::string nan = error_of([] { parse_volume_csv("x,y,z,d\n1,2,3,nan\n", "a.csv"); });
  EXPECT_NE(nan.find("a.csv: line 2: column 'd': expected a finite number, got 'nan'"), std::string::npos) << nan;
  EXPECT_NE(error_of([] { parse_volume_csv("1,2,3\n", "a.csv"); }).find("expected a header"), std::string::npos);
  EXPECT_NE(error_of([] { parse_volume_csv("x,y,z\n", "a.csv"); }).find("at least one point"), std::string::npos);
  EXPECT_NE(error_of([] { select_attributes(parse_volume_csv("x,y,z,d\n1,2,3,4\n", "a.csv"), {"e"}); }).find("(the data has: d)"),
            std::string::npos);
}

TEST(VolumeData, PlyAsciiAndBinaryGiveTheSameVertexProperties) {
  const std::string header_tail =
      "element vertex 2\nproperty float x\nproperty float y\nproperty float z\nproperty double temperature\n"
      "property list uchar int extra\nproperty uchar label\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ascii = "ply\nformat ascii 1.0\ncomment c\n" + header_tail + "1 2 3 0.25 2 7 8 9\n-1 -2 -3 -0.5 0 200\n3 0 1 1\n";
  std::string binary = "ply\nformat binary_little_endian 1.0\n" + header_tail;
  const float xyz[2][3] = {{1, 2, 3}, {-1, -2, -3}};
  const double temperature[2] = {0.25, -0.5};
  const unsigned char label[2] = {9, 200};
  for (int v = 0; v < 2; ++v) {
    for (float c : xyz[v]) append(binary, c);
    append(binary, temperature[v]);
    append(binary, static_cast<unsigned char>(v == 0 ? 2 : 0));
    if (v == 0) append(binary, std::int32_t{7}), append(binary, std::int32_t{8});
    append(binary, label[v]);
  }
  append(binary, static_cast<unsigned char>(3));
  for (std::int32_t i : {0, 1, 1}) append(binary, i);
  for (const std::string& bytes : {ascii, binary}) {
    const VolumeData d = parse_volume_ply(bytes, "a.ply");
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d.points[1], Eigen::Vector3d(-1, -2, -3));
    ASSERT_EQ(d.attribute_names, (std::vector<std::string>{"temperature", "label"}));
    EXPECT_EQ(d.attributes(0, 0), 0.25);
    EXPECT_EQ(d.attributes(1, 0), -0.5);
    EXPECT_EQ(d.attributes(0, 1), 9);
    EXPECT_EQ(d.attributes(1, 1), 200);
  }
  const std::string truncated = error_of([&] { parse_volume_ply(binary.substr(0, binary.size() - 20), "a.ply"); });
  EXPECT_NE(truncated.find("a.ply: vertex 1: property"), std::string::npos) << truncated;
  EXPECT_NE(error_of([] { parse_volume_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n1 2\n", "b.ply"); })
                .find("no property z"),
            std::string::npos);
}

std::string inr_header(const std::string& fields) {
  std::string header = "#INRIMAGE-4#{\n" + fields + "##}\n";
  header.resize(256, '\n');
  return header;
}

TEST(VolumeData, InrimageVoxelCentresRespectSpacingOriginAndByteOrder) {
  // 3 x 2 x 2 float32 little-endian, value = i + 10 j + 100 k.
  std::string bytes = inr_header("XDIM=3\nYDIM=2\nZDIM=2\nVDIM=1\nTYPE=float\nPIXSIZE=32 bits\nCPU=decm\nVX=0.5\nVY=2\nVZ=3\nTX=1\nTY=-1\nTZ=0\n");
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) append(bytes, static_cast<float>(i + 10 * j + 100 * k));
  const VolumeData d = parse_inrimage(bytes, "a.inr");
  ASSERT_EQ(d.size(), 12u);
  ASSERT_EQ(d.attribute_names, std::vector<std::string>{"value"});
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const std::size_t v = static_cast<std::size_t>(i + 3 * j + 6 * k);
        EXPECT_EQ(d.points[v], Eigen::Vector3d(1 + 0.5 * i, -1 + 2 * j, 3 * k));
        EXPECT_EQ(d.attributes(static_cast<Eigen::Index>(v), 0), i + 10 * j + 100 * k);
      }
  // Signed 16-bit big-endian, two values per voxel.
  std::string sun = inr_header("XDIM=2\nYDIM=1\nZDIM=1\nVDIM=2\nTYPE=signed fixed\nPIXSIZE=16 bits\nCPU=sun\n");
  for (std::int16_t v : {-3, 4, 300, -32768}) append(sun, v, true);
  const VolumeData s = parse_inrimage(sun, "b.inr");
  ASSERT_EQ(s.attribute_names, (std::vector<std::string>{"value_0", "value_1"}));
  EXPECT_EQ(s.attributes(0, 0), -3);
  EXPECT_EQ(s.attributes(0, 1), 4);
  EXPECT_EQ(s.attributes(1, 0), 300);
  EXPECT_EQ(s.attributes(1, 1), -32768);
  EXPECT_EQ(s.points[1], Eigen::Vector3d(1, 0, 0));

  const std::string truncated = error_of([&] { parse_inrimage(bytes.substr(0, bytes.size() - 1), "a.inr"); });
  EXPECT_NE(truncated.find("a.inr: data: truncated"), std::string::npos) << truncated;
  const std::string type = error_of([] { parse_inrimage(inr_header("XDIM=1\nYDIM=1\nZDIM=1\nTYPE=complex\nPIXSIZE=32 bits\n"), "c.inr"); });
  EXPECT_NE(type.find("c.inr: header line 5: TYPE"), std::string::npos) << type;
  std::string nan = inr_header("XDIM=1\nYDIM=1\nZDIM=1\nTYPE=float\nPIXSIZE=32 bits\n");
  append(nan, std::nanf(""));
  EXPECT_NE(error_of([&] { parse_inrimage(nan, "d.inr"); }).find("d.inr: point 0: attribute 'value' is not a finite number"), std::string::npos);
}

TEST(VolumeData, VtkImageAndLegacyFilesGiveVoxelCentres) {
  TemporaryDirectory dir;
  // 2 x 2 x 1 points, origin (1, 2, 3), spacing (0.5, 0.25, 1); value = 10 i + j.
  write_bytes(dir / "a.vti",
              "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
              "<ImageData WholeExtent=\"0 1 0 1 0 0\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 1\">\n<Piece Extent=\"0 1 0 1 0 0\">\n"
              "<PointData><DataArray type=\"Float64\" Name=\"f\" format=\"ascii\">0 10 1 11</DataArray>\n"
              "<DataArray type=\"Float32\" Name=\"g\" NumberOfComponents=\"2\" format=\"ascii\">1 2 3 4 5 6 7 8</DataArray></PointData>\n"
              "<CellData></CellData>\n</Piece>\n</ImageData>\n</VTKFile>\n");
  write_bytes(dir / "a.vtk",
              "# vtk DataFile Version 3.0\nimage\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 1\nORIGIN 1 2 3\nSPACING 0.5 0.25 1\n"
              "POINT_DATA 4\nSCALARS f double 1\nLOOKUP_TABLE default\n0 10 1 11\n");
  for (const char* name : {"a.vti", "a.vtk"}) {
    const VolumeData d = read_volume_data(dir / name);
    ASSERT_EQ(d.size(), 4u) << name;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const auto v = static_cast<std::size_t>(i + 2 * j);
        EXPECT_EQ(d.points[v], Eigen::Vector3d(1 + 0.5 * i, 2 + 0.25 * j, 3)) << name;
        EXPECT_EQ(d.attributes(static_cast<Eigen::Index>(v), d.attribute_column("f")), 10 * i + j) << name;
      }
  }
  const VolumeData vti = read_volume_data(dir / "a.vti");
  EXPECT_EQ(vti.attribute_names, (std::vector<std::string>{"f", "g_0", "g_1"}));
  EXPECT_EQ(vti.attributes(2, 2), 6);
  write_bytes(dir / "bad.vti", "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\"");
  EXPECT_NE(error_of([&] { read_volume_data(dir / "bad.vti"); }).find("bad.vti"), std::string::npos);
  EXPECT_THROW(read_volume_data(dir / "absent.vtu"), IoError);
  EXPECT_NE(error_of([&] { read_volume_data(dir / "a.xyz"); }).find("unknown volume data format .xyz"), std::string::npos);
}

TEST(VolumeData, NiftiVoxelSizeBecomesTheSpacing) {
  TemporaryDirectory dir;
  // A NIfTI-1 single file: 348-byte header, 4 bytes of extension flag, then 3 x 2 x 1 float32.
  std::string bytes(348, '\0');
  const auto put = [&](std::size_t offset, auto value) { std::memcpy(bytes.data() + offset, &value, sizeof value); };
  put(0, std::int32_t{348});
  const std::int16_t dim[8] = {3, 3, 2, 1, 1, 1, 1, 1};
  for (int i = 0; i < 8; ++i) put(40 + 2 * static_cast<std::size_t>(i), dim[i]);
  put(70, std::int16_t{16});  // NIFTI_TYPE_FLOAT32
  put(72, std::int16_t{32});
  const float pixdim[8] = {1, 0.5f, 2, 4, 1, 1, 1, 1};
  for (int i = 0; i < 8; ++i) put(76 + 4 * static_cast<std::size_t>(i), pixdim[i]);
  put(108, 352.0f);
  put(112, 1.0f);  // scl_slope
  std::memcpy(bytes.data() + 344, "n+1\0", 4);
  bytes.append(4, '\0');
  for (int v = 0; v < 6; ++v) append(bytes, static_cast<float>(v * v));
  write_bytes(dir / "a.nii", bytes);
  const VolumeData d = read_volume_data(dir / "a.nii");
  ASSERT_EQ(d.size(), 6u);
  ASSERT_EQ(d.attribute_names.size(), 1u);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const auto v = static_cast<std::size_t>(i + 3 * j);
      EXPECT_EQ(d.points[v], Eigen::Vector3d(0.5 * i, 2 * j, 0));
      EXPECT_EQ(d.attributes(static_cast<Eigen::Index>(v), 0), static_cast<double>(v * v));
    }

  // scl_slope 2 and scl_inter 1 scale the values (CT images store Hounsfield units so); a qform
  // (code 1, no rotation) offsets the voxel centres by its qoffset; gzip-compressed alike.
  put(112, 2.0f);
  put(116, 1.0f);
  put(252, std::int16_t{1});  // qform_code
  put(268, 10.0f);
  put(272, 20.0f);
  put(276, 30.0f);
  write_bytes(dir / "b.nii", bytes);
  ASSERT_EQ(std::system(("gzip -c " + (dir / "b.nii").string() + " > " + (dir / "b.nii.gz").string()).c_str()), 0);
  for (const char* name : {"b.nii", "b.nii.gz"}) {
    const VolumeData scaled = read_volume_data(dir / name);
    ASSERT_EQ(scaled.size(), 6u) << name;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const auto v = static_cast<std::size_t>(i + 3 * j);
        EXPECT_EQ(scaled.points[v], Eigen::Vector3d(10 + 0.5 * i, 20 + 2 * j, 30)) << name;
        EXPECT_EQ(scaled.attributes(static_cast<Eigen::Index>(v), 0), 2.0 * static_cast<double>(v * v) + 1) << name;
      }
  }
  write_bytes(dir / "c.txt.gz", "x");
  EXPECT_NE(error_of([&] { read_volume_data(dir / "c.txt.gz"); }).find("unknown volume data format .gz"), std::string::npos);
}

// Legacy files with fewer values than declared, or a value that is not a number: VTK's legacy
// readers warn or complain and go on with zeros; the file is refused, named.
TEST(VolumeData, DamagedLegacyVtkFilesAreRefused) {
  TemporaryDirectory dir;
  const std::string header = "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 5 float\n0 0 0 1 0 0 0 1 0 0 0 1 1 1 1\n";
  write_bytes(dir / "short.vtk", header + "POINT_DATA 5\nSCALARS d float 1\nLOOKUP_TABLE default\n1 2 3\n");
  write_bytes(dir / "word.vtk", header + "POINT_DATA 5\nSCALARS d float 1\nLOOKUP_TABLE default\n1 2 abc 4 5\n");
  write_bytes(dir / "points.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0\n");
  write_bytes(dir / "kind.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET NOTHING\n");
  write_bytes(dir / "good.vtk", header + "POINT_DATA 5\nSCALARS d float 1\nLOOKUP_TABLE default\n1 2 3 4 5\n");
  for (const char* name : {"short.vtk", "word.vtk", "points.vtk", "kind.vtk"})
    EXPECT_NE(error_of([&] { read_volume_data(dir / name); }).find(name), std::string::npos) << name;
  const VolumeData good = read_volume_data(dir / "good.vtk");
  ASSERT_EQ(good.size(), 5u);
  EXPECT_EQ(good.attributes(4, 0), 5);
  EXPECT_EQ(good.points[4], Eigen::Vector3d(1, 1, 1));
}

TEST(VolumeData, FireUnstructuredGridHasItsPointsAndFields) {
  const auto path = test_support::shared_volume_data() / "fire_ug.vtu";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (see docs/fitting.md)";
  const VolumeData d = read_volume_data(path);
  EXPECT_EQ(d.size(), 12323u);
  for (const char* name : {"t", "u", "v", "w", "mfrac", "uvw_0", "uvw_1", "uvw_2"}) EXPECT_NO_THROW(d.attribute_column(name)) << name;
  // The vector field uvw and its separate components u, v, w are independent arrays of the file.
  EXPECT_EQ(d.attributes.col(d.attribute_column("uvw_0")), d.attributes.col(d.attribute_column("u")));
  EXPECT_EQ(d.attributes.col(d.attribute_column("uvw_2")), d.attributes.col(d.attribute_column("w")));
}

TEST(VolumeData, SkullImageHasItsVoxelGrid) {
  const auto path = test_support::shared_volume_data() / "skull_2.9.inr";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent (see docs/fitting.md)";
  const VolumeData d = read_volume_data(path);
  ASSERT_EQ(d.size(), 64u * 64 * 64);
  EXPECT_EQ(d.points[0], Eigen::Vector3d::Zero());
  EXPECT_NEAR(d.points[1].x(), 3.94305, 1e-12);
  EXPECT_NEAR(d.points[64].y(), 3.94305, 1e-12);
  EXPECT_NEAR(d.points[64 * 64].z(), 3.65, 1e-2);
  EXPECT_GE(d.attributes.minCoeff(), 0);
  EXPECT_LE(d.attributes.maxCoeff(), 5.5);
  EXPECT_GT(d.attributes.maxCoeff(), 5);
}

TEST(VolumeDataExamples, MarschnerLobbMatchesItsClosedFormAtKnownPoints) {
  // r = 0: cos(2π f_M cos 0) = 1, so ρ = (1 − sin(πz/2) + 2α) / (2 (1 + α)).
  EXPECT_NEAR(marschner_lobb({0, 0, -1}), 1.0, 1e-15);
  EXPECT_NEAR(marschner_lobb({0, 0, 1}), 0.2, 1e-15);
  // r = 1 (x = 1): cos(π/2) = 0, cos 0 = 1: ρ = (1 − sin(πz/2) + 0.5) / 2.5.
  EXPECT_NEAR(marschner_lobb({1, 0, 0}), 0.6, 1e-15);
  const VolumeData d = marschner_lobb_data(41);
  ASSERT_EQ(d.size(), 41u * 41 * 41);
  EXPECT_EQ(d.points.front(), Eigen::Vector3d(-1, -1, -1));
  EXPECT_EQ(d.points.back(), Eigen::Vector3d(1, 1, 1));
  EXPECT_GE(d.attributes.minCoeff(), 0);
  EXPECT_LE(d.attributes.maxCoeff(), 1 + 1e-15);
  const VolumeData jump = two_material_data(5, 0);
  for (std::size_t i = 0; i < jump.size(); ++i) {
    const Eigen::Vector3d& x = jump.points[i];
    EXPECT_EQ(jump.attributes(static_cast<Eigen::Index>(i), 0), (x.x() < 0.5 ? 1.0 : 2.0) + 0.1 * (x.y() + x.z()));
  }
}

// The names the command line and Python take for generated data: the same points and values as
// the functions, the tilt kept, the truth the function; malformed names refused with what was
// expected; other names (files) left alone.
TEST(VolumeDataExamples, GeneratedDataNamesGiveTheirDataAndTruth) {
  const auto tilted = generated_volume_data("two-material:6:0.37");
  ASSERT_TRUE(tilted);
  const VolumeData direct = two_material_data(6, 0.37);
  ASSERT_EQ(tilted->size(), direct.size());
  EXPECT_EQ(tilted->attributes, direct.attributes);
  const auto truth = generated_volume_truth("two-material:6:0.37");
  ASSERT_TRUE(truth);
  EXPECT_EQ(truth(Eigen::Vector3d(0.3, 0.9, 0.5))[0], two_material({0.3, 0.9, 0.5}, 0.37));
  EXPECT_EQ(generated_volume_data("marschner-lobb:7")->size(), 343u);
  EXPECT_EQ(generated_volume_truth("marschner-lobb:7")(Eigen::Vector3d(1, 0, 0))[0], marschner_lobb({1, 0, 0}));
  EXPECT_FALSE(generated_volume_data("fire_ug.vtu"));
  EXPECT_FALSE(generated_volume_truth("fire_ug.vtu"));
  for (const char* bad : {"two-material:", "two-material:6:x", "two-material:6:0.3:1", "two-material:1", "two-material:401",
                          "two-material:6:inf", "marschner-lobb:7:1", "marschner-lobb:x", "marschner-lobb:7x"}) {
    try {
      generated_volume_data(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace volspline
