#pragma once
// A simplex spline volume written as a VTK unstructured grid for ParaView: one Lagrange
// tetrahedron of order max(2, degree) per domain tetrahedron (VTK_QUADRATIC_TETRA for order 2,
// VTK_LAGRANGE_TETRAHEDRON above), its nodes (the tetrahedron's lattice points of that order,
// shared between neighbours) placed at the spline's geometry s(x) and carrying every attribute,
// so the curved solid and its fields show without a plug-in. Sampled, hence lossy: the model file
// is the exact form.
#include <string>

#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// \throw InvalidInput for an attribute name that clashes with the arrays written ("Tetrahedron").
std::string simplex_spline_vtu_text(const DmsSplineVolume& volume);

}  // namespace volspline
