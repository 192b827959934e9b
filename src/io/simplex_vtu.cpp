#include "simplex_vtu.h"
#include "vtk_data_array.h"
#include "vtk_lagrange_tetrahedron.h"

#include <algorithm>
#include <cstdint>
#include <map>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

std::string simplex_spline_vtu_text(const DmsSplineVolume& volume) {
  for (const std::string& name : volume.attribute_names())
    if (name == "Tetrahedron" || name.find_first_of("<>&\"") != std::string::npos)
      throw InvalidInput("an attribute named \"" + name + "\" cannot be written to VTK (a clash with an array volspline writes, or XML markup); rename it",
                         "attributes");
  const TetrahedralMesh& domain = volume.domain();
  // One Lagrange tetrahedron per domain tetrahedron, of the spline's degree (at least 2, so that
  // ParaView shows the curved solid even for degrees 0 and 1): degree 2 as VTK's 10-node
  // quadratic tetrahedron (24), higher degrees as VTK's Lagrange tetrahedron (71), whose nodes
  // sample the spline at the domain's lattice points of that order. A node shared by neighbouring
  // tetrahedra (on a common edge or face) is written once: its key is its (domain point, weight)
  // pairs, sorted.
  const int order = std::max(2, volume.degree());
  const std::vector<std::array<int, 4>> lattice = vtk_lagrange_tetrahedron_nodes(order);
  using NodeKey = std::array<std::pair<int, int>, 4>;
  std::map<NodeKey, int> node_index;
  std::vector<Eigen::Vector3d> nodes;
  std::string connectivity, offsets, types, tet_index;
  const std::string type = order == 2 ? "24 " : "71 ";
  std::int64_t offset = 0;
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    const auto& tet = domain.tetrahedra[t];
    for (const auto& l : lattice) {
      NodeKey key;
      key.fill({-1, 0});
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (std::size_t c = 0; c < 4; ++c) {
        if (l[c] == 0) continue;
        key[c] = {tet[c], l[c]};
        x += (static_cast<double>(l[c]) / order) * domain.points[static_cast<std::size_t>(tet[c])];
      }
      std::sort(key.begin(), key.end());
      const auto [it, added] = node_index.emplace(key, static_cast<int>(nodes.size()));
      if (added) nodes.push_back(x);
      connectivity += std::to_string(it->second) + ' ';
    }
    offset += static_cast<std::int64_t>(lattice.size());
    offsets += std::to_string(offset) + ' ';
    types += type;
    tet_index += std::to_string(t) + ' ';
  }
  DmsSplineEvaluator evaluator(volume);
  std::string points;
  std::vector<std::string> attributes(volume.attribute_names().size());
  for (const Eigen::Vector3d& x : nodes) {
    const DmsSplinePoint p = evaluator.evaluate(x);
    for (int c = 0; c < 3; ++c) points += format_double(p.value[c]) + ' ';
    for (std::size_t a = 0; a < attributes.size(); ++a) attributes[a] += format_double(p.value[static_cast<Eigen::Index>(3 + a)]) + ' ';
  }
  std::string out = "<?xml version=\"1.0\"?>\n";
  out += "<!-- written by volspline: a degree " + std::to_string(volume.degree()) +
         " simplex spline volume sampled on Lagrange tetrahedra of order " + std::to_string(order) + ", one per domain tetrahedron -->\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(nodes.size()) + "\" NumberOfCells=\"" + std::to_string(domain.tetrahedra.size()) + "\">\n";
  out += "      <PointData>\n";
  for (std::size_t a = 0; a < attributes.size(); ++a) vtk_data_array(out, "Float64", volume.attribute_names()[a], 1, attributes[a]);
  out += "      </PointData>\n      <CellData>\n";
  vtk_data_array(out, "Int64", "Tetrahedron", 1, tet_index);
  out += "      </CellData>\n      <Points>\n";
  vtk_data_array(out, "Float64", "Points", 3, points);
  out += "      </Points>\n      <Cells>\n";
  vtk_data_array(out, "Int64", "connectivity", 1, connectivity);
  vtk_data_array(out, "Int64", "offsets", 1, offsets);
  vtk_data_array(out, "UInt8", "types", 1, types);
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

}  // namespace volspline
