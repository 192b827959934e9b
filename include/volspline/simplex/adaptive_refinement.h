#pragma once
// Local adaptive refinement of a volume-data fit (Hua–He–Qin §5.1 step 4, §5.4): every domain
// tetrahedron whose fitting error stays above ε is split 1 → 4 at the point where the fitted
// attributes' gradient is largest, the control vectors are fitted again (eq. 10, all of them, as
// the paper does instead of polar-form knot insertion), and this repeats until every tetrahedron
// is below ε or a budget (tetrahedra, time, rounds) is reached. Decisions (docs/fitting.md,
// "Adaptive refinement"): the error of a tetrahedron is the root mean square, over the data
// points it holds and the attributes, of the normalised attribute error (data mapped to [0, 1]);
// the split point is the data point of largest normalised gradient magnitude pulled halfway to
// the centroid (so the four new tetrahedra are not flat); the spline spaces before and after a
// split are not nested for DMS splines, so a round whose refit raises the total error is undone
// and ends the refinement — the error never increases, and the report says why it stopped.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "volspline/io/volume_data.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline {

/// Per domain tetrahedron: the data points it holds (each point in one: the evaluator's
/// tetrahedron), the root mean square normalised attribute error there, and the candidate split
/// point (the held data point of largest Σ_a |∇s_a| / range_a).
struct TetrahedronFitErrors {
  /// Per data point: its tetrahedron (−1 outside Ω).
  std::vector<int> point_tetrahedron;
  std::vector<std::size_t> points;
  std::vector<double> rms;
  std::vector<Eigen::Vector3d> steepest;
};

/// The per-tetrahedron errors of `volume` at the data (attributes matched by name).
/// \throw InvalidInput if the volume lacks one of the data's attributes.
TetrahedronFitErrors tetrahedron_fit_errors(const DmsSplineVolume& volume, const VolumeData& data);

/// A phrase for the report ("converged: every tetrahedron below the error bound", ...).
std::string refinement_stop_text(RefinementStop stop);

/// The mean over attributes of the normalised field mean square error (the refinement's total).
double mean_normalised_field_error(const VolumeFitErrors& errors);

/// Refines a fitted `volume` (with `errors` its current errors, updated) as described above.
/// `after_round`, if given, is called after every round (progress reports).
AdaptiveRefinementReport refine_volume_fit(DmsSplineVolume& volume, VolumeFitErrors& errors, const VolumeData& data,
                                           const AdaptiveRefinementOptions& options, const ControlVectorFitOptions& fit_options,
                                           const std::function<void(const RefinementRound&)>& after_round = {});

}  // namespace volspline
