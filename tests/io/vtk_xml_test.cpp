// VTK XML unstructured grids of Bézier cells: VTK's own reader (Debian's python3-vtk9) reads the
// written file and evaluates every cell at parametric points; the positions and the interpolated
// attributes must equal volspline's evaluation of the original splines. Our reader brings the
// cells back, and files with wrong point counts are rejected with their location.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "support/exchange_support.h"
#include "support/temporary_directory.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/vtk_xml.h"
#include "volspline/spline/bezier_extraction.h"

namespace volspline {
namespace {

TEST(VtkBezierPointOrder, IsAPermutationStartingWithTheCorners) {
  for (int parameters = 1; parameters <= 3; ++parameters) {
    for (const std::array<int, 3> degrees : {std::array<int, 3>{1, 1, 1}, {2, 3, 1}, {3, 2, 4}, {1, 4, 2}}) {
      const auto order = vtk_bezier_point_order(parameters, degrees);
      std::size_t expected = 1;
      for (int d = 0; d < parameters; ++d) expected *= static_cast<std::size_t>(degrees[static_cast<std::size_t>(d)] + 1);
      ASSERT_EQ(order.size(), expected);
      const std::set<std::array<int, 3>> distinct(order.begin(), order.end());
      EXPECT_EQ(distinct.size(), expected);
      for (std::size_t m = 0; m < (std::size_t{1} << parameters); ++m) {
        for (int d = 0; d < parameters; ++d) {
          const int index = order[m][static_cast<std::size_t>(d)];
          EXPECT_TRUE(index == 0 || index == degrees[static_cast<std::size_t>(d)]) << "point " << m << " is not a corner";
        }
      }
    }
  }
}

/// A rational torus (16 cells), a polynomial volume with non-uniform interior knots of degrees
/// (2, 3, 1) and a rational random volume, all with the attribute "temperature" (the torus's is
/// its z coordinate).
Model volume_model(std::mt19937& rng) {
  Model model;
  const BSplineVolume t = torus(2.0, 0.5);
  ModelObject torus_object{"torus", false, t, nullptr};
  std::vector<double> z;
  for (int i = 0; i < t.num_control_points_total(); ++i) z.push_back(t.points()[3 * static_cast<std::size_t>(i) + 2]);
  torus_object.attributes["temperature"] = z;
  model.objects.push_back(torus_object);
  const Model random = test_support::random_exchange_model(rng);
  model.objects.push_back(random.objects[4]);
  model.objects.push_back(random.objects[5]);
  return model;
}

/// "cell r s t x y z temperature" for random parametric points and the corners of every cell,
/// from the original splines (not from the Bézier pieces the file holds).
std::string expected_values(const Model& model, std::mt19937& rng) {
  std::string out = "names temperature\n";
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t cell = 0;
  for (const ModelObject& object : model.objects) {
    visit_classic_spline(object, "test", "",
        [&](const auto& spline) {
          constexpr int D = std::decay_t<decltype(spline)>::num_parameters;
          for (const auto& piece : bezier_pieces(spline)) {
            for (int n = 0; n < 12; ++n) {
              std::array<double, 3> pc{unit(rng), unit(rng), unit(rng)};
              if (n < 8) pc = {double(n & 1), double((n >> 1) & 1), double(n >> 2)};
              typename std::decay_t<decltype(spline)>::Parameter t{};
              std::vector<double> tv;
              for (int d = 0; d < D; ++d) {
                t[static_cast<std::size_t>(d)] = piece.domain_min(d) + pc[static_cast<std::size_t>(d)] * (piece.domain_max(d) - piece.domain_min(d));
                tv.push_back(t[static_cast<std::size_t>(d)]);
              }
              const Eigen::VectorXd x = spline.evaluate(t);
              out += std::to_string(cell);
              std::vector<double> values(pc.begin(), pc.end());
              for (int c = 0; c < 3; ++c) values.push_back(c < x.size() ? x[c] : 0.0);
              values.push_back(evaluate_attribute(object, "temperature", tv));
              for (double v : values) {
                out += ' ';
                out += format_double(v);
              }
              out += '\n';
            }
            ++cell;
          }
        });
  }
  return out;
}

const char* kVtkScript = R"(import sys, vtk
reader = vtk.vtkXMLUnstructuredGridReader()
reader.SetFileName(sys.argv[1])
reader.Update()
grid = reader.GetOutput()
lines = open(sys.argv[2]).read().split('\n')
arrays = [grid.GetPointData().GetArray(n) for n in lines[0].split()[1:]]
worst, count = 0.0, 0
for line in lines[1:]:
    if not line.strip():
        continue
    f = line.split()
    cell = grid.GetCell(int(f[0]))
    pc = [float(v) for v in f[1:4]]
    x = [0.0, 0.0, 0.0]
    weights = [0.0] * cell.GetNumberOfPoints()
    cell.EvaluateLocation(vtk.reference(0), pc, x, weights)
    values = list(x) + [sum(weights[i] * a.GetValue(cell.GetPointId(i)) for i in range(len(weights))) for a in arrays]
    worst = max(worst, max(abs(u - float(v)) for u, v in zip(values, f[4:])))
    count += 1
print('cells', grid.GetNumberOfCells())
print('types', ' '.join(str(t) for t in sorted(set(grid.GetCellType(i) for i in range(grid.GetNumberOfCells())))))
print('rational_weights_attribute', int(grid.GetPointData().GetRationalWeights() is not None))
print('degrees_attribute', int(grid.GetCellData().GetHigherOrderDegrees() is not None))
print('checked', count)
print('max_error', repr(worst))
)";

bool vtk_available() {
  static const bool available = std::system("/usr/bin/python3 -c 'import vtk' >/dev/null 2>&1") == 0;
  return available;
}

/// Runs VTK on the file; returns the script's "key value" lines.
std::map<std::string, std::string> run_vtk(const test_support::TemporaryDirectory& dir, const Model& model, std::mt19937& rng) {
  write_vtu(model, dir / "model.vtu");
  std::ofstream(dir / "expected.txt") << expected_values(model, rng);
  std::ofstream(dir / "check.py") << kVtkScript;
  const std::string command = "/usr/bin/python3 " + (dir / "check.py").string() + " " + (dir / "model.vtu").string() + " " +
                              (dir / "expected.txt").string() + " >" + (dir / "out.txt").string() + " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir / "out.txt");
  std::map<std::string, std::string> result;
  std::string all;
  for (std::string line; std::getline(in, line);) {
    all += line + "\n";
    const auto space = line.find(' ');
    if (space != std::string::npos) result[line.substr(0, space)] = line.substr(space + 1);
  }
  EXPECT_TRUE(result.contains("max_error")) << all;
  return result;
}

std::size_t total_cells(const Model& model) {
  std::size_t cells = 0;
  for (const auto& object : model.objects) visit_classic_spline(object, "test", "", [&](const auto& s) { cells += bezier_pieces(s).size(); });
  return cells;
}

TEST(VtkReader, ReadsRationalAndMultiPieceVolumesAsVolsplineEvaluatesThem) {
  if (!vtk_available()) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (install python3-vtk9)";
  const test_support::TemporaryDirectory dir;
  std::mt19937 rng(1);
  const Model model = volume_model(rng);
  const auto result = run_vtk(dir, model, rng);
  EXPECT_EQ(result.at("cells"), std::to_string(total_cells(model)));
  EXPECT_EQ(result.at("types"), "79");
  EXPECT_EQ(result.at("rational_weights_attribute"), "1");
  EXPECT_EQ(result.at("degrees_attribute"), "1");
  EXPECT_EQ(result.at("checked"), std::to_string(12 * total_cells(model)));
  EXPECT_LT(std::stod(result.at("max_error")), 1e-12);
}

TEST(VtkReader, ReadsBezierCurvesAndQuadrilateralsToo) {
  if (!vtk_available()) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (install python3-vtk9)";
  const test_support::TemporaryDirectory dir;
  std::mt19937 rng(2);
  const Model model = test_support::random_exchange_model(rng);
  const auto result = run_vtk(dir, model, rng);
  EXPECT_EQ(result.at("types"), "75 77 79");
  EXPECT_LT(std::stod(result.at("max_error")), 1e-12);
  // Not every object is a volume in R^3: no Jacobian array.
  EXPECT_EQ(vtu_text(model).find("Name=\"Jacobian\""), std::string::npos);
}

TEST(VtuFile, TheJacobianArrayIsTheDeterminantAtEachControlPointsParameter) {
  // The unit-speed cylinder parameterization has det J = rho * (angle speed) etc.; simpler: an
  // affine volume x = A u has det J = det A at every point.
  const std::vector<double> points = {0, 0, 0, 2, 0, 0, 0, 3, 0, 2, 3, 0, 1, 0, 4, 3, 0, 4, 1, 3, 4, 3, 3, 4};
  const BSplineVolume affine({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, points);
  const std::string text = vtu_text(Model{{ModelObject{"", false, affine, nullptr}}, nullptr});
  const auto at = text.find("Name=\"Jacobian\"");
  ASSERT_NE(at, std::string::npos);
  std::istringstream values(text.substr(text.find('>', at) + 1));
  for (int i = 0; i < 8; ++i) {
    double j = 0;
    values >> j;
    EXPECT_NEAR(j, 24.0, 1e-12);
  }
}

TEST(VtuFile, OurReaderGivesBackEveryCellAndItsAttributes) {
  std::mt19937 rng(3);
  const Model model = test_support::random_exchange_model(rng);
  const Model cells = parse_vtu(vtu_text(model), "m.vtu");
  ASSERT_EQ(cells.objects.size(), total_cells(model));
  std::size_t c = 0;
  double worst = 0.0;
  for (const ModelObject& object : model.objects) {
    visit_classic_spline(object, "test", "",
        [&](const auto& spline) {
          using S = std::decay_t<decltype(spline)>;
          constexpr int D = S::num_parameters;
          for (const auto& piece : bezier_pieces(spline)) {
            const ModelObject& cell = cells.objects[c++];
            const S& read = std::get<S>(cell.spline);
            EXPECT_TRUE(cell.bezier);
            EXPECT_EQ(cell.attributes.size(), object.attributes.size());
            for (int n = 0; n < 10; ++n) {
              const auto t = test_support::random_parameter(rng, piece);
              typename S::Parameter unit{};
              std::vector<double> tv(t.begin(), t.end()), uv;
              for (int d = 0; d < D; ++d) {
                unit[static_cast<std::size_t>(d)] = (t[static_cast<std::size_t>(d)] - piece.domain_min(d)) / (piece.domain_max(d) - piece.domain_min(d));
                uv.push_back(unit[static_cast<std::size_t>(d)]);
              }
              worst = std::max(worst, (read.evaluate(unit) - spline.evaluate(t)).norm());
              for (const auto& item : object.attributes) {
                worst = std::max(worst, std::abs(evaluate_attribute(cell, item.first, uv) - evaluate_attribute(object, item.first, tv)));
              }
            }
          }
        });
  }
  EXPECT_LT(worst, 1e-12);
}

std::string vtu_error_of(const std::string& text) {
  try {
    parse_vtu(text, "bad.vtu");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(VtuFile, WrongPointCountsAndOtherBadFilesSayWhere) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
  const BSplineVolume cube({KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)}, 3, points);
  const std::string good = vtu_text(Model{{ModelObject{"", false, cube, nullptr}}, nullptr});
  EXPECT_EQ(vtu_error_of(good), "no error");
  EXPECT_EQ(vtu_error_of(replaced(good, "NumberOfPoints=\"8\"", "NumberOfPoints=\"7\"")),
            "bad.vtu: line 20, /VTKFile/UnstructuredGrid/Piece/Points/DataArray: expected 21 numbers (3 per point, NumberOfPoints = 7), got 24");
  EXPECT_EQ(vtu_error_of(replaced(good, "          8 \n", "          7 \n")),
            "bad.vtu: line 25, /VTKFile/UnstructuredGrid/Piece/Cells/DataArray[1]: expected 7 integers (the last offset), got 8");
  EXPECT_EQ(vtu_error_of(replaced(good, "Name=\"HigherOrderDegrees\" NumberOfComponents=\"3\" format=\"ascii\">\n          1 1 1",
                                     "Name=\"HigherOrderDegrees\" NumberOfComponents=\"3\" format=\"ascii\">\n          1 1 2")),
            "bad.vtu: line 28, /VTKFile/UnstructuredGrid/Piece/Cells/DataArray[2]: cell 0 has 8 points, expected 12 for degrees 1 1 2 "
            "(a Bezier cell of degree >= 1 with prod (degree + 1) points)");
  EXPECT_EQ(vtu_error_of(replaced(good, "          79 \n", "          12 \n")),
            "bad.vtu: line 31, /VTKFile/UnstructuredGrid/Piece/Cells/DataArray[3]: cell 0 has type 12: expected a Bezier curve (75), "
            "quadrilateral (77) or hexahedron (79)");
  EXPECT_EQ(vtu_error_of(replaced(good, "version=\"2.2\"", "version=\"1.0\"")).rfind("bad.vtu: line 3, /VTKFile: expected version 2.2 or later", 0), 0u);
  EXPECT_NE(vtu_error_of(good.substr(0, good.size() / 2)).find("invalid XML"), std::string::npos);
  EXPECT_EQ(vtu_error_of(replaced(good, "Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\"", "Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\"")).find("binary and appended data are not read") != std::string::npos, true);
}

TEST(VtuFile, SplinesBeyondThreeCoordinatesAreRefused) {
  std::mt19937 rng(4);
  EXPECT_THROW(vtu_text(Model{{ModelObject{"", false, test_support::random_spline<3>(rng, {1, 1, 1}, 1, 4, false), nullptr}}, nullptr}), InvalidInput);
}

}  // namespace
}  // namespace volspline
