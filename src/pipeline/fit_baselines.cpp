#include "volspline/pipeline/fit_baselines.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include <Eigen/SparseCore>

#include "volspline/core/elapsed_time.h"
#include "volspline/core/error.h"
#include "volspline/mesh/point_cloud_domain.h"
#include "volspline/simplex/dms_spline_evaluator.h"
#include "../simplex/control_fit.h"

namespace volspline {
namespace {

struct DataBox {
  Eigen::Vector3d lo, hi;
};

DataBox data_box_of(const std::vector<Eigen::Vector3d>& points) {
  DataBox box{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
              Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (const auto& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

// Spans per direction: s_d = c · side_d (at least 1), with c chosen so that
// Π (s_d + degree) is the largest not above `coefficients`.
std::array<int, 3> spans_for(const Eigen::Vector3d& sides, int degree, std::size_t coefficients) {
  auto spans_at = [&](double c) {
    std::array<int, 3> s{};
    for (int d = 0; d < 3; ++d) s[static_cast<std::size_t>(d)] = std::max(1, static_cast<int>(std::floor(c * sides[d] / sides.maxCoeff())));
    return s;
  };
  auto count = [&](const std::array<int, 3>& s) {
    double n = 1;
    for (int v : s) n *= v + degree;
    return n;
  };
  double lo = 0, hi = 1;
  while (count(spans_at(hi)) <= static_cast<double>(coefficients) && hi < 1e6) hi *= 2;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (count(spans_at(mid)) <= static_cast<double>(coefficients) ? lo : hi) = mid;
  }
  return spans_at(lo);
}

// Index of the grid interval [axis[i], axis[i + 1]] holding t (clamped), and its local coordinate.
std::pair<std::size_t, double> interval_of(const std::vector<double>& axis, double t) {
  t = std::clamp(t, axis.front(), axis.back());
  const auto upper = std::upper_bound(axis.begin(), axis.end(), t);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (upper - axis.begin()) - 1));
  i = std::min(i, axis.size() - 2);
  return {i, (t - axis[i]) / (axis[i + 1] - axis[i])};
}

// Calls f(control point index, basis value) for the (p+1)^3 tensor-product basis functions that
// may be nonzero at x (inside the knot vectors' domains), first index fastest.
template <class F>
void for_each_tensor_basis(const std::array<KnotVector, 3>& knots, const Eigen::Vector3d& x, F&& f) {
  const int p = knots[0].degree();
  std::array<int, 3> span{};
  std::array<std::array<double, 6>, 3> basis{};  // degrees 1..5
  for (int d = 0; d < 3; ++d) {
    const KnotVector& k = knots[static_cast<std::size_t>(d)];
    span[static_cast<std::size_t>(d)] = k.find_span(x[d]);
    k.basis(span[static_cast<std::size_t>(d)], x[d], basis[static_cast<std::size_t>(d)].data());
  }
  const int nu = knots[0].num_basis(), nv = knots[1].num_basis();
  for (int k = 0; k <= p; ++k)
    for (int j = 0; j <= p; ++j)
      for (int i = 0; i <= p; ++i)
        f((span[0] - p + i) + nu * ((span[1] - p + j) + nv * (span[2] - p + k)),
          basis[0][static_cast<std::size_t>(i)] * basis[1][static_cast<std::size_t>(j)] * basis[2][static_cast<std::size_t>(k)]);
}

void add_errors(MethodError& e, double difference, double count_inverse) {
  e.data_mean_square += difference * difference * count_inverse;
  e.data_max_abs = std::max(e.data_max_abs, std::abs(difference));
}

void add_truth_errors(MethodError& e, double difference, double count_inverse) {
  e.truth_mean_square += difference * difference * count_inverse;
  e.truth_max_abs = std::max(e.truth_max_abs, std::abs(difference));
}

}  // namespace

Eigen::VectorXd TensorProductFit::operator()(const Eigen::Vector3d& x) const {
  const std::array<KnotVector, 3>& knots = volume.knot_vectors();
  Eigen::Vector3d t;
  for (int d = 0; d < 3; ++d)
    t[d] = std::clamp(x[d], knots[static_cast<std::size_t>(d)].domain_min(), knots[static_cast<std::size_t>(d)].domain_max());
  Eigen::VectorXd value = Eigen::VectorXd::Zero(coefficients.cols());
  for_each_tensor_basis(knots, t, [&](int index, double w) { value += w * coefficients.row(index).transpose(); });
  return value;
}

TensorProductFit fit_tensor_product_volume(const VolumeData& data, int degree, std::size_t coefficients) {
  validate_volume_data(data, "data");
  if (data.attribute_names.empty()) throw InvalidInput("the data has no attributes to fit", "data");
  if (degree < 1 || degree > 5) throw InvalidInput("expected a degree of 1 to 5, got " + std::to_string(degree), "degree");
  if (coefficients < 8) throw InvalidInput("expected at least 8 coefficients, got " + std::to_string(coefficients), "coefficients");
  const DataBox box = data_box_of(data.points);
  const Eigen::Vector3d sides = box.hi - box.lo;
  if (!(sides.minCoeff() > 0)) throw InvalidInput("the data's points lie in a plane or line: a tensor-product volume needs a box", "data");
  const std::array<int, 3> spans = spans_for(sides, degree, coefficients);
  std::array<KnotVector, 3> knots{KnotVector::uniform_clamped(degree, spans[0], box.lo.x(), box.hi.x()),
                                  KnotVector::uniform_clamped(degree, spans[1], box.lo.y(), box.hi.y()),
                                  KnotVector::uniform_clamped(degree, spans[2], box.lo.z(), box.hi.z())};
  // The identity map: control points at the Greville abscissae (linear precision).
  std::array<std::vector<double>, 3> greville{knots[0].greville_abscissae(), knots[1].greville_abscissae(), knots[2].greville_abscissae()};
  std::vector<double> points;
  for (double z : greville[2])
    for (double y : greville[1])
      for (double x : greville[0]) points.insert(points.end(), {x, y, z});
  TensorProductFit fit{BSplineVolume(knots, 3, std::move(points)), data.attribute_names, {}};
  const auto counts = fit.volume.num_control_points();
  const Eigen::Index unknowns = static_cast<Eigen::Index>(counts[0]) * counts[1] * counts[2];
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(data.size() * static_cast<std::size_t>((degree + 1) * (degree + 1) * (degree + 1)));
  for (std::size_t s = 0; s < data.size(); ++s)
    for_each_tensor_basis(knots, data.points[s], [&](int index, double w) { entries.emplace_back(static_cast<int>(s), index, w); });
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(data.size()), unknowns);
  a.setFromTriplets(entries.begin(), entries.end());
  // The simplex fit's solver and regularisation (simplex/control_fit.h), so the comparison
  // differs in the spline space only.
  ControlFitOptions options;
  options.refinement_steps = 3;
  options.direct_limit = 8000;
  fit.coefficients = solve_control_columns(a, data.attributes, Eigen::MatrixXd::Zero(unknowns, data.attributes.cols()), options);
  return fit;
}

Eigen::VectorXd RegularGridData::trilinear(const Eigen::Vector3d& x) const {
  const auto [i, s] = interval_of(axes[0], x.x());
  const auto [j, t] = interval_of(axes[1], x.y());
  const auto [k, u] = interval_of(axes[2], x.z());
  const std::size_t nx = axes[0].size(), ny = axes[1].size();
  Eigen::VectorXd value = Eigen::VectorXd::Zero(values.cols());
  for (int c = 0; c < 8; ++c) {
    const std::size_t di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double w = (di ? s : 1 - s) * (dj ? t : 1 - t) * (dk ? u : 1 - u);
    value += w * values.row(static_cast<Eigen::Index>((i + di) + nx * ((j + dj) + ny * (k + dk)))).transpose();
  }
  return value;
}

Eigen::VectorXd RegularGridData::nearest(const Eigen::Vector3d& x) const {
  std::array<std::size_t, 3> node{};
  for (int d = 0; d < 3; ++d) {
    const auto [i, f] = interval_of(axes[static_cast<std::size_t>(d)], x[d]);
    node[static_cast<std::size_t>(d)] = f > 0.5 ? i + 1 : i;
  }
  return values.row(static_cast<Eigen::Index>(node[0] + axes[0].size() * (node[1] + axes[1].size() * node[2]))).transpose();
}

std::optional<RegularGridData> regular_grid_of(const VolumeData& data) {
  std::optional<CompleteGrid> complete = complete_grid_of(data.points);
  if (!complete) return std::nullopt;
  RegularGridData grid;
  grid.axes = std::move(complete->axes);
  grid.attribute_names = data.attribute_names;
  grid.values.resize(static_cast<Eigen::Index>(data.size()), data.attributes.cols());
  for (std::size_t s = 0; s < data.size(); ++s)
    grid.values.row(static_cast<Eigen::Index>(complete->node[s])) = data.attributes.row(static_cast<Eigen::Index>(s));
  return grid;
}

std::vector<MethodError> compare_volume_fits(const VolumeData& data, const DmsSplineVolume& volume, const FitComparisonOptions& options) {
  validate_volume_data(data, "data");
  const std::size_t attributes = data.attribute_names.size();
  std::vector<int> columns;
  for (const auto& name : data.attribute_names) columns.push_back(volume.attribute_column(name));
  using FitMethod = std::function<Eigen::VectorXd(const Eigen::Vector3d&)>;
  struct FitCandidate {
    std::string name;
    std::size_t coefficients;
    double seconds;
    FitMethod evaluate;
  };
  std::vector<FitCandidate> candidates;
  DmsSplineEvaluator evaluator(volume);
  // The simplex spline at a point; NaN outside its domain (such points are not compared).
  candidates.push_back({"dms simplex spline", static_cast<std::size_t>(volume.control_vector_count()), 0, [&](const Eigen::Vector3d& x) {
                          const DmsSplinePoint p = evaluator.evaluate(x);
                          Eigen::VectorXd out(static_cast<Eigen::Index>(attributes));
                          for (std::size_t a = 0; a < attributes; ++a)
                            out[static_cast<Eigen::Index>(a)] =
                                p.inside ? p.value[columns[a]] : std::numeric_limits<double>::quiet_NaN();
                          return out;
                        }});
  const auto start = std::chrono::steady_clock::now();
  const int degree = options.tensor_product_degree > 0 ? options.tensor_product_degree : std::max(1, volume.degree());
  auto tensor = std::make_shared<TensorProductFit>(
      fit_tensor_product_volume(data, degree, static_cast<std::size_t>(std::max(8, volume.control_vector_count()))));
  candidates.push_back({"tensor-product least squares (degree " + std::to_string(degree) + ")", tensor->coefficient_count(),
                        seconds_since(start), [tensor](const Eigen::Vector3d& x) { return (*tensor)(x); }});
  if (auto grid = regular_grid_of(data)) {
    auto shared = std::make_shared<RegularGridData>(std::move(*grid));
    candidates.push_back({"trilinear interpolation", data.size(), 0, [shared](const Eigen::Vector3d& x) { return shared->trilinear(x); }});
    candidates.push_back({"nearest node", data.size(), 0, [shared](const Eigen::Vector3d& x) { return shared->nearest(x); }});
  }
  // The points against the truth: random, inside the simplex spline's domain, so every method
  // is measured on the same set.
  const DataBox box = data_box_of(data.points);
  std::vector<Eigen::Vector3d> truth_points;
  if (options.truth) {
    std::mt19937_64 random(20261202);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::size_t tries = 0; truth_points.size() < options.truth_points && tries < 20 * options.truth_points; ++tries) {
      // Drawn one by one (argument order is unspecified; this is g++'s), so that every compiler
      // samples the same points.
      const double rz = unit(random), ry = unit(random), rx = unit(random);
      const Eigen::Vector3d x = box.lo + (box.hi - box.lo).cwiseProduct(Eigen::Vector3d(rx, ry, rz));
      if (evaluator.evaluate(x).inside) truth_points.push_back(x);
    }
  }
  std::vector<double> low(attributes, std::numeric_limits<double>::infinity()), high(attributes, -std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < data.size(); ++s)
    for (std::size_t a = 0; a < attributes; ++a) {
      low[a] = std::min(low[a], data.attributes(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(a)));
      high[a] = std::max(high[a], data.attributes(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(a)));
    }
  std::vector<Eigen::VectorXd> truth(truth_points.size());
  for (std::size_t i = 0; i < truth_points.size(); ++i) truth[i] = options.truth(truth_points[i]);
  // Every method is measured at the same data points: those in the simplex spline's domain (a
  // point it does not fit is left out for all, not only for it).
  std::vector<char> in_domain(data.size());
  std::size_t compared = 0;
  for (std::size_t s = 0; s < data.size(); ++s) compared += (in_domain[s] = evaluator.evaluate(data.points[s]).inside ? 1 : 0);
  std::vector<MethodError> out;
  for (const FitCandidate& candidate : candidates) {
    std::vector<MethodError> errors(attributes);
    for (std::size_t a = 0; a < attributes; ++a) errors[a] = {candidate.name, data.attribute_names[a], candidate.coefficients};
    std::vector<Eigen::VectorXd> values(data.size());
    for (std::size_t s = 0; s < data.size(); ++s)
      if (in_domain[s]) values[s] = candidate.evaluate(data.points[s]);
    for (std::size_t s = 0; s < data.size(); ++s) {
      if (!in_domain[s]) continue;
      for (std::size_t a = 0; a < attributes; ++a)
        add_errors(errors[a], values[s][static_cast<Eigen::Index>(a)] - data.attributes(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(a)),
                   1.0 / static_cast<double>(compared));
    }
    for (std::size_t i = 0; i < truth_points.size(); ++i) {
      const Eigen::VectorXd v = candidate.evaluate(truth_points[i]);
      for (std::size_t a = 0; a < attributes; ++a)
        add_truth_errors(errors[a], v[static_cast<Eigen::Index>(a)] - truth[i][static_cast<Eigen::Index>(a)],
                         1.0 / static_cast<double>(truth_points.size()));
    }
    for (std::size_t a = 0; a < attributes; ++a) {
      MethodError& e = errors[a];
      const double range = high[a] > low[a] ? high[a] - low[a] : 1.0;
      if (truth_points.empty()) e.truth_mean_square = e.truth_max_abs = std::numeric_limits<double>::quiet_NaN();
      e.normalised_data_mean_square = e.data_mean_square / (range * range);
      e.normalised_data_max_abs = e.data_max_abs / range;
      e.normalised_truth_mean_square = e.truth_mean_square / (range * range);
      e.normalised_truth_max_abs = e.truth_max_abs / range;
      e.seconds = candidate.seconds;
      e.data_points = compared;
      out.push_back(e);
    }
  }
  return out;
}

}  // namespace volspline
