#pragma once
// Import of tetrahedral meshes (the domain Ω of a simplex spline) from what mesh generators
// write. docs/tetrahedral-domains.md describes each format as read.
//
// Errors are InvalidInput whose where() names the file as given and the place:
// "cube.mesh: line 12" for text formats, "grid.vtu: cell 17" for VTK files, "grid.vtu" alone
// for what the VTK library reports.
#include <filesystem>

#include "volspline/mesh/tetrahedral_mesh.h"

namespace volspline {

/// Reads tetrahedra from medit `.mesh` (Vertices/Tetrahedra sections), TetGen `.node` + `.ele`
/// (give either path; the other is found beside it), VTK `.vtu` (XML) and legacy `.vtk`
/// unstructured grids — the VTK ones with the VTK library (vtkXMLUnstructuredGridReader,
/// vtkUnstructuredGridReader), VTK_TETRA cells as tetrahedra.
/// Cells of lower dimension (vertices, edges, triangles, quadrilaterals and polygons: the
/// boundary elements medit and gmsh write beside the volume) add nothing to Ω and are skipped;
/// volume cells other than tetrahedra (hexahedra, wedges/prisms, pyramids, voxels, quadratic
/// tetrahedra, TetGen's 10-node elements) are an error naming the first one, since dropping
/// them would leave holes in Ω. Points that no tetrahedron uses are an error too (naming the
/// point), as in validate_tetrahedral_mesh.
/// Orients positively (orient_positively) and validates (validate_tetrahedral_mesh).
/// \throw IoError if a file cannot be opened; InvalidInput with the file name and line (or cell
/// index) for what is wrong in it, and for an extension other than .mesh, .node, .ele, .vtu, .vtk.
TetrahedralMesh read_tetrahedral_mesh(const std::filesystem::path& path);

}  // namespace volspline
