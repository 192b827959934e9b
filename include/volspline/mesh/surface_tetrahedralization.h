#pragma once
// Tetrahedralising the inside of a closed triangle mesh with CGAL's Mesh_3: the domain Ω of a
// simplex spline from a boundary surface (Hua–He–Qin Fig. 6, the bunny).
// docs/tetrahedral-domains.md.
#include "volspline/mesh/tetrahedral_mesh.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

struct SurfaceTetrahedralizationOptions {
  double cell_size = 0;       /* 0: bounding-box diagonal / 20 */
  double facet_distance = 0;  /* 0: cell_size/10 */
  int seed = 0;
};

/// Tetrahedralises the inside of a closed, consistently oriented triangle mesh by CGAL Mesh_3 and
/// returns a validated TetrahedralMesh. \throw InvalidInput if the surface is not closed or not
/// consistently oriented (located at `triangles`).
/// The domain is Polyhedral_mesh_domain_with_features_3: edges whose faces meet at more than 60°
/// are protected (edge size `cell_size`), so flat faces and sharp edges are kept exactly.
/// Mesh_3 criteria: cell size and facet size `cell_size`, facet distance (the largest distance
/// from a boundary facet's circumcentre to the surface) `facet_distance`, facet angle >= 25°,
/// cell radius-edge ratio <= 3; slivers are then removed by exudation (no perturbation).
/// Sequential, every random choice of Mesh_3 draws from a generator seeded by `seed`, and
/// exudation has no time limit (make_mesh_3's default stops it after as long as refinement took),
/// so the same input and options give the same mesh whatever the machine's load. The tetrahedra approximate the inside: their
/// boundary lies within about `facet_distance` of the surface, not on it.
/// \throw InvalidInput also (located at `triangles[i]`) for a triangle CGAL cannot add (a
/// repeated corner or a non-manifold configuration), for an empty surface, and (located at
/// `cell_size` / `facet_distance`) for negative or non-finite sizes.
TetrahedralMesh tetrahedralize_closed_surface(const TriangleMesh& surface, const SurfaceTetrahedralizationOptions& options = {});

}  // namespace volspline
