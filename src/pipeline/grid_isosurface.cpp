#include "volspline/pipeline/grid_isosurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/mesh/parts.h"

namespace volspline {

TriangleMesh grid_isosurface(const RegularGridData& grid, const std::string& attribute, double value) {
  const auto found = std::find(grid.attribute_names.begin(), grid.attribute_names.end(), attribute);
  if (found == grid.attribute_names.end()) {
    std::string names;
    for (const auto& n : grid.attribute_names) names += (names.empty() ? "" : ", ") + n;
    throw InvalidInput("the data have no attribute '" + attribute + "' (they have: " + (names.empty() ? "none" : names) + ")", "attribute");
  }
  if (!std::isfinite(value)) throw InvalidInput("the isovalue must be finite", "value");
  const auto column = static_cast<Eigen::Index>(found - grid.attribute_names.begin());
  const std::int64_t nx = static_cast<std::int64_t>(grid.axes[0].size()), ny = static_cast<std::int64_t>(grid.axes[1].size()),
                     nz = static_cast<std::int64_t>(grid.axes[2].size());
  auto id = [&](std::int64_t i, std::int64_t j, std::int64_t k) { return i + nx * (j + ny * k); };
  auto sample = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return MarchingTetrahedra::Sample{id(i, j, k),
                                      Eigen::Vector3d(grid.axes[0][static_cast<std::size_t>(i)], grid.axes[1][static_cast<std::size_t>(j)],
                                                      grid.axes[2][static_cast<std::size_t>(k)]),
                                      grid.values(id(i, j, k), column) - value};
  };
  MarchingTetrahedra marching;
  for (std::int64_t k = 0; k + 1 < nz; ++k)
    for (std::int64_t j = 0; j + 1 < ny; ++j)
      for (std::int64_t i = 0; i + 1 < nx; ++i) {
        std::array<MarchingTetrahedra::Sample, 8> corner;
        int positive = 0;
        for (int c = 0; c < 8; ++c) {
          corner[static_cast<std::size_t>(c)] = sample(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          positive += corner[static_cast<std::size_t>(c)].value >= 0;
        }
        if (positive == 0 || positive == 8) continue;
        for (const auto& t : kKuhnTetrahedra)
          marching.add_tetrahedron_oriented_by_corners({corner[static_cast<std::size_t>(t[0])], corner[static_cast<std::size_t>(t[1])],
                                                        corner[static_cast<std::size_t>(t[2])], corner[static_cast<std::size_t>(t[3])]});
      }
  TriangleMesh mesh;
  const Eigen::Vector3d low(grid.axes[0].front(), grid.axes[1].front(), grid.axes[2].front());
  const Eigen::Vector3d extent = Eigen::Vector3d(grid.axes[0].back(), grid.axes[1].back(), grid.axes[2].back()) - low;
  for (const Eigen::Vector3d& x : marching.vertices()) mesh.add_vertex(x, (x - low).cwiseQuotient(extent));
  for (const auto& t : marching.triangles()) mesh.add_triangle(t[0], t[1], t[2], Part::AttributeIsosurface);
  return mesh;
}

}  // namespace volspline
