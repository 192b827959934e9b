#include "volspline/simplex/volume_fitting.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "volume_fitting_assembly.h"
#include "volume_fitting_solver.h"
#include "volspline/core/error.h"
#include "volspline/simplex/adaptive_refinement.h"
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
  const Eigen::MatrixXd solution = solve_fitting_least_squares(c.a, targets, prior, solver, &report);
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
