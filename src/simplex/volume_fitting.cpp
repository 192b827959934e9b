#include "volspline/simplex/volume_fitting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <Eigen/QR>

#include "volume_fitting_assembly.h"
#include "volume_fitting_solver.h"
#include "volspline/core/error.h"
#include "volspline/core/binomial.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/knot_placement.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "volspline/simplex/knot_clouds.h"
#include "volspline/simplex/knot_optimisation.h"
#include "volspline/mesh/interface_split.h"
#include "volspline/mesh/material_interface.h"
#include "volspline/mesh/tetrahedron_locator.h"

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

// The fairing rows (docs/fitting.md, "Fairing"): in every domain tetrahedron three forward
// differences of order n + 1 of the spline, Σ_k (−1)^(n+1−k) C(n+1, k) s(g + k h d), from the
// centroid g along each axis d (−d where +d leaves Ω), with n + 1 steps h spanning half the
// tetrahedron's shortest edge. A difference of order n + 1 is 0 for every polynomial of degree
// <= n, so the term never pulls away from such a polynomial; stencils that do not fit inside Ω
// either way are left out. Along all three axes (decision, 2026-12-07): one axis per tetrahedron
// (x, y, z in turn) left each piece free to swing along the other two, and placed layouts rang
// next to ∂Ω (Marschner-Lobb 41^3 placed: largest error 0.88 against the truth, 0.49 now).
Eigen::SparseMatrix<double, Eigen::RowMajor> fairing_rows(const DmsSplineVolume& volume) {
  const TetrahedralMesh& domain = volume.domain();
  const int order = volume.degree() + 1;
  const DmsSplineEvaluator locator(volume);
  // A stencil stays in its tetrahedron's part: across an interface (sharp features) the spline
  // jumps, and the difference would pull the two sides together.
  const std::vector<int> parts = tetrahedron_parts(domain);
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
    for (Eigen::Index axis = 0; axis < 3; ++axis)
      for (const double sign : {1.0, -1.0}) {
        const Eigen::Vector3d step = sign * h * Eigen::Vector3d::Unit(axis);
        bool fits = true;
        for (int k = 1; k <= order && fits; ++k) {
          const int holder = locator.locate(g + k * step);
          fits = holder >= 0 && parts[static_cast<std::size_t>(holder)] == parts[t];
        }
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

// The prior of the attribute columns (decision, docs/fitting.md "The least-squares fit"): per
// part of Ω (tetrahedron_parts; one part unless the domain is split at a jump), the blossom of
// the least-squares polynomial of degree n of the part's data (below), else of its linear
// function — its value at the control point of the identity geometry, which is the mean of the
// blossom arguments — or of their mean where the part has too few points for a plane. A
// coefficient that no data point sees keeps it, so a part's trend (and a constant on each side
// of a jump) continues where the data are thin.
Eigen::MatrixXd polynomial_prior(const DmsSplineVolume& volume, const Collocation& c, const VolumeData& data) {
  const std::vector<int> parts = tetrahedron_parts(volume.domain());
  const int part_count = parts.empty() ? 1 : *std::max_element(parts.begin(), parts.end()) + 1;
  std::vector<int> row_part(static_cast<std::size_t>(volume.control_vector_count()), 0);
  for (int r = 0; r < volume.control_vector_count(); ++r)
    row_part[static_cast<std::size_t>(r)] = parts[static_cast<std::size_t>(volume.control_row_uses()[static_cast<std::size_t>(r)].front()[0])];
  const Eigen::Index k = data.attributes.cols();
  // Normal equations of [1 x y z] per part, centred on the part's mean point for conditioning.
  std::vector<Eigen::Vector3d> centre(static_cast<std::size_t>(part_count), Eigen::Vector3d::Zero());
  std::vector<std::vector<Eigen::Index>> members(static_cast<std::size_t>(part_count));
  for (Eigen::Index i = 0; i < c.a.rows(); ++i) {
    if (!c.inside[static_cast<std::size_t>(i)]) continue;
    Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(c.a, i);
    if (!it) continue;
    const auto p = static_cast<std::size_t>(row_part[static_cast<std::size_t>(it.col())]);
    members[p].push_back(i);
    centre[p] += data.points[static_cast<std::size_t>(i)];
  }
  Eigen::RowVectorXd overall = Eigen::RowVectorXd::Zero(k);
  std::size_t inside = 0;
  for (const auto& list : members)
    for (Eigen::Index i : list) overall += data.attributes.row(i), ++inside;
  if (inside > 0) overall /= static_cast<double>(inside);
  std::vector<Eigen::MatrixXd> coefficients(static_cast<std::size_t>(part_count));  // 4 x k: value at centre, gradient
  for (std::size_t p = 0; p < members.size(); ++p) {
    Eigen::MatrixXd& f = coefficients[p];
    f = Eigen::MatrixXd::Zero(4, k);
    if (members[p].empty()) {
      f.row(0) = overall;
      continue;
    }
    centre[p] /= static_cast<double>(members[p].size());
    Eigen::MatrixXd design(static_cast<Eigen::Index>(members[p].size()), 4), targets(static_cast<Eigen::Index>(members[p].size()), k);
    for (std::size_t j = 0; j < members[p].size(); ++j) {
      const auto row = static_cast<Eigen::Index>(j);
      design(row, 0) = 1;
      design.block<1, 3>(row, 1) = (data.points[static_cast<std::size_t>(members[p][j])] - centre[p]).transpose();
      targets.row(row) = data.attributes.row(members[p][j]);
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
    if (qr.rank() == 4) {
      f = qr.solve(targets);
    } else {
      f.row(0) = targets.colwise().mean();
    }
  }
  Eigen::MatrixXd prior(volume.control_vector_count(), k);
  for (int r = 0; r < volume.control_vector_count(); ++r) {
    const auto p = static_cast<std::size_t>(row_part[static_cast<std::size_t>(r)]);
    const Eigen::Vector3d x = volume.control_vectors().row(r).head<3>().transpose() - centre[p];
    prior.row(r) = coefficients[p].row(0) + x.transpose() * coefficients[p].bottomRows<3>();
  }
  // Degree n >= 2: where a part has at least twice as many points as there are polynomials of
  // degree <= n and they determine one, the prior is the blossom of the part's least-squares
  // polynomial of degree n instead (decision, docs/fitting.md "Fairing"): a coefficient that the
  // data and the fairing barely see keeps its prior, so with a linear prior samples of a cubic
  // came back only to 8e-9 (one direction of singular value 1.7e-8 decided by it); with this
  // one every polynomial of degree <= n is reproduced whatever such directions there are.
  const int n = volume.degree();
  if (n >= 2) {
    // Monomials of degree <= n as lists of coordinate indices.
    std::vector<std::vector<int>> monomials;
    for (int a = 0; a <= n; ++a)
      for (int b = 0; a + b <= n; ++b)
        for (int d = 0; a + b + d <= n; ++d) {
          std::vector<int> m(static_cast<std::size_t>(a), 0);
          m.insert(m.end(), static_cast<std::size_t>(b), 1);
          m.insert(m.end(), static_cast<std::size_t>(d), 2);
          monomials.push_back(m);
        }
    const auto mcount = static_cast<Eigen::Index>(monomials.size());
    std::vector<Eigen::MatrixXd> poly(static_cast<std::size_t>(part_count));
    std::vector<double> scales(static_cast<std::size_t>(part_count), 1);
    std::vector<bool> ok(static_cast<std::size_t>(part_count), false);
    for (std::size_t p = 0; p < members.size(); ++p) {
      if (static_cast<Eigen::Index>(members[p].size()) < 2 * mcount) continue;
      double radius = 0;
      for (Eigen::Index i : members[p]) radius += (data.points[static_cast<std::size_t>(i)] - centre[p]).squaredNorm();
      scales[p] = std::sqrt(radius / static_cast<double>(members[p].size()));
      if (!(scales[p] > 0)) continue;
      Eigen::MatrixXd design(static_cast<Eigen::Index>(members[p].size()), mcount), targets(static_cast<Eigen::Index>(members[p].size()), k);
      for (std::size_t j = 0; j < members[p].size(); ++j) {
        const Eigen::Vector3d q = (data.points[static_cast<std::size_t>(members[p][j])] - centre[p]) / scales[p];
        for (Eigen::Index m = 0; m < mcount; ++m) {
          double v = 1;
          for (int coordinate : monomials[static_cast<std::size_t>(m)]) v *= q[coordinate];
          design(static_cast<Eigen::Index>(j), m) = v;
        }
        targets.row(static_cast<Eigen::Index>(j)) = data.attributes.row(members[p][j]);
      }
      // A part whose points barely determine the polynomial (a thin slab, a few layers) keeps the
      // linear prior: a badly conditioned fit would extrapolate to the knots few points see.
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
      qr.setThreshold(1e-8);
      if (qr.rank() < mcount) continue;
      poly[p] = qr.solve(targets);
      ok[p] = true;
    }
    std::vector<int> order(static_cast<std::size_t>(n));
    for (int r = 0; r < volume.control_vector_count(); ++r) {
      const auto p = static_cast<std::size_t>(row_part[static_cast<std::size_t>(r)]);
      if (!ok[p]) continue;
      const auto& use = volume.control_row_uses()[static_cast<std::size_t>(r)].front();
      std::vector<Eigen::Vector3d> arguments = dms_blossom_arguments(volume, use[0], use[1]);
      for (auto& a : arguments) a = (a - centre[p]) / scales[p];
      // The blossom of each monomial (times 1^(n-d)): the mean over orderings of the arguments of
      // the product of its coordinates taken at the first d of them.
      Eigen::RowVectorXd blossom = Eigen::RowVectorXd::Zero(mcount);
      for (int i = 0; i < n; ++i) order[static_cast<std::size_t>(i)] = i;
      int permutations = 0;
      do {
        ++permutations;
        for (Eigen::Index m = 0; m < mcount; ++m) {
          double v = 1;
          const auto& mono = monomials[static_cast<std::size_t>(m)];
          for (std::size_t t = 0; t < mono.size(); ++t) v *= arguments[static_cast<std::size_t>(order[t])][mono[t]];
          blossom[m] += v;
        }
      } while (std::next_permutation(order.begin(), order.end()));
      prior.row(r) = (blossom / permutations) * poly[p];
    }
  }
  return prior;
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


// Sharp features (§4.2): the regions of a jump in the data, the interface between them as a cut
// through the domain (points on it once per side), and the data points on their own side.
// Returns the data to fit: those not across the estimated interface from their region.
VolumeData split_domain_at_jump(PointCloudDomain& domain, const VolumeData& data, double jump, SharpFeatureReport& report) {
  Eigen::MatrixXd normalised = data.attributes;
  for (Eigen::Index c = 0; c < normalised.cols(); ++c) {
    const double lo = normalised.col(c).minCoeff(), range = normalised.col(c).maxCoeff() - lo;
    normalised.col(c) = (normalised.col(c).array() - lo) / (range > 0 ? range : 1.0);
  }
  const JumpRegions regions = jump_regions(data.points, normalised, jump);
  report.enabled = true;
  report.region_points = regions.sizes;
  report.jump_edges = regions.jump_edges;
  if (regions.sizes.size() != 2) {
    std::string sizes;
    for (std::size_t r = 0; r < regions.sizes.size() && r < 8; ++r) sizes += (r ? ", " : "") + std::to_string(regions.sizes[r]);
    throw InvalidInput("the jump " + std::to_string(jump) + " splits the data into " + std::to_string(regions.sizes.size()) +
                           " regions (points: " + sizes + (regions.sizes.size() > 8 ? ", ..." : "") +
                           "); sharp features are fitted between two regions", "jump");
  }
  const MaterialInterface interface(data.points, regions.label);
  report.interface_samples = interface.sample_count();
  std::vector<double> level(domain.mesh.points.size());
  std::vector<Eigen::Vector3d> normal(domain.mesh.points.size());
  for (std::size_t v = 0; v < level.size(); ++v) level[v] = interface.level(domain.mesh.points[v], &normal[v]);
  InterfaceSplit split = split_at_interface(domain.mesh, level, normal);
  report.cut_tetrahedra = split.cut_tetrahedra;
  report.snapped_points = split.snapped_points;
  report.interface_points = split.interface_points;
  // A data point is fitted by the side whose closed tetrahedra hold it.
  std::array<TetrahedralMesh, 2> sides;
  for (std::size_t t = 0; t < split.side.size(); ++t) sides[static_cast<std::size_t>(split.side[t])].tetrahedra.push_back(split.mesh.tetrahedra[t]);
  for (TetrahedralMesh& m : sides) m.points = split.mesh.points;
  const TetrahedronLocator locate_0(sides[0]), locate_1(sides[1]);
  std::vector<Eigen::Index> kept;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const bool own = (regions.label[i] == 0 ? locate_0 : locate_1).locate(data.points[i]) >= 0;
    const bool other = !own && (regions.label[i] == 0 ? locate_1 : locate_0).locate(data.points[i]) >= 0;
    if (other)
      ++report.points_across;
    else
      kept.push_back(static_cast<Eigen::Index>(i));
  }
  domain.mesh = std::move(split.mesh);
  domain.kinds = classify_vertices(domain.mesh);
  domain.data_index.assign(domain.mesh.points.size(), -1);  // interface points are no data points
  VolumeData fitted;
  fitted.attribute_names = data.attribute_names;
  fitted.attributes.resize(static_cast<Eigen::Index>(kept.size()), data.attributes.cols());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    fitted.points.push_back(data.points[static_cast<std::size_t>(kept[k])]);
    fitted.attributes.row(static_cast<Eigen::Index>(k)) = data.attributes.row(kept[k]);
  }
  return fitted;
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
  if (options.prior_from_volume) {
    for (std::size_t a = 0; a < columns.size(); ++a) prior.col(3 + static_cast<Eigen::Index>(a)) = control.col(columns[a]);
  } else {
    prior.rightCols(width - 3) = polynomial_prior(volume, c, data);
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

// The fairing weight (at least) of the fits that judge a placement.
constexpr double kPlacementFairing = 0.1;

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
  ControlVectorFitOptions fit_options = options.fit;
  if (domain_options.primary_knots == 0) {
    // About 1, 7.5, 24, 55 control vectors per vertex for degrees 1..4: this keeps them below
    // the number of points (0.08, 0.31, 0.6, 0.9 per point).
    const int n = options.degree;
    domain_options.primary_knots = std::max(4, static_cast<int>(data.size() / static_cast<std::size_t>(2 * (n + 2) * (n + 1))));
  }
  // Grid data: the farthest-point knots of a grid make an irregular Delaunay domain (edge
  // lengths varying by 2x, slivers by the hull) that approximates smooth data less well per
  // coefficient than the lattice's congruent tetrahedra, which need the fairing term to keep
  // the basis functions reaching outside the box from overshooting (docs/fitting.md, "Grid data").
  // Only where the lattice's whole cells come to at most a quarter more knots than asked (not on
  // small grids, where they would give many more control vectors than the fit was sized for).
  if (options.grid_layout && !domain_options.lattice && !(options.jump > 0) && !options.knots.enabled && is_complete_grid(data.points) &&
      4 * lattice_primary_knots(data.points, domain_options.primary_knots) <=
          5 * std::min(static_cast<std::size_t>(domain_options.primary_knots), data.size())) {
    domain_options.lattice = true;
  }
  if (fit_options.fairing == 0 && !(options.jump > 0)) fit_options.fairing = options.default_fairing;
  statistics.layout = domain_options.lattice ? "lattice" : "farthest";
  statistics.fairing = fit_options.fairing;
  // The domain, its split at a jump, the knot clouds and the least-squares fit (eq. 10) for a
  // choice of primary knots; the sharp-feature report and own-side data of the chosen one are kept.
  struct Built {
    PointCloudDomain domain;
    std::optional<VolumeData> own_side;  // the data fitted when the domain is split at a jump
    SharpFeatureReport sharp;
    std::optional<DmsSplineVolume> volume;
    VolumeFitErrors errors;
  };
  // `within`: the phase a build belongs to (knot placement's fits), shown before its own steps so
  // that progress says "placement 2: domain", not "domain" again (28 characters show).
  const auto build = [&](const PointCloudDomainOptions& domain_with, const VolumeData& to_fit, const ControlVectorFitOptions& fit_with,
                         std::vector<FitPhase>* phases, const std::string& within = "") {
    const auto step = [&](const std::string& phase) { announce(within.empty() ? phase : within + ": " + phase); };
    Built b;
    step("domain");
    const auto start = std::chrono::steady_clock::now();
    b.domain = point_cloud_domain(data.points, domain_with);
    if (phases) phases->push_back({"domain", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    if (options.jump > 0) {
      step("sharp features");
      const auto split_start = std::chrono::steady_clock::now();
      b.own_side = split_domain_at_jump(b.domain, to_fit, options.jump, b.sharp);
      if (phases) phases->push_back({"sharp features", std::chrono::duration<double>(std::chrono::steady_clock::now() - split_start).count()});
    }
    KnotCloudOptions cloud_options;
    cloud_options.spread = options.spread;
    // An interface meets ∂Ω in wedges as sharp as its angle with the boundary: sub-knots on the ray.
    if (b.own_side) cloud_options.lean = 0;
    const auto clouds_start = std::chrono::steady_clock::now();
    KnotClouds clouds = generate_knot_clouds(b.domain.mesh, options.degree, cloud_options);
    if (phases) phases->push_back({"knot clouds", std::chrono::duration<double>(std::chrono::steady_clock::now() - clouds_start).count()});
    b.volume.emplace(std::move(b.domain.mesh), std::move(clouds), DmsControlSharing::Shared);
    step("least squares");
    b.errors = fit_control_vectors(*b.volume, b.own_side ? *b.own_side : to_fit, fit_with, phases);
    return b;
  };
  Built built = build(domain_options, data, fit_options, &statistics.phases);
  clock.restart();
  if (options.knots.enabled && options.knots.placement_rounds > 0 && !(options.jump > 0) && !domain_options.lattice) {
    // Primary knots placed again where the error asks for them (knot_placement.h), as many as
    // before. Knots crowded where the data are hard can fit the data better and the field worse
    // (basis functions between the samples that no sample pins down), so a placement is judged
    // on data it was not fitted to: every 8th point is held out, the candidates are fitted to
    // the rest, and a round is kept only if the held-out error falls; the chosen domain is then
    // fitted to all the data. Each round sizes from the last one's fit (a fixed-point iteration
    // towards equidistribution); the best round by the held-out error is kept.
    announce("knot placement");
    const auto start = std::chrono::steady_clock::now();
    KnotPlacementReport& placement = statistics.knot_placement;
    placement.before = mean_normalised_field_error(built.errors);
    placement.after = placement.before;
    const VolumeData training = every_nth_point(data, kKnotHoldOut, kKnotHoldOut / 2, false);
    const VolumeData held_out = every_nth_point(data, kKnotHoldOut, kKnotHoldOut / 2, true);
    if (held_out.size() > 0 && training.size() > 0) {
      try {
        // The judging fits are faired (at least kPlacementFairing): without, basis functions next to
        // ∂Ω that few samples see ring between them, and that noise, not the layout, decides.
        // The kept layout's final fit is faired the same way.
        ControlVectorFitOptions judging = fit_options;
        judging.fairing = std::max(judging.fairing, kPlacementFairing);
        Built current = build(domain_options, training, judging, nullptr, "placement");
        placement.held_out_before = mean_normalised_field_error(volume_fit_errors(*current.volume, held_out));
        placement.held_out_after = placement.held_out_before;
        PointCloudDomainOptions best = domain_options;
        for (int round = 0; round < options.knots.placement_rounds; ++round) {
          ++placement.rounds;
          PointCloudDomainOptions placed = domain_options;
          placed.spacing = error_equidistributing_spacing(*current.volume, data, tetrahedron_fit_errors(*current.volume, data),
                                                          {options.knots.spacing_ratio});
          // No valid knot clouds for a domain (a sub-knot of a boundary point that stays inside
          // a clipped, locally concave Ω, say): the spacing is tempered (its square root, twice)
          // before the rounds give up and the best so far is kept.
          bool made = false;
          for (int temper = 0; temper < 3 && !made; ++temper) {
            try {
              current = build(placed, training, judging, nullptr, "placement " + std::to_string(round + 1));
              made = true;
            } catch (const InvalidInput&) {
              ++placement.failed;
              for (double& h : placed.spacing) h = std::sqrt(h);
            }
          }
          if (!made) break;
          const double error = mean_normalised_field_error(volume_fit_errors(*current.volume, held_out));
          if (error < placement.held_out_after) {
            placement.held_out_after = error;
            placement.kept = round + 1;
            best = std::move(placed);
          }
        }
        if (placement.kept > 0) {
          // Faired like the fits that chose it: the larger tetrahedra of a placed layout ring
          // without (measured: docs/fitting.md, "Knot placement").
          built = build(best, data, judging, nullptr, "placement, kept");
          placement.fairing = judging.fairing;
          domain_options = std::move(best);
          placement.after = mean_normalised_field_error(built.errors);
          // And so are the refits that follow (the local step, adaptive refinement): unfaired,
          // the local step's refit of a placed Marschner–Lobb 41³ layout rang to 0.56 normalised
          // mean square against the truth (largest error 72) for 2.1e-3 at the data.
          fit_options.fairing = placement.fairing;
          statistics.fairing = fit_options.fairing;
        }
      } catch (const InvalidInput&) {
        // Too few held-in points for the first domain's fit, or a kept layout that could not be
        // fitted to all the data: the first fit stays, and the report says so.
        placement.kept = 0;
        placement.fairing = 0;
        placement.after = placement.before;
      }
    }
    statistics.phases.push_back({"knot placement", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    clock.restart();
  }
  statistics.sharp_features = built.sharp;
  std::optional<VolumeData> own_side = std::move(built.own_side);
  const VolumeData& fitted = own_side ? *own_side : data;
  DmsSplineVolume volume = std::move(*built.volume);
  statistics.data_points = data.size();
  statistics.delaunay_tetrahedra = built.domain.delaunay_tetrahedra;
  statistics.domain_tetrahedra = volume.domain().tetrahedra.size();
  statistics.primary_knots = volume.domain().points.size();
  statistics.knots = volume.knots().knots.size();
  for (VertexKind kind : built.domain.kinds) {
    statistics.corner_vertices += kind == VertexKind::Corner;
    statistics.curve_vertices += kind == VertexKind::Curve;
    statistics.general_vertices += kind == VertexKind::General;
  }
  statistics.control_points = static_cast<std::size_t>(volume.control_vector_count());
  statistics.errors = std::move(built.errors);
  if (options.knots.enabled && options.knots.local) {
    announce("knot optimisation");
    const auto start = std::chrono::steady_clock::now();
    KnotOptimisationOptions knots = options.knots;
    if (!(knots.threshold > 0) && options.refinement.error > 0) knots.threshold = options.refinement.error;
    statistics.knot_optimisation = optimise_knots(volume, statistics.errors, fitted, knots, fit_options);
    statistics.phases.push_back({"knot optimisation", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  }
  if (options.refinement.error > 0) {
    announce("adaptive refinement");
    const auto start = std::chrono::steady_clock::now();
    AdaptiveRefinementOptions refinement = options.refinement;
    refinement.spread = options.spread;
    statistics.refinement = refine_volume_fit(volume, statistics.errors, fitted, refinement, fit_options, [&](const RefinementRound& round) {
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
  if (own_side) {
    // The errors at all the data, those across the interface included.
    const LeastSquaresSolve solver = statistics.errors.solver;
    statistics.errors = volume_fit_errors(volume, data);
    statistics.errors.solver = solver;
  }
  return {std::move(volume), std::move(statistics)};
}

}  // namespace volspline
