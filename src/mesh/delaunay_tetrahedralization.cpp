#include "volspline/mesh/delaunay_tetrahedralization.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "exact_orientation.h"
#include "volspline/core/error.h"

namespace volspline {
namespace {

using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, exact::Kernel>;
using CellBase = CGAL::Delaunay_triangulation_cell_base_3<exact::Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<exact::Kernel, DataStructure>;

std::string point_name(std::size_t i) { return "points[" + std::to_string(i) + "]"; }

}  // namespace

TetrahedralMesh delaunay_tetrahedralization(std::span<const Eigen::Vector3d> points) {
  if (points.size() < 4) {
    throw InvalidInput("a Delaunay tetrahedralisation needs at least 4 points, got " + std::to_string(points.size()),
                       "points");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput("coordinate is not finite", point_name(i));
  }
  // Duplicates are found by sorting, before CGAL silently merges them.
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  const auto lexicographic = [&](int a, int b) {
    const auto& p = points[a];
    const auto& q = points[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(q.x(), q.y(), q.z(), b);
  };
  std::sort(order.begin(), order.end(), lexicographic);
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (points[order[k]] == points[order[k - 1]]) {
      throw InvalidInput("duplicate of " + point_name(order[k - 1]) + "; a tetrahedralisation needs distinct points",
                         point_name(order[k]));
    }
  }

  std::vector<std::pair<exact::Point, int>> input;
  input.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) input.emplace_back(exact::to_cgal(points[i]), static_cast<int>(i));
  // The range insertion sorts spatially (Hilbert order) by the coordinates alone, so the
  // triangulation does not depend on the order of `points`.
  const Delaunay triangulation(input.begin(), input.end());
  if (triangulation.dimension() < 3) {
    throw InvalidInput("all " + std::to_string(points.size()) + " points are " +
                           (triangulation.dimension() == 2 ? "coplanar" : "collinear") + "; nothing to tetrahedralise",
                       "points");
  }

  TetrahedralMesh mesh;
  mesh.points.assign(points.begin(), points.end());
  mesh.tetrahedra.reserve(triangulation.number_of_finite_cells());
  for (auto cell = triangulation.finite_cells_begin(); cell != triangulation.finite_cells_end(); ++cell) {
    std::array<int, 4> t;
    for (int k = 0; k < 4; ++k) t[k] = cell->vertex(k)->info();
    mesh.tetrahedra.push_back(t);
  }
  // CGAL's cells are positively oriented; sorting makes the order independent of CGAL's memory
  // layout.
  for (auto& t : mesh.tetrahedra) {
    // Rotate the smallest index to the front by an even permutation (orientation kept).
    const int m = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    static constexpr std::array<std::array<int, 4>, 4> kEven{{{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}}};
    const std::array<int, 4> old = t;
    for (int k = 0; k < 4; ++k) t[k] = old[kEven[m][k]];
  }
  std::sort(mesh.tetrahedra.begin(), mesh.tetrahedra.end());
  return mesh;
}

}  // namespace volspline
