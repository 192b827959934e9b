#pragma once
// Primary-knot placement from a fit's error (the global half of knot optimisation, Hua–He–Qin
// §5.1 step 3 and §5.2: "there should be more primary knots distributed in the region
// containing features"). The local step of §5.3 (knot_optimisation.h) moves sub-knots within a
// fraction of an edge; it cannot move knots from where the data are easy to where they are hard,
// which is what lowers the error at a fixed number of coefficients (measured: docs/fitting.md,
// "Knot optimisation"). Decision: error equidistribution. On a tetrahedron T of size h_T
// holding data fitted to RMS error e_T by degree n, e_T ≈ g_T h_T^(n+1) with g_T the size of the
// (n+1)st derivatives; minimising Σ_T g_T² h_T^(2n+2) h_T³ for a fixed number of tetrahedra
// (∫ h^-3 fixed) gives h ∝ g^(-1/(n+3)). That spacing, clamped to [1/r, r] times its median, is
// the sizing field of the farthest-point samples of the next domain (point_cloud_domain.h).
#include <vector>

#include "volspline/io/volume_data.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

struct KnotSpacingOptions {
  /// The spacing stays within [median / ratio, median × ratio].
  double ratio = 2.5;
};

/// One relative spacing per data point (median 1) from the per-tetrahedron errors `local` of a
/// fit of `volume` to `data`: h ∝ (e_T / h_T^(n+1))^(-1/(n+3)) for the tetrahedron T holding the
/// point, h_T the cube root of six times its volume (the edge of a cube of that volume, up
/// to a constant that the median removes). Points outside Ω, and tetrahedra fitted exactly,
/// get the largest spacing allowed. Deterministic.
std::vector<double> error_equidistributing_spacing(const DmsSplineVolume& volume, const VolumeData& data,
                                                   const TetrahedronFitErrors& local, const KnotSpacingOptions& options = {});

}  // namespace volspline
