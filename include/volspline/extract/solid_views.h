#pragma once
// One request for everything Lasser 1994 §IV shows of a solid's inside — families of
// isoparametric surfaces (Figs. 8, 9), the three through a point (Fig. 10), cross sections and
// series of parallel slices (Figs. 11, 12), the core section (Fig. 13) and paddlewheel probes —
// turned into one mesh per volume, so that several patches of a model are cut by the same
// planes.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "volspline/extract/planar_slices.h"
#include "volspline/mesh/triangle_mesh.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

struct SolidViewRequest {
  struct Family {
    int direction;  // 0 = u, 1 = v, 2 = w
    int count;
  };
  struct Series {
    int axis;  // 0 = x, 1 = y, 2 = z
    int count;
  };
  struct Paddlewheel {
    int axis;  // 0 = x, 1 = y, 2 = z: the direction of the common line
    int count;
    /// A point of the common line; the centre of the solids' box when absent.
    std::optional<Eigen::Vector3d> point;
  };
  std::vector<Family> families;
  /// Parameters (u, v, w) of the point the three isoparametric surfaces pass through.
  std::optional<std::array<double, 3>> through;
  std::vector<Series> series;
  /// Single cross sections.
  std::vector<Plane> planes;
  /// The point of a core section (three orthogonal slices), in space.
  std::optional<Eigen::Vector3d> core;
  std::vector<Paddlewheel> paddlewheels;
  /// Also the six boundary faces (opaque: they hide what is inside).
  bool faces = false;
  /// Draw the faces with a wedge cut away — the part on the positive side of every cross
  /// section and core plane — so those slices are seen in place inside the solid; each such
  /// slice is trimmed to the wedge's wall. Implies `faces`.
  bool cutaway = false;
  /// Segments per parameter direction for every surface (plus every knot).
  int resolution = 32;

  /// True if nothing but the faces is asked for.
  bool probes_empty() const;
};

/// Every plane of the request (cross sections, series, core, paddlewheels) for solids whose
/// box is [lo, hi]. \throw InvalidInput for an axis not 0..2, a count < 1 or non-finite input.
std::vector<Plane> requested_planes(const SolidViewRequest& request, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// The planes that bound the cut-away wedge (cross sections, then the core planes) when
/// request.cutaway, else none; a subset of requested_planes.
std::vector<Plane> cut_planes(const SolidViewRequest& request);

/// The mesh of `volume` for the request: its faces if asked for, its isoparametric surfaces
/// (parts 7..9) and its slices by `planes` (part 10), every vertex with its parameters.
/// \throw InvalidInput as the underlying constructions (a `through` point outside the domain,
/// control points not in R^3, resolution < 1).
TriangleMesh solid_view_mesh(const BSplineVolume& volume, const SolidViewRequest& request, const std::vector<Plane>& planes);

}  // namespace volspline
