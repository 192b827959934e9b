#pragma once
// The node order of VTK's arbitrary-order Lagrange tetrahedron (VTK_LAGRANGE_TETRAHEDRON, 71).
#include <array>
#include <vector>

namespace volspline {

// The nodes of an order-`order` Lagrange tetrahedron in VTK's order, each as integer barycentric
// coordinates (l0, l1, l2, l3) summing to `order` (node = sum l_i v_i / order). VTK orders them
// recursively: the four vertices; the edges (0,1), (1,2), (2,0), (0,3), (1,3), (2,3), each from its
// first vertex to its second; the faces (0,1,3), (2,3,1), (0,3,2), (0,2,1), each's interior as a
// Lagrange triangle of order - 3 with the same rule; the interior as a tetrahedron of order - 4.
// tests/io/vtk_lagrange_tetrahedron_test.cpp compares this with VTK's own parametric coordinates.
std::vector<std::array<int, 4>> vtk_lagrange_tetrahedron_nodes(int order);

}  // namespace volspline
