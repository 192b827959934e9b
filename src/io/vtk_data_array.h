#pragma once
// One <DataArray> of a VTK XML file in ascii, as the VTU writers write it (io/vtk_xml.cpp for
// Bézier cells, io/simplex_vtu.cpp for simplex spline volumes).
#include <string>

namespace volspline {

inline void vtk_data_array(std::string& out, const char* type, const std::string& name, int components, const std::string& values) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\"";
  if (!name.empty()) out += " Name=\"" + name + "\"";
  if (components > 1) out += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  out += " format=\"ascii\">\n          ";
  out += values;
  out += "\n        </DataArray>\n";
}

}  // namespace volspline
