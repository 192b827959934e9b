#pragma once
// The solid of a DMS spline volume shown cell by cell (Hua–He–Qin Fig. 1b, Fig. 13): every domain
// tetrahedron upsampled into k³ tetrahedra (the crack-free edgewise subdivision of
// extract/simplex_isosurface.h), each mapped by the volume's geometry at its corners and shrunk
// toward its centroid, so that the interior of the solid is seen between the cells.
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// Four outward triangles per cell, Part::DomainBoundary; parameters are the domain points.
/// \throw InvalidInput for k outside 1..16 or a shrink factor outside (0, 1].
TriangleMesh simplex_cell_mesh(const DmsSplineVolume& volume, int subdivisions, double shrink = 0.7);

}  // namespace volspline
