#include "volspline/simplex/volume_fitting.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "volume_fitting_assembly.h"
#include "volume_fitting_solver.h"
#include "volspline/core/error.h"
#include "volspline/core/binomial.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/knot_clouds.h"
#include "volspline/simplex/knot_optimisation.h"

namespace volspline {
namespace {

class PhaseClock {
 public:
  explicit PhaseClock(std::vector<FitPhase>& phases) : phases_(phases), start_(std::chrono::steady_clock::now()) {}
  void done(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    phases_.push_back({name, std::chrono::duration<double>(now - start_).count()});
    start_ = now;
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::vector<FitPhase>& phases_;
  std::chrono::steady_clock::time_point start_;
};

// Values of all columns of the volume at the data points (rows outside Ω: 0) and whether each
// point lies in Ω (its basis functions sum to 1 there, to 0 outside).
struct Collocation {
  Eigen::SparseMatrix<double, Eigen::RowMajor> a;
  std::vector<bool> inside;
};

Collocation collocation(const DmsSplineVolume& volume, const VolumeData& data) {
  Collocation c{parallel_basis_matrix(volume, data.points), {}};
  const Eigen::VectorXd sums = c.a * Eigen::VectorXd::Ones(c.a.cols());
  c.inside.resize(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) c.inside[i] = sums[static_cast<Eigen::Index>(i)] > 0.5;
  return c;
}

// The fairing rows (docs/fitting.md, "Fairing"): in every domain tetrahedron one forward
// difference of order n + 1 of the spline, Σ_k (−1)^(n+1−k) C(n+1, k) s(g + k h d), from the
// centroid g along one axis d (x, y, z in turn over the tetrahedra, −d where +d leaves Ω), with
// n + 1 steps h spanning half the tetrahedron's shortest edge. A difference of order n + 1 is 0
// for every polynomial of degree <= n, so the term never pulls away from such a polynomial;
// stencils that do not fit inside Ω either way are left out.
Eigen::SparseMatrix<double, Eigen::RowMajor> fairing_rows(const DmsSplineVolume& volume) {
  const TetrahedralMesh& domain = volume.domain();
  const int order = volume.degree() + 1;
  const DmsSplineEvaluator locator(volume);
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    const auto& v = domain.tetrahedra[t];
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    double shortest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 4; ++i) {
      g += 0.25 * domain.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])];
      for (int j = i + 1; j < 4; ++j)
        shortest = std::min(shortest, (domain.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])] -
                                       domain.points[static_cast<std::size_t>(v[static_cast<std::size_t>(j)])]).norm());
    }
    const double h = 0.5 * shortest / order;
    for (const double sign : {1.0, -1.0}) {
      const Eigen::Vector3d step = sign * h * Eigen::Vector3d::Unit(static_cast<Eigen::Index>(t % 3));
      bool fits = true;
      for (int k = 1; k <= order && fits; ++k) fits = locator.locate(g + k * step) >= 0;
      if (!fits) continue;
      for (int k = 0; k <= order; ++k) {
        points.push_back(g + k * step);
        weights.push_back(((order - k) % 2 ? -1.0 : 1.0) * static_cast<double>(binomial_coefficient(order, k)));
      }
      break;
    }
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor> values = parallel_basis_matrix(volume, points);
  // A stencil counts only if the basis sums to 1 at each of its points (inside Ω as the basis
  // matrix sees it, not merely within the locator's rounding margin): then its weights, which
  // sum to 0, annihilate every polynomial of degree <= n exactly.
  const Eigen::VectorXd sums = values * Eigen::VectorXd::Ones(values.cols());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::Index stencils = 0;
  for (Eigen::Index first = 0; first + order < values.rows(); first += order + 1) {
    bool inside = true;
    for (int k = 0; k <= order; ++k) inside = inside && std::abs(sums[first + k] - 1) < 1e-9;
    if (!inside) continue;
    for (Eigen::Index r = first; r <= first + order; ++r)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(values, r); it; ++it)
        entries.emplace_back(stencils, it.col(), weights[static_cast<std::size_t>(r)] * it.value());
    ++stencils;
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows(stencils, values.cols());
  rows.setFromTriplets(entries.begin(), entries.end());
  return rows;
}

std::vector<int> attribute_columns(DmsSplineVolume& volume, const VolumeData& data) {
  std::vector<int> columns;
  for (const auto& name : data.attribute_names) {
    const auto& names = volume.attribute_names();
    if (std::find(names.begin(), names.end(), name) == names.end()) volume.add_attribute(name);
    columns.push_back(volume.attribute_column(name));
  }
  return columns;
}

VolumeFitErrors errors_at(const Eigen::MatrixXd& values, const VolumeData& data, const std::vector<bool>& inside,
                          const std::vector<int>& columns) {
  VolumeFitErrors e;
  e.data_points = data.size();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const auto& p : data.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  e.geometric_scale = data.size() ? std::max((hi - lo).maxCoeff(), 1e-300) : 1;
  const std::size_t k = columns.size();
  e.attributes.resize(k);
  for (std::size_t a = 0; a < k; ++a) {
    e.attributes[a].name = data.attribute_names[a];
    e.attributes[a].data_min = INFINITY;
    e.attributes[a].data_max = -INFINITY;
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (!inside[i]) {
      ++e.outside_points;
      continue;
    }
    ++e.fitted_points;
    const auto r = static_cast<Eigen::Index>(i);
    const double g = (values.row(r).head<3>().transpose() - data.points[i]).squaredNorm();
    e.geometric_mean_square += g;
    e.geometric_max = std::max(e.geometric_max, g);
    for (std::size_t a = 0; a < k; ++a) {
      const double d = data.attributes(r, static_cast<Eigen::Index>(a));
      const double error = values(r, columns[a]) - d;
      auto& f = e.attributes[a];
      f.data_min = std::min(f.data_min, d);
      f.data_max = std::max(f.data_max, d);
      f.mean_square += error * error;
      f.max_abs = std::max(f.max_abs, std::abs(error));
    }
  }
  const double n = std::max<double>(1, static_cast<double>(e.fitted_points));
  e.geometric_mean_square /= n;
  e.normalised_geometric_mean_square = e.geometric_mean_square / (e.geometric_scale * e.geometric_scale);
  e.normalised_geometric_max = e.geometric_max / (e.geometric_scale * e.geometric_scale);
  for (auto& f : e.attributes) {
    if (e.fitted_points == 0) f.data_min = f.data_max = 0;
    f.mean_square /= n;
    const double range = f.data_max > f.data_min ? f.data_max - f.data_min : 1;
    f.normalised_mean_square = f.mean_square / (range * range);
    f.normalised_max_abs = f.max_abs / range;
  }
  return e;
}


}  // namespace

VolumeFitErrors fit_control_vectors(DmsSplineVolume& volume, const VolumeData& data, const ControlVectorFitOptions& options,
                                    std::vector<FitPhase>* phases) {
  validate_volume_data(data, "the data");
  std::vector<FitPhase> ignored;
  PhaseClock clock(phases ? *phases : ignored);
  const std::vector<int> columns = attribute_columns(volume, data);
  const Collocation c = collocation(volume, data);
  clock.done("basis matrix");
  const std::size_t fitted = static_cast<std::size_t>(std::count(c.inside.begin(), c.inside.end(), true));
  if (fitted < static_cast<std::size_t>(volume.control_vector_count()))
    throw InvalidInput(std::to_string(fitted) + " of the " + std::to_string(data.size()) +
                       " data points lie in the domain, too few to determine the " + std::to_string(volume.control_vector_count()) +
                       " control vectors of degree " + std::to_string(volume.degree()) +
                       " (expected at least as many points as control vectors: use more points, a lower degree or fewer primary knots)");
  const Eigen::Index m = static_cast<Eigen::Index>(data.size());
  const Eigen::Index width = 3 + static_cast<Eigen::Index>(columns.size());
  Eigen::MatrixXd targets(m, width), prior(volume.control_vector_count(), width);
  for (Eigen::Index i = 0; i < m; ++i) {
    targets.row(i).head<3>() = data.points[static_cast<std::size_t>(i)].transpose();
    targets.row(i).tail(width - 3) = data.attributes.row(i);
  }
  Eigen::MatrixXd& control = volume.control_vectors();
  prior.leftCols<3>() = control.leftCols<3>();  // the identity geometry (blossom of x)
  for (std::size_t a = 0; a < columns.size(); ++a) {
    double sum = 0;
    for (Eigen::Index i = 0; i < m; ++i)
      if (c.inside[static_cast<std::size_t>(i)]) sum += data.attributes(i, static_cast<Eigen::Index>(a));
    if (options.prior_from_volume)
      prior.col(3 + static_cast<Eigen::Index>(a)) = control.col(columns[a]);
    else
      prior.col(3 + static_cast<Eigen::Index>(a)).setConstant(sum / static_cast<double>(fitted));
  }
  FittingSolverOptions solver;
  solver.regularisation = options.regularisation;
  solver.refinement_steps = options.refinement_steps;
  solver.direct_limit = options.direct_limit;
  solver.iterative_tolerance = options.iterative_tolerance;
  solver.inner_tolerance = options.inner_tolerance;
  FittingSolverReport report;
  Eigen::MatrixXd solution;
  if (options.fairing > 0 && volume.degree() >= 1 && width > 3) {
    // The geometry (the identity, in the space for every valid knot set) is fitted to the data
    // alone; the attributes to the data rows, then the fairing rows scaled so that the two terms
    // weigh `fairing` to 1 per row.
    solution.resize(prior.rows(), width);
    solution.leftCols<3>() = solve_fitting_least_squares(c.a, targets.leftCols<3>(), prior.leftCols<3>(), solver, &report);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> d = fairing_rows(volume);
    const double scale = std::sqrt(options.fairing * static_cast<double>(fitted) / static_cast<double>(std::max<Eigen::Index>(1, d.rows())));
    Eigen::SparseMatrix<double, Eigen::RowMajor> stacked(c.a.rows() + d.rows(), c.a.cols());
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(c.a.nonZeros() + d.nonZeros()));
    for (Eigen::Index r = 0; r < c.a.rows(); ++r)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(c.a, r); it; ++it) entries.emplace_back(r, it.col(), it.value());
    for (Eigen::Index r = 0; r < d.rows(); ++r)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(d, r); it; ++it)
        entries.emplace_back(c.a.rows() + r, it.col(), scale * it.value());
    stacked.setFromTriplets(entries.begin(), entries.end());
    Eigen::MatrixXd stacked_targets = Eigen::MatrixXd::Zero(stacked.rows(), width - 3);
    stacked_targets.topRows(m) = targets.rightCols(width - 3);
    // λ stays what it is for the data alone (a fraction of AᵀA's mean diagonal).
    FittingSolverOptions faired = solver;
    faired.regularisation *= c.a.squaredNorm() / std::max(stacked.squaredNorm(), 1e-300);
    FittingSolverReport attributes_report;
    solution.rightCols(width - 3) = solve_fitting_least_squares(stacked, stacked_targets, prior.rightCols(width - 3), faired, &attributes_report);
    report.normal_seconds += attributes_report.normal_seconds;
    report.factor_seconds += attributes_report.factor_seconds;
    report.solve_seconds += attributes_report.solve_seconds;
    report.iterations += attributes_report.iterations;
  } else {
    solution = solve_fitting_least_squares(c.a, targets, prior, solver, &report);
  }
  control.leftCols<3>() = solution.leftCols<3>();
  for (std::size_t a = 0; a < columns.size(); ++a) control.col(columns[a]) = solution.col(3 + static_cast<Eigen::Index>(a));
  if (phases) {
    phases->push_back({"normal equations", report.normal_seconds});
    phases->push_back({report.direct ? "factorisation" : "preconditioner", report.factor_seconds});
    phases->push_back({"solve", report.solve_seconds});
  }
  clock.restart();
  VolumeFitErrors errors = errors_at(c.a * control, data, c.inside, columns);
  errors.solver = {report.direct, report.refinement_steps, report.iterations};
  clock.done("errors");
  return errors;
}

VolumeFitErrors volume_fit_errors(const DmsSplineVolume& volume, const VolumeData& data) {
  validate_volume_data(data, "the data");
  std::vector<int> columns;
  for (const auto& name : data.attribute_names) columns.push_back(volume.attribute_column(name));
  const Collocation c = collocation(volume, data);
  return errors_at(c.a * volume.control_vectors(), data, c.inside, columns);
}

VolumeFit fit_volume_data(const VolumeData& data, const VolumeFitOptions& options, const std::function<void(const std::string&)>& progress) {
  const auto announce = [&](const std::string& phase) {
    if (progress) progress(phase);
  };
  if (options.degree < 1 || options.degree > kMaxKnotCloudDegree)
    throw InvalidInput("expected a degree in 1.." + std::to_string(kMaxKnotCloudDegree) + ", got " + std::to_string(options.degree), "degree");
  validate_volume_data(data, "the data");
  VolumeFitStatistics statistics;
  PhaseClock clock(statistics.phases);
  PointCloudDomainOptions domain_options = options.domain;
  if (domain_options.primary_knots == 0) {
    // About 1, 7.5, 24, 55 control vectors per vertex for degrees 1..4: this keeps them below
    // the number of points (0.08, 0.31, 0.6, 0.9 per point).
    const int n = options.degree;
    domain_options.primary_knots = std::max(4, static_cast<int>(data.size() / static_cast<std::size_t>(2 * (n + 2) * (n + 1))));
  }
  announce("domain");
  PointCloudDomain domain = point_cloud_domain(data.points, domain_options);
  clock.done("domain");
  KnotCloudOptions cloud_options;
  cloud_options.spread = options.spread;
  KnotClouds clouds = generate_knot_clouds(domain.mesh, options.degree, cloud_options);
  clock.done("knot clouds");
  statistics.data_points = data.size();
  statistics.delaunay_tetrahedra = domain.delaunay_tetrahedra;
  statistics.domain_tetrahedra = domain.mesh.tetrahedra.size();
  statistics.primary_knots = domain.mesh.points.size();
  statistics.knots = clouds.knots.size();
  for (VertexKind kind : domain.kinds) {
    statistics.corner_vertices += kind == VertexKind::Corner;
    statistics.curve_vertices += kind == VertexKind::Curve;
    statistics.general_vertices += kind == VertexKind::General;
  }
  DmsSplineVolume volume(std::move(domain.mesh), std::move(clouds), DmsControlSharing::Shared);
  statistics.control_points = static_cast<std::size_t>(volume.control_vector_count());
  announce("least squares");
  statistics.errors = fit_control_vectors(volume, data, options.fit, &statistics.phases);
  if (options.knots.enabled) {
    announce("knot optimisation");
    const auto start = std::chrono::steady_clock::now();
    KnotOptimisationOptions knots = options.knots;
    if (!(knots.threshold > 0) && options.refinement.error > 0) knots.threshold = options.refinement.error;
    statistics.knot_optimisation = optimise_knots(volume, statistics.errors, data, knots, options.fit);
    statistics.phases.push_back({"knot optimisation", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  }
  if (options.refinement.error > 0) {
    announce("adaptive refinement");
    const auto start = std::chrono::steady_clock::now();
    AdaptiveRefinementOptions refinement = options.refinement;
    refinement.spread = options.spread;
    statistics.refinement = refine_volume_fit(volume, statistics.errors, data, refinement, options.fit, [&](const RefinementRound& round) {
      announce("adaptive refinement: " + std::to_string(round.tetrahedra) + " tetrahedra");
    });
    statistics.phases.push_back({"adaptive refinement", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    statistics.domain_tetrahedra = volume.domain().tetrahedra.size();
    statistics.primary_knots = volume.domain().points.size();
    statistics.knots = volume.knots().knots.size();
    statistics.control_points = static_cast<std::size_t>(volume.control_vector_count());
  } else {
    RefinementRound unrefined;
    unrefined.tetrahedra = statistics.domain_tetrahedra;
    unrefined.control_points = statistics.control_points;
    unrefined.field_mean_square = mean_normalised_field_error(statistics.errors);
    statistics.refinement.rounds = {unrefined};
  }
  return {std::move(volume), std::move(statistics)};
}

}  // namespace volspline
