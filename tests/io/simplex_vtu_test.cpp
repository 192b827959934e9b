// A simplex spline volume written to VTK (io/simplex_vtu.h) as VTK's own reader (Debian's
// python3-vtk9) sees it: one quadratic tetrahedron per domain tetrahedron whose interpolation of
// a quadratic attribute over the identity geometry is exact, so VTK's values inside every cell
// match the polynomial the spline reproduces.
#include <cstdlib>
#include <fstream>
#include <map>

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
def f(x):
    return (x[0] + 2 * x[1] - x[2] + 0.5) * (0.3 * x[0] - x[1] + 0.2 * x[2] + 1)
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

TEST(SimplexVtu, VtkInterpolatesTheSplineExactlyWhereItIsQuadratic) {
  if (std::system("/usr/bin/python3 -c 'import vtk' >/dev/null 2>&1") != 0) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (install python3-vtk9)";
  DmsSplineVolume v = test_support::cube_simplex_volume(2);
  set_column_from_blossom(v, 3, [](std::span<const Eigen::Vector3d> a) {
    auto l1 = [](const Eigen::Vector3d& x) { return x.x() + 2 * x.y() - x.z() + 0.5; };
    auto l2 = [](const Eigen::Vector3d& x) { return 0.3 * x.x() - x.y() + 0.2 * x.z() + 1; };
    return (l1(a[0]) * l2(a[1]) + l1(a[1]) * l2(a[0])) / 2;
  });
  const std::size_t cells = v.domain().tetrahedra.size();
  Model model;
  model.objects.push_back({"", false, std::move(v), nullptr});
  const test_support::TemporaryDirectory dir;
  write_vtu(model, dir / "s.vtu");
  std::ofstream(dir / "check.py") << kScript;
  const std::string command = "/usr/bin/python3 " + (dir / "check.py").string() + " " + (dir / "s.vtu").string() + " >" + (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir / "out.txt");
  std::map<std::string, std::string> result;
  for (std::string line; std::getline(in, line);) {
    const auto space = line.find(' ');
    if (space != std::string::npos) result[line.substr(0, space)] = line.substr(space + 1);
  }
  ASSERT_TRUE(result.contains("max_error"));
  EXPECT_EQ(result.at("cells"), std::to_string(cells));
  EXPECT_EQ(result.at("types"), "24");
  EXPECT_EQ(result.at("checked"), std::to_string(3 * cells));
  EXPECT_LT(std::stod(result.at("max_error")), 1e-10);
}

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
