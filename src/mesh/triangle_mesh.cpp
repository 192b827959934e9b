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
