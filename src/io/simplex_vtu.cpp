#include "simplex_vtu.h"
#include "vtk_data_array.h"

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
  // Nodes: the domain's points, then one per edge (its midpoint), numbered in order of appearance.
  std::map<std::pair<int, int>, int> edge_nodes;
  std::vector<Eigen::Vector3d> nodes(domain.points.begin(), domain.points.end());
  static constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};  // VTK_QUADRATIC_TETRA order
  std::string connectivity, offsets, types, tet_index;
  int offset = 0;
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    const auto& tet = domain.tetrahedra[t];
    for (int c = 0; c < 4; ++c) connectivity += std::to_string(tet[static_cast<std::size_t>(c)]) + ' ';
    for (const auto& e : kEdges) {
      const int a = tet[static_cast<std::size_t>(e[0])], b = tet[static_cast<std::size_t>(e[1])];
      const auto [it, added] = edge_nodes.emplace(std::minmax(a, b), static_cast<int>(nodes.size()));
      if (added) nodes.push_back((domain.points[static_cast<std::size_t>(a)] + domain.points[static_cast<std::size_t>(b)]) / 2);
      connectivity += std::to_string(it->second) + ' ';
    }
    offset += 10;
    offsets += std::to_string(offset) + ' ';
    types += "24 ";
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
         " simplex spline volume sampled on quadratic tetrahedra, one per domain tetrahedron -->\n";
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
