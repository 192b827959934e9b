#pragma once
// VTK XML unstructured grids (.vtu, file version 2.2) holding the exact solid as rational Bézier
// cells, so that ParaView (5.9 or later) and VTK draw, slice and contour the spline itself rather
// than a tessellation. Conventions and what is kept: docs/formats.md.
//
// Every nonempty knot cell of every object becomes one cell (spline/bezier_extraction.h): a
// VTK_BEZIER_CURVE (75), VTK_BEZIER_QUADRILATERAL (77) or VTK_BEZIER_HEXAHEDRON (79), with its own
// (p+1)(q+1)(r+1) points in VTK's higher-order point order (vtk_bezier_point_order). VTK's Bézier
// cells take Cartesian points plus the point-data array named by the PointData attribute
// RationalWeights; the degrees are the 3-component cell-data array named by the CellData attribute
// HigherOrderDegrees. Attributes of the objects become point-data arrays of their Bézier
// coefficients, so VTK interpolates them exactly as volspline evaluates them (evaluate_attribute).
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "volspline/io/model_file.h"

namespace volspline {

/// VTK's point order for a Bézier cell of D = 1, 2 or 3 parameters and the given degrees (unused
/// entries ignored): element m is the control-point index (i, j, k) (0 for unused directions) of
/// VTK's point m. The order is VTK's higher-order cell order: the corners, then the interior
/// points of the edges, of the faces, and of the body (vtkHigherOrderHexahedron::PointIndexFromIJK).
std::vector<std::array<int, 3>> vtk_bezier_point_order(int parameters, const std::array<int, 3>& degrees);

/// The .vtu text of `model`. Point data: RationalWeights (when an object is rational), Jacobian
/// (det of d(x,y,z)/d(u,v,w) at each control point's own parameter (i/p, j/q, k/r) of its cell,
/// when every object is a volume in R^3), and one array per attribute name (NaN at the points of
/// objects that lack it). Cell data: HigherOrderDegrees, and Object (the index of the object
/// each cell comes from). Points with fewer than 3 coordinates are padded with zeros.
/// \throw InvalidInput for an object with more than 3 coordinates or malformed attributes.
std::string vtu_text(const Model& model);

/// Writes vtu_text(model) atomically. \throw IoError, InvalidInput as vtu_text.
void write_vtu(const Model& model, const std::filesystem::path& path);

/// Parses a .vtu file made of Bézier cells (types 75, 77, 79, as vtu_text writes them, ASCII data
/// arrays): every cell becomes one bezier_* object on [0, 1]^D, its point-data arrays other than
/// RationalWeights and Jacobian become attributes.
/// \throw InvalidInput "SOURCE: line L, /VTKFile/...: what was expected, got what" for malformed
/// XML, binary or appended data, other cell types, and wrong point counts (NumberOfPoints against
/// the Points array, a cell's point count against its degrees, indices out of range).
Model parse_vtu(std::string_view text, const std::string& source_name);

/// Reads and parses a .vtu file. \throw IoError, InvalidInput as parse_vtu.
Model read_vtu(const std::filesystem::path& path);

}  // namespace volspline
