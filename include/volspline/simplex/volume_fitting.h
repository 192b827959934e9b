#pragma once
// Fitting scattered volume data with a trivariate DMS spline (Hua–He–Qin §5.1–5.2, eq. 10):
// the domain from the data (mesh/point_cloud_domain.h), generated knot clouds, and the control
// vectors — geometry and every attribute together — by least squares at the data points, whose
// positions are their own parameters:  min Σ_i |p_i − s(x_i, y_i, z_i)|².
// Knot optimisation (§5.3, simplex/knot_optimisation.h) and adaptive refinement (§5.4,
// simplex/adaptive_refinement.h) follow in fit_volume_data when asked for (docs/fitting.md).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "volspline/io/volume_data.h"
#include "volspline/mesh/point_cloud_domain.h"
#include "volspline/simplex/dms_spline_volume.h"

namespace volspline {

/// How long each phase took (seconds of wall-clock time).
struct FitPhase {
  std::string name;
  double seconds = 0;
};

/// The fitting error of one attribute at the data points inside Ω.
struct AttributeFitError {
  std::string name;
  /// The data range at those points; normalised errors divide by max − min (by 1 if constant),
  /// i.e. they are the errors of the data mapped to [0, 1].
  double data_min = 0, data_max = 0;
  double mean_square = 0, max_abs = 0;
  double normalised_mean_square = 0, normalised_max_abs = 0;
};

/// How eq. 10's least squares were solved.
struct LeastSquaresSolve {
  /// SimplicialLDLT (true) or conjugate gradients.
  bool direct = true;
  int tikhonov_steps = 0;
  /// Conjugate-gradient iterations of all solves (0 when direct).
  int iterations = 0;
};

struct VolumeFitErrors {
  /// Data points, those inside Ω (fitted), those outside (not fitted, not in the errors).
  std::size_t data_points = 0, fitted_points = 0, outside_points = 0;
  /// Mean and largest squared distance |s_xyz(x_i) − x_i|², raw and divided by the square of
  /// the data's largest bounding-box side (geometry mapped into [0, 1]³).
  double geometric_mean_square = 0, geometric_max = 0;
  double normalised_geometric_mean_square = 0, normalised_geometric_max = 0;
  double geometric_scale = 1;
  std::vector<AttributeFitError> attributes;
  LeastSquaresSolve solver;
};

struct ControlVectorFitOptions {
  /// λ of the Tikhonov term as a fraction of the normal matrix's mean diagonal.
  double regularisation = 1e-8;
  /// Iterated Tikhonov steps (src/simplex/control_fit.h), so that the bias of the
  /// regularisation vanishes where the data determine the coefficients.
  int refinement_steps = 40;
  /// Up to this many control vectors the normal equations are factored (SimplicialLDLT), above
  /// it they are solved by conjugate gradients with an incomplete Cholesky preconditioner.
  long direct_limit = 8000;
  double iterative_tolerance = 1e-13;
  /// Each conjugate-gradient solve runs to this fraction of its right-hand side; the iterated
  /// Tikhonov steps refine it (src/simplex/volume_fitting_solver.h).
  double inner_tolerance = 1e-6;
  /// Weight of the fairing term of the attribute columns relative to the data term (0: none):
  /// the squared finite differences of order n + 1 of the spline along stencils in every domain
  /// tetrahedron, which vanish on polynomials of degree <= n (such a polynomial minimises both
  /// terms), while oscillations between data points (basis functions that few data points see,
  /// next to the boundary) are damped. The geometry is fitted without it. docs/fitting.md,
  /// "Fairing".
  double fairing = 0;
  /// The prior of the attribute columns (and the conjugate gradients' start) is the volume's
  /// current values there instead of the data mean: for refits after a refinement or a knot
  /// move, where the old fit is a good guess.
  bool prior_from_volume = false;
};

/// Solves eq. 10 for the control vectors of `volume` with its domain and knots fixed: columns
/// x, y, z fitted to the data positions and one attribute column per data attribute (added to
/// the volume where it lacks them; the volume's other attributes are left alone). The prior of
/// the regularisation is the identity geometry and the data mean of each attribute, which a
/// coefficient no data point sees keeps.
/// \throw InvalidInput if the data fail validate_volume_data, or fewer data points lie inside
/// Ω than the volume has control vectors (too few points for the degree and domain).
/// `phases`, if given, gets the time of the basis matrix, the normal equations, the
/// factorisation (or preconditioner), the solve and the errors.
VolumeFitErrors fit_control_vectors(DmsSplineVolume& volume, const VolumeData& data, const ControlVectorFitOptions& options = {},
                                    std::vector<FitPhase>* phases = nullptr);

/// The errors of `volume` at the data (as fit_control_vectors reports them).
VolumeFitErrors volume_fit_errors(const DmsSplineVolume& volume, const VolumeData& data);

// The options and report of adaptive refinement (simplex/adaptive_refinement.h, §5.4).
struct AdaptiveRefinementOptions {
  /// ε; refinement runs only for ε > 0.
  double error = 0;
  /// The most domain tetrahedra (0: 8 times the initial number).
  std::size_t max_tetrahedra = 0;
  /// Wall-clock seconds for the whole refinement (0: none); checked between rounds.
  double seconds = 0;
  int max_rounds = 30;
  /// The knot-cloud spread of new vertices (fit_volume_data passes its own).
  double spread = 0.15;
};

enum class RefinementStop {
  NotRequested,  // ε = 0
  Converged,     // every tetrahedron below ε
  TetrahedronBudget,
  TimeBudget,
  RoundBudget,
  ErrorIncreased,  // the last round's refit raised the total error: undone
  NoValidSplit,    // no split gave valid knot clouds
  TooFewPoints,    // more control vectors than data points in Ω
};

struct RefinementRound {
  std::size_t tetrahedra = 0, control_points = 0;
  /// Tetrahedra above ε before this round's splits, and how many were split.
  std::size_t above = 0, split = 0;
  /// Mean over the attributes of the normalised field mean square error, and the largest
  /// tetrahedron error, after the round's fit.
  double field_mean_square = 0, largest_tetrahedron_error = 0;
  double seconds = 0;
  bool undone = false;
};

struct AdaptiveRefinementReport {
  /// Round 0 is the fit before refinement.
  std::vector<RefinementRound> rounds;
  RefinementStop stop = RefinementStop::NotRequested;
  /// Tetrahedra still above ε at the end.
  std::size_t above = 0;
};

// The options and report of local knot optimisation (simplex/knot_optimisation.h, §5.3).
/// Knot placement and the local knot step judge their moves on every kKnotHoldOut-th data point
/// (every_nth_point(data, kKnotHoldOut, kKnotHoldOut / 2, true)), fitted to the others.
inline constexpr std::size_t kKnotHoldOut = 8;

struct KnotOptimisationOptions {
  bool enabled = false;
  /// Vertices whose 1-ring error (RMS normalised field error of the data in the tetrahedra
  /// around them) is above this move their knots; 0: above the mean over the vertices.
  double threshold = 0;
  /// Passes over the vertices, each followed by a fit of all control vectors (eq. 10).
  int sweeps = 2;
  /// Levenberg–Marquardt iterations per vertex.
  int iterations = 5;
  /// The most data points of a 1-ring the objective looks at (evenly strided, deterministic).
  int ring_points = 96;
  /// Knots keep at least this distance from each other and the vertex, and sub-knots stay within
  /// max_radius of the vertex, as fractions of the vertex's shortest edge.
  double min_distance = 0.04, max_radius = 0.45;
  /// The primary knot (the vertex) moves with its sub-knots where that leaves Ω unchanged: freely
  /// inside, within the plane of a flat boundary, along a straight feature line (two planes);
  /// corners and vertices of a curved boundary stay (docs/fitting.md, "The local step"). Over all
  /// sweeps it stays within primary_radius of where the optimisation found it (a fraction of its
  /// shortest edge then), and each of its tetrahedra keeps min_volume_fraction of its volume then.
  bool move_primary_knots = true;
  double primary_radius = 0.25, min_volume_fraction = 0.25;
  /// Before the local step: rounds of primary-knot placement from the error (knot_placement.h:
  /// the domain made again with as many primary knots, spaced by error equidistribution, within
  /// spacing_ratio of the median spacing); a round is kept only if its fit is better.
  int placement_rounds = 3;
  double spacing_ratio = 2.5;
  /// After the placement, the local step of §5.3 (sub-knots by Levenberg–Marquardt, `sweeps`
  /// passes); false: placement only (`--knots place`).
  bool local = true;
  /// The local step's sweeps are judged on held-out data, as the placement's rounds: every
  /// kKnotHoldOut-th point is left out of the objective and the refits, a sweep is kept only if
  /// the error there falls, and the knots kept are fitted to all the data at the end (so the
  /// error at the data may end above where it began). false, or fewer than 16 held-out points:
  /// judged at the data (a sweep is kept only if the error there falls).
  bool held_out = true;
};

struct KnotPlacementReport {
  /// Placement rounds made, and the round kept (0: none): the one of lowest error at the
  /// held-out data (every 8th point, not fitted while rounds are judged), if below the first fit's.
  int rounds = 0, kept = 0;
  /// Domains without valid knot clouds (each tempers the spacing; three in a row end the rounds).
  int failed = 0;
  /// The mean normalised field mean square error at all data (the final fits) and at the
  /// held-out points (the fits to the others), before and after.
  double before = 0, after = 0, held_out_before = 0, held_out_after = 0;
  /// The fairing weight of the fits that judged the rounds and of the kept layout's final fit
  /// (at least 0.1; 0 when no round was kept: the first fit stays, with the options' fairing).
  double fairing = 0;
};

struct KnotOptimisationReport {
  int sweeps = 0;
  /// Vertices above the threshold (each sweep), and those whose knots moved.
  std::size_t vertices_tried = 0, vertices_moved = 0;
  /// Of those moved, the vertices whose primary knot moved too (summed over the sweeps, as
  /// vertices_moved).
  std::size_t primary_knots_moved = 0;
  /// The mean normalised field mean square error at all the data before and after (after ≤
  /// before when judged at the data), and, when judged on held-out data, at the held-out points
  /// of the fits to the others before and after (after ≤ before: a sweep that raised it is
  /// undone).
  double before = 0, after = 0, held_out_before = 0, held_out_after = 0;
  /// Whether the sweeps were judged on held-out data (KnotOptimisationOptions::held_out).
  bool judged_on_held_out = false;
  /// Sweeps kept (their knots are the result) and undone; with none kept the fit is the one given.
  int kept_sweeps = 0, undone_sweeps = 0;
};

struct VolumeFitOptions {
  int degree = 2;
  /// Sharp features (§4.2): where > 0, neighbouring data points whose values (each attribute
  /// normalised to [0, 1]) differ by more than this are on two sides of a jump; the two regions
  /// this makes (mesh/material_interface.h) get the surface between them as a domain interface
  /// (mesh/interface_split.h), with knots on it and no control vector shared across it, so the
  /// fit jumps there. 0: off. docs/fitting.md, "Sharp features".
  double jump = 0;
  /// primary_knots 0: points / (4 C(n + 2, 2)), at least 4 (points / 24 for degree 2).
  PointCloudDomainOptions domain;
  /// Knot cloud spread (knot_clouds.h).
  double spread = 0.15;
  /// Data on a complete regular grid (is_complete_grid: images, generated grids) get the lattice
  /// layout (domain.lattice); not with a jump or knot optimisation (they place knots at data
  /// points). false: the layout as given. docs/fitting.md, "Grid data".
  bool grid_layout = true;
  /// Where fit.fairing is 0 the fit is faired with this weight (0: unfaired), except with a jump
  /// (its fits were measured unfaired; fairing stencils stay on their side of the interface):
  /// unfaired, basis functions next to ∂Ω that few data see ring between the samples
  /// (docs/fitting.md, "Fairing").
  double default_fairing = 0.1;
  ControlVectorFitOptions fit;
  AdaptiveRefinementOptions refinement;
  KnotOptimisationOptions knots;
};

/// What the sharp-feature step did (VolumeFitOptions::jump).
struct SharpFeatureReport {
  bool enabled = false;
  /// Data points per region, neighbour pairs across the jump, samples of the interface.
  std::vector<std::size_t> region_points;
  std::size_t jump_edges = 0, interface_samples = 0;
  /// Domain tetrahedra cut, points moved onto the interface, points on it (before duplication).
  std::size_t cut_tetrahedra = 0, snapped_points = 0, interface_points = 0;
  /// Data points that lie on the other side of the estimated interface than their region: not
  /// fitted (they would pull the other material's coefficients), but in the errors.
  std::size_t points_across = 0;
};

struct VolumeFitStatistics {
  /// Table 1 of the paper: data points, domain tetrahedra, control points, knots (all knots of
  /// all clouds: vertices × (n + 1)), primary knots (domain vertices).
  std::size_t data_points = 0, delaunay_tetrahedra = 0, domain_tetrahedra = 0, control_points = 0, knots = 0, primary_knots = 0;
  /// Boundary vertices by kind (§5.2).
  std::size_t corner_vertices = 0, curve_vertices = 0, general_vertices = 0;
  /// The primary-knot layout used ("farthest" or "lattice") and the fairing weight of the fit.
  std::string layout;
  double fairing = 0;
  VolumeFitErrors errors;
  std::vector<FitPhase> phases;
  AdaptiveRefinementReport refinement;
  KnotOptimisationReport knot_optimisation;
  KnotPlacementReport knot_placement;
  SharpFeatureReport sharp_features;
};

struct VolumeFit {
  DmsSplineVolume volume;
  VolumeFitStatistics statistics;
};

/// The whole fit: domain, knot clouds, control vectors, then adaptive refinement when
/// options.refinement.error > 0. `progress`, if given, hears each phase's name as it starts.
/// \throw InvalidInput for bad data (validate_volume_data), too few or coplanar points, a degree
/// outside 1..5, or a domain whose knot clouds cannot be made valid.
VolumeFit fit_volume_data(const VolumeData& data, const VolumeFitOptions& options = {},
                          const std::function<void(const std::string& phase)>& progress = {});

}  // namespace volspline
