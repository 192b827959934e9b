#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

int TriangleMesh::add_vertex(const Eigen::Vector3d& position, const Eigen::Vector3d& parameter) {
  positions.push_back(position);
  parameters.push_back(parameter);
  return static_cast<int>(positions.size()) - 1;
}

void TriangleMesh::add_triangle(int a, int b, int c, int part) {
  triangles.push_back({a, b, c});
  parts.push_back(part);
}

void TriangleMesh::append(const TriangleMesh& other) {
  const int offset = static_cast<int>(positions.size());
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  parameters.insert(parameters.end(), other.parameters.begin(), other.parameters.end());
  for (const auto& t : other.triangles) triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  parts.insert(parts.end(), other.parts.begin(), other.parts.end());
}

TriangleMesh triangles_of_part(const TriangleMesh& mesh, int part) {
  TriangleMesh out;
  std::vector<int> index(mesh.num_vertices(), -1);
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    if (mesh.parts[t] != part) continue;
    std::array<int, 3> corners{};
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[t][static_cast<std::size_t>(k)]);
      if (index[v] < 0) index[v] = out.add_vertex(mesh.positions[v], mesh.parameters[v]);
      corners[static_cast<std::size_t>(k)] = index[v];
    }
    out.add_triangle(corners[0], corners[1], corners[2], part);
  }
  return out;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> TriangleMesh::bounding_box() const {
  if (positions.empty()) return {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Vector3d lo = positions.front(), hi = positions.front();
  for (const auto& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

}  // namespace volspline
