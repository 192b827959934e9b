#pragma once
// A free-form deformation example for the demo and the docs: a bar bent and twisted by a
// segmented lattice (Lasser 1994, §III.2).
#include "volspline/deform/lattice.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct FfdExample {
  /// The undeformed bar, 4 x 1 x 1, as a finely subdivided closed mesh.
  TriangleMesh mesh;
  /// A degree (3, 2, 2) lattice with 3 cells along the bar, its control points lifted by
  /// 1.2 sin(pi s) and turned by 0.9 s radians about the bar's axis (s the lattice coordinate
  /// along the bar).
  Lattice lattice;
};

/// Every input is a constant, so this throws nothing but std::bad_alloc.
FfdExample bent_bar_ffd_example();

}  // namespace volspline
