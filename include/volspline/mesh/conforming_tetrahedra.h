#pragma once
// A conforming tetrahedral mesh of some boxes of an adaptive (octree-like) tiling of a box by
// integer-lattice boxes: the tetrahedra of two boxes that touch share their faces exactly, even
// where a large box meets many small ones, so marching tetrahedra on it
// (mesh/marching_tetrahedra.h) gives a surface without cracks (Joy–Duchaineau 1999 §7, where the
// cells of the adaptive subdivision of §6 are split this way).
//
// Every face of a box is cut into rectangles, each the common part of the face and a face of the
// box across the plane (or the whole face on the boundary of the tiling); a rectangle is fanned
// from its centre over every lattice point of the tiling on its boundary, the same way from both
// sides; each triangle of the fan and the centre of the box make a tetrahedron. Nothing here
// knows about splines: the lattice is any integer grid.
#include <array>
#include <cstdint>
#include <vector>

namespace volspline {

/// A point of the integer lattice.
using LatticePoint = std::array<std::int64_t, 3>;

/// A box of the tiling: [origin, origin + extent) in each axis, and whether it is meshed.
struct LatticeBox {
  LatticePoint origin{};
  LatticePoint extent{};
  /// Meshed; the others only shape the faces of their meshed neighbours.
  bool kept = false;
};

/// The tetrahedra of the kept boxes: their corners, ids into `points`.
struct ConformingTetrahedralMesh {
  /// Every lattice point a tetrahedron uses, once, in the order the tetrahedra first use them.
  std::vector<LatticePoint> points;
  /// Each tetrahedron as (centre of its box, centre of a rectangle, two consecutive points on the
  /// rectangle's boundary).
  std::vector<std::array<int, 4>> tetrahedra;
};

/// The conforming tetrahedra of the kept boxes of `boxes`. The boxes must tile a box without
/// overlap, and along each axis any two of their intervals must be nested or disjoint (as the
/// cells of a dyadic subdivision are); every extent must be even, so that the centres of boxes
/// and of rectangles are lattice points. Whether they tile is not checked (the result is then
/// not conforming).
/// \throw InvalidInput if an extent is not positive and even.
ConformingTetrahedralMesh conforming_tetrahedra(const std::vector<LatticeBox>& boxes);

}  // namespace volspline
