// The Lagrange tetrahedron's node order (io/vtk_lagrange_tetrahedron.h) against VTK's own:
// Debian's python3-vtk9 prints the parametric coordinates of every node of vtkLagrangeTetra of
// orders 1 to 7, and each must equal ours (l1, l2, l3) / order.
#include "io/vtk_lagrange_tetrahedron.h"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "support/temporary_directory.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

const char* kParametricScript = R"(import vtk
for order in range(1, 8):
    n = (order + 1) * (order + 2) * (order + 3) // 6
    cell = vtk.vtkLagrangeTetra()
    cell.GetPointIds().SetNumberOfIds(n)
    cell.GetPoints().SetNumberOfPoints(n)
    cell.Initialize()
    pc = cell.GetParametricCoords()
    print(order, ' '.join(repr(pc[i]) for i in range(3 * n)))
)";

TEST(VtkLagrangeTetrahedron, NodesAreVtksInVtksOrder) {
  if (std::system("/usr/bin/python3 -c 'import vtk' >/dev/null 2>&1") != 0) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (install python3-vtk9)";
  const test_support::TemporaryDirectory dir;
  std::ofstream(dir / "order.py") << kParametricScript;
  const std::string command = "/usr/bin/python3 " + (dir / "order.py").string() + " >" + (dir / "out.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir / "out.txt");
  int orders = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    int order = 0;
    fields >> order;
    const std::vector<std::array<int, 4>> nodes = vtk_lagrange_tetrahedron_nodes(order);
    ASSERT_EQ(nodes.size(), static_cast<std::size_t>((order + 1) * (order + 2) * (order + 3) / 6));
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      EXPECT_EQ(nodes[i][0] + nodes[i][1] + nodes[i][2] + nodes[i][3], order);
      for (std::size_t c = 1; c < 4; ++c) {
        double coordinate = 0;
        ASSERT_TRUE(fields >> coordinate) << "order " << order << " node " << i;
        EXPECT_NEAR(coordinate, static_cast<double>(nodes[i][c]) / order, 1e-12) << "order " << order << " node " << i << " coordinate " << c;
      }
    }
    ++orders;
  }
  EXPECT_EQ(orders, 7);
}

TEST(VtkLagrangeTetrahedron, EveryLatticePointOnceForEveryOrder) {
  for (int order = 1; order <= 10; ++order) {
    const std::vector<std::array<int, 4>> nodes = vtk_lagrange_tetrahedron_nodes(order);
    const std::set<std::array<int, 4>> distinct(nodes.begin(), nodes.end());
    EXPECT_EQ(distinct.size(), nodes.size());
    EXPECT_EQ(nodes.size(), static_cast<std::size_t>((order + 1) * (order + 2) * (order + 3) / 6));
    for (const auto& l : nodes)
      for (int c : l) EXPECT_GE(c, 0);
  }
  EXPECT_THROW(vtk_lagrange_tetrahedron_nodes(0), InvalidInput);
  EXPECT_THROW(vtk_lagrange_tetrahedron_nodes(11), InvalidInput);
}

}  // namespace
}  // namespace volspline
