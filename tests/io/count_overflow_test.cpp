// Products of counts declared by a file never wrap (core/checked_arithmetic.h): whatever the
// reader, a declared grid whose size times its coordinates does not fit is refused as
// InvalidInput naming the file, never accepted with a short array. The representative is issue
// 16's G+Smo file (three degree-1 knot vectors of 65,538 knots and geoDim 65536: 2^48 x 2^16 =
// 2^64 wrapped to 0, so an empty <coefs> passed the size check); the others are the same class
// in other readers, other parameter counts and other sizes.
#include <gtest/gtest.h>

#include <climits>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/cli_runner.h"
#include "support/temporary_directory.h"
#include "volspline/core/checked_arithmetic.h"
#include "volspline/core/error.h"
#include "volspline/io/gismo_xml.h"
#include "volspline/io/irit_itd.h"
#include "volspline/io/model_file.h"
#include "volspline/io/volume_data.h"
#include "volspline/io/vtk_xml.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/spline/tensor_spline.h"

#include <utility>

#include "support/invalid_input_message.h"

namespace volspline {
namespace {

template <class F>
std::string overflow_error_of(F&& f) {
  return test_support::invalid_input_message(std::forward<F>(f));
}

bool overflow_contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// "0 0 1 2 ... n-2 n-2": a clamped degree-1 knot vector of n knots (n - 2 basis functions).
std::string overflow_degree1_knots(int n) {
  std::string text = "0";
  for (int i = 0; i < n - 2; ++i) text += " " + std::to_string(i);
  return text + " " + std::to_string(n - 3);
}

std::vector<double> overflow_degree1_knot_values(int n) {
  std::vector<double> k{0.0};
  for (int i = 0; i < n - 2; ++i) k.push_back(i);
  k.push_back(n - 3);
  return k;
}

TEST(CheckedArithmetic, ProductsThatFitAreExactAndOthersAreRefused) {
  EXPECT_EQ(multiply_exactly<int>(46340, 46340), 46340 * 46340);
  EXPECT_FALSE(multiply_exactly<int>(46341, 46341));
  EXPECT_FALSE(multiply_exactly<int>(-1, 3));
  EXPECT_EQ(multiply_exactly<std::uint64_t>(std::uint64_t{1} << 32, (std::uint64_t{1} << 32) - 1),
            (std::uint64_t{1} << 32) * ((std::uint64_t{1} << 32) - 1));
  EXPECT_FALSE(multiply_exactly<std::uint64_t>(std::uint64_t{1} << 48, std::uint64_t{1} << 16));  // 2^64 wraps to 0
  EXPECT_EQ(product_exactly<std::uint64_t>({65536, 65536, 65536}), std::uint64_t{1} << 48);
  EXPECT_FALSE(product_exactly<std::uint64_t>({65536, 65536, 65536, 65536}));
  EXPECT_EQ(product_exactly<int>({0, INT_MAX, INT_MAX}), 0);  // a zero factor: no overflow however large the others
  EXPECT_EQ(product_exactly<int>(std::vector<int>{}), 1);
  EXPECT_EQ(checked_product<int>({1290, 1290, 1290}, "n"), 1290 * 1290 * 1290);
  EXPECT_EQ(overflow_error_of([] { checked_product<int>({1291, 1291, 1291}, "control points", "control_points"); }),
            "control_points: control points = 1291 x 1291 x 1291 is more than 2147483647 (the counts multiply beyond what can be "
            "represented or held)");
  EXPECT_TRUE(overflow_contains(overflow_error_of([] { checked_product<long long>({10, 10}, "voxels", "h", 99); }), "voxels = 10 x 10 is more than 99"));
}

TEST(CountOverflow, TensorSplineRefusesGridsWhoseTotalDoesNotFitWhateverTheParameterCount) {
  // 65536^3 wraps an int to 0, which an empty array of points matched before.
  const KnotVector big(1, overflow_degree1_knot_values(65538));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineVolume({big, big, big}, 65536, {}); }), "is more than 2147483647"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineVolume({big, big, big}, 1, {}); }), "is more than 2147483647"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineSurface({big, big}, 1, {}); }), "65536 x 65536 x 2"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineHypervolume({big, big, big, big}, 3, {}); }), "is more than"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineCurve({big}, 65536, {}); }), "65536 x 65537"));
  // Just fitting is fine (a count mismatch, not an overflow); the homogeneous constructor too.
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineCurve({big}, 1, {}); }), "expected 65536 control points"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([&] { BSplineVolume::from_homogeneous({big, big, big}, 3, true, {}); }), "is more than"));
}

std::string overflow_gismo_volume(int knots, const std::string& geo_dim) {
  const std::string kv = "<Basis type=\"BSplineBasis\"><KnotVector degree=\"1\">" + overflow_degree1_knots(knots) + "</KnotVector></Basis>\n";
  return "<?xml version=\"1.0\"?>\n<xml>\n<Geometry type=\"TensorBSpline3\">\n<Basis type=\"TensorBSplineBasis3\">\n" + kv + kv +
         kv + "</Basis>\n<coefs geoDim=\"" + geo_dim + "\"></coefs>\n</Geometry>\n</xml>\n";
}

TEST(CountOverflow, GismoXmlNamesTheFileTheCoefsAndTheCounts) {
  // Issue 16's file: 65536^3 coefficients x geoDim 65536 = 2^64.
  const std::string e = overflow_error_of([] { parse_gismo_xml(overflow_gismo_volume(65538, "65536"), "wrap.xml"); });
  EXPECT_EQ(e.rfind("wrap.xml: line 9, /xml/Geometry/coefs: coefficients (from the knot vectors) x (geoDim + 1) = 65536 x 65536 x "
                    "65536 x 65537 is more than 2147483647",
                    0),
            0u)
      << e;
  // Other sizes: no wrap of 64 bits but more than the spline's sizes hold; a smaller grid.
  EXPECT_TRUE(overflow_contains(overflow_error_of([] { parse_gismo_xml(overflow_gismo_volume(65538, "1"), "a.xml"); }), "a.xml: line 9"));
  EXPECT_TRUE(overflow_contains(overflow_error_of([] { parse_gismo_xml(overflow_gismo_volume(1300, "3"), "b.xml"); }), "1298 x 1298 x 1298 x 4 is more than"));
  // Within the limits the old count check speaks.
  EXPECT_TRUE(overflow_contains(overflow_error_of([] { parse_gismo_xml(overflow_gismo_volume(12, "3"), "c.xml"); }), "expected 3000 numbers"));
}

TEST(CountOverflow, JsonModelRefusesTheGridAndThePointsTimesCoordinates) {
  const std::string kv = "[" + [] {
    std::string t;
    for (double x : overflow_degree1_knot_values(65538)) t += (t.empty() ? "" : ",") + std::to_string(static_cast<int>(x));
    return t;
  }() + "]";
  const std::string volume = R"({"volspline":1,"objects":[{"type":"bspline_volume","degree":[1,1,1],"knots":[)" +
                             kv + "," + kv + "," + kv + R"(],"control_points":[]}]})";
  const std::string e = overflow_error_of([&] { parse_model(volume, "v.json"); });
  EXPECT_TRUE(overflow_contains(e, "v.json")) << e;
  EXPECT_TRUE(overflow_contains(e, "control_points")) << e;
  EXPECT_TRUE(overflow_contains(e, "65536 x 65536 x 65536")) << e;
  // n points of which the first has k coordinates: n x (k + 1) > INT_MAX is refused before the
  // rest is read (and before anything is sized by n x k).
  std::string points = "[[";
  for (int c = 0; c < 32768; ++c) points += c ? ",0" : "0";
  points += "]";
  for (int i = 1; i < 65536; ++i) points += ",[0]";
  points += "]";
  const std::string curve = R"({"volspline":1,"objects":[{"type":"bspline_curve","degree":[1],"knots":[)" + kv + R"(],"control_points":)" + points + "}]}";
  const std::string e2 = overflow_error_of([&] { parse_model(curve, "c.json"); });
  EXPECT_TRUE(overflow_contains(e2, "c.json")) << e2;
  EXPECT_TRUE(overflow_contains(e2, "65536 x 32769 is more than 2147483647")) << e2;
}

TEST(CountOverflow, IritRefusesHeadersAskingForMoreControlPointsThanTheFileHolds) {
  const std::string kv = "[KV " + overflow_degree1_knots(65538) + "]\n";
  const std::string text = "[OBJECT big\n[TRIVAR BSPLINE 65536 65536 65536 2 2 2 E3\n" + kv + kv + kv + "[0 0 0]\n]\n]\n";
  const std::string e = overflow_error_of([&] { parse_irit_itd(text, "big.itd"); });
  EXPECT_EQ(e.rfind("big.itd: line 2", 0), 0u) << e;
  EXPECT_TRUE(overflow_contains(e, "more control points than the file holds")) << e;
  const std::string surface = "[OBJECT s\n[SURFACE BSPLINE 2147483647 2147483647 2 2 E2\n[KV 0 0 1 1]\n]\n]\n";
  EXPECT_EQ(overflow_error_of([&] { parse_irit_itd(surface, "s.itd"); }).rfind("s.itd: line ", 0), 0u);
}

TEST(CountOverflow, VtuInrimagePlyAndStlRefuseDeclaredCountsTheirDataCannotHold) {
  const std::string vtu = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="2.2" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints="2147483647" NumberOfCells="2147483647">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0</DataArray></Points>
<Cells><DataArray type="Int64" Name="connectivity" format="ascii">0</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">1</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">75</DataArray></Cells>
</Piece></UnstructuredGrid></VTKFile>
)";
  const std::string v = overflow_error_of([&] { parse_vtu(vtu, "p.vtu"); });
  EXPECT_EQ(v.rfind("p.vtu: line 4", 0), 0u) << v;

  for (const char* dims : {"XDIM=1048576\nYDIM=1048576\nZDIM=1048576\n", "XDIM=1024\nYDIM=1024\nZDIM=1024\nVDIM=1048576\n"}) {
    std::string header = std::string("#INRIMAGE-4#{\n") + dims + "TYPE=float\nPIXSIZE=32 bits\nCPU=decm\n";
    header += std::string(252 - header.size(), '\n') + "##}\n";
    const std::string e = overflow_error_of([&] { parse_inrimage(header, "i.inr"); });
    EXPECT_EQ(e.rfind("i.inr: header", 0), 0u) << e;
    EXPECT_TRUE(overflow_contains(e, "is more than 268435456")) << e;
  }

  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 2147483648\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(overflow_error_of([&] { parse_ply(ply, "m.ply"); }).rfind("m.ply", 0), 0u);
  EXPECT_EQ(overflow_error_of([&] { parse_volume_ply(ply, "v.ply"); }).rfind("v.ply", 0), 0u);
  std::string stl(84, '\0');
  for (int i = 80; i < 84; ++i) stl[static_cast<std::size_t>(i)] = '\xff';  // 2^32 - 1 triangles declared
  EXPECT_EQ(overflow_error_of([&] { parse_stl(stl, "m.stl"); }).rfind("m.stl", 0), 0u);
}

TEST(CountOverflowCli, EveryCommandRefusesTheWrappingFileWithExitTwoAndWritesNothing) {
  test_support::TemporaryDirectory tmp;
  const auto file = tmp.path() / "wrap.xml";
  std::ofstream(file) << overflow_gismo_volume(65538, "65536");
  const std::string f = file.string();
  const auto out = (tmp.path() / "out.json").string();
  for (const std::string& args : {"eval " + f + " --at 0.5,0.5,0.5", "info " + f, "info --mass " + f, "convert " + f + " -o " + out,
                                  "faces " + f + " -o " + (tmp.path() / "f.ply").string()}) {
    const auto r = test_support::run_cli(args, tmp.path());
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_TRUE(overflow_contains(r.err, "wrap.xml: line 9, /xml/Geometry/coefs")) << args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "f.ply"));
}

}  // namespace
}  // namespace volspline
