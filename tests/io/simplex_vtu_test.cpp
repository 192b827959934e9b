// A simplex spline volume written to VTK (io/simplex_vtu.h) as VTK's own reader (Debian's
// python3-vtk9) sees it: one Lagrange tetrahedron of the spline's degree per domain tetrahedron.
// A degree-n spline reproduces a degree-n polynomial attribute over the identity geometry, and
// VTK's order-n interpolation of its node samples is then exact: VTK's values inside every cell
// match the polynomial, which only holds if every node sits where VTK's node order expects it.
#include <cstdlib>
#include <fstream>
#include <algorithm>
#include <map>
#include <numeric>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "support/simplex_domains.h"
#include "support/temporary_directory.h"
#include "volspline/core/error.h"
#include "volspline/io/vtk_xml.h"

namespace volspline {
namespace {

const char* kScript = R"(import sys, vtk
reader = vtk.vtkXMLUnstructuredGridReader()
reader.SetFileName(sys.argv[1])
reader.Update()
grid = reader.GetOutput()
density = grid.GetPointData().GetArray('density')
degree = int(sys.argv[2])
forms = [(1, 2, -1, 0.5), (0.3, -1, 0.2, 1), (-0.5, 0.4, 1, 0.7), (0.8, 0.1, -0.6, 1.2)][:degree]
def f(x):
    value = 1.0
    for a in forms:
        value *= a[0] * x[0] + a[1] * x[1] + a[2] * x[2] + a[3]
    return value
worst, count = 0.0, 0
for c in range(grid.GetNumberOfCells()):
    cell = grid.GetCell(c)
    for pc in ([0.2, 0.3, 0.1], [0.25, 0.25, 0.25], [0.6, 0.1, 0.2]):
        x = [0.0, 0.0, 0.0]
        weights = [0.0] * cell.GetNumberOfPoints()
        cell.EvaluateLocation(vtk.reference(0), pc, x, weights)
        value = sum(weights[i] * density.GetValue(cell.GetPointId(i)) for i in range(len(weights)))
        worst = max(worst, abs(value - f(x)))
        count += 1
print('cells', grid.GetNumberOfCells())
print('types', ' '.join(str(t) for t in sorted(set(grid.GetCellType(i) for i in range(grid.GetNumberOfCells())))))
print('checked', count)
print('max_error', repr(worst))
)";

// The product of the first n of four linear forms, and its blossom: the symmetric average of the
// products of the forms at the n arguments over all n! assignments.
constexpr double kForms[4][4] = {{1, 2, -1, 0.5}, {0.3, -1, 0.2, 1}, {-0.5, 0.4, 1, 0.7}, {0.8, 0.1, -0.6, 1.2}};

double product_blossom(std::span<const Eigen::Vector3d> arguments) {
  const int n = static_cast<int>(arguments.size());
  std::vector<int> slot(static_cast<std::size_t>(n));
  std::iota(slot.begin(), slot.end(), 0);
  double sum = 0;
  int count = 0;
  do {
    double term = 1;
    for (int i = 0; i < n; ++i) {
      const double* a = kForms[i];
      const Eigen::Vector3d& x = arguments[static_cast<std::size_t>(slot[static_cast<std::size_t>(i)])];
      term *= a[0] * x.x() + a[1] * x.y() + a[2] * x.z() + a[3];
    }
    sum += term;
    ++count;
  } while (std::next_permutation(slot.begin(), slot.end()));
  return sum / count;
}

class SimplexVtuDegree : public ::testing::TestWithParam<int> {};

TEST_P(SimplexVtuDegree, VtkInterpolatesTheSplineExactlyWhereItIsAPolynomialOfItsDegree) {
  if (std::system("/usr/bin/python3 -c 'import vtk' >/dev/null 2>&1") != 0) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (install python3-vtk9)";
  const int degree = GetParam();
  DmsSplineVolume v = test_support::cube_simplex_volume(degree);
  set_column_from_blossom(v, 3, product_blossom);
  const std::size_t cells = v.domain().tetrahedra.size();
  Model model;
  model.objects.push_back({"", false, std::move(v), nullptr});
  const test_support::TemporaryDirectory dir;
  write_vtu(model, dir / "s.vtu");
  std::ofstream(dir / "check.py") << kScript;
  const std::string command = "/usr/bin/python3 " + (dir / "check.py").string() + " " + (dir / "s.vtu").string() + " " + std::to_string(degree) + " >" +
                              (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir / "out.txt");
  std::map<std::string, std::string> result;
  for (std::string line; std::getline(in, line);) {
    const auto space = line.find(' ');
    if (space != std::string::npos) result[line.substr(0, space)] = line.substr(space + 1);
  }
  ASSERT_TRUE(result.contains("max_error"));
  EXPECT_EQ(result.at("cells"), std::to_string(cells));
  EXPECT_EQ(result.at("types"), degree == 2 ? "24" : "71");
  EXPECT_EQ(result.at("checked"), std::to_string(3 * cells));
  EXPECT_LT(std::stod(result.at("max_error")), 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Degrees, SimplexVtuDegree, ::testing::Values(2, 3, 4));

TEST(SimplexVtu, RefusesAMixWithTensorProductObjects) {
  Model model;
  model.objects.push_back({"", false, test_support::cube_simplex_volume(1), nullptr});
  model.objects.push_back(model.objects.front());
  try {
    vtu_text(model);
    FAIL() << "accepted two objects";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.where(), "objects[0]");
  }
}

}  // namespace
}  // namespace volspline
