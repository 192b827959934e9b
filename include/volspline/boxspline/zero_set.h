#pragma once
// The surface of a scene: the zero set of its box spline inside the box, of the primitives
// themselves outside it (Peters & Wittman 1995, §6 locality), as one welded triangle mesh.
//
// Two methods (§7):
//  * Control: the spline's coefficients after K refinements are the values at the lattice
//    points, face and cube centres get the averages of their corners, and marching tetrahedra
//    runs on that piecewise linear control function. No value of the spline is ever computed;
//    the coefficients converge to the function quadratically in the spacing.
//  * Exact: the same marching on the exact values of the spline at lattice points, face and
//    cube centres of the K-times refined lattice, vertices by linear interpolation along the
//    edges and, optionally, projected onto the zero set by Newton steps.
// Triangles from cubes whose centre lies in the box get Part::BlendSpline (the spline surface),
// the others Part::BlendPrimitive (the primitives; mesh/parts.h).
#include <optional>

#include "volspline/boxspline/implicit_scene.h"
#include "volspline/boxspline/lattice_field.h"
#include "volspline/core/progress.h"
#include "volspline/mesh/parts.h"
#include "volspline/mesh/triangle_mesh.h"

namespace volspline {

enum class ZeroSetMethod { Control, Exact };

struct ZeroSetOptions {
  /// Refinements K of the lattice before marching.
  int levels = 2;
  ZeroSetMethod method = ZeroSetMethod::Control;
  /// Exact method only: move each vertex onto the zero set (at most 8 Newton steps, never
  /// farther than one grid spacing).
  bool project = false;
  /// Fill ZeroSetStats beyond counts and seconds: evaluates the spline at every vertex and checks
  /// the edges (costs more than the meshing itself; benchmarks turn it off).
  bool statistics = true;
  /// Receives the phases "refinement", "values", "marching", "projection" and "statistics".
  /// Null: nobody listens.
  Progress* progress = nullptr;
};

struct ZeroSetStats {
  std::size_t vertices = 0, triangles = 0;
  /// Largest |f| at the vertices: the spline inside the box, the CSG function outside.
  double max_abs_value = 0.0;
  /// Largest distance of a vertex to the intended surface, where the scene is one sphere,
  /// plane, cylinder or torus (known distance functions); empty otherwise.
  std::optional<double> max_distance;
  /// Largest |spline − CSG function| at grid nodes in the box next to a cube that crosses both
  /// the box boundary and the surface: the size of the seam in function units (0 without a domain
  /// beyond the box).
  double seam_value_difference = 0.0;
  /// Grid spacing after refinement, h / 2^K.
  double grid_spacing = 0.0;
  std::size_t boundary_edges = 0, nonmanifold_edges = 0;
  bool closed = false;
  double seconds = 0.0;
};

struct ZeroSet {
  TriangleMesh mesh;
  ZeroSetStats stats;
};

/// The surface of `scene`. \throw InvalidInput for bad options or a lattice/grid that is too
/// large.
ZeroSet scene_zero_set(const Scene& scene, const ZeroSetOptions& options);

/// The surface of a given field inside [lo, hi] (which must lie in the field's domain), with
/// no primitives outside. \throw InvalidInput as scene_zero_set, or if the box is not in the
/// domain.
ZeroSet field_zero_set(const LatticeField& field, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const ZeroSetOptions& options);

/// The zero set of the pointwise (CSG) function of `node` over [lo, hi], marched on a grid of
/// the given spacing with exact values at all partition vertices; every triangle gets
/// Part::BlendPrimitive.
/// \throw InvalidInput for an empty box, bad spacing or too many grid nodes.
TriangleMesh implicit_zero_set(const SceneNode& node, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing);

/// Distance from x to the surface of a single primitive, where a closed form is simple (sphere,
/// plane, cylinder, torus); empty otherwise.
std::optional<double> primitive_distance(const ImplicitPrimitive& primitive, const Eigen::Vector3d& x);

}  // namespace volspline
