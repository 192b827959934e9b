#include "volspline/pipeline/object_evaluation.h"

#include <algorithm>
#include <array>
#include <string>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

template <int D>
std::vector<double> row_at(const TensorSpline<D>& s, const std::vector<double>& t, bool derivatives) {
  if (t.size() != static_cast<std::size_t>(D))
    throw InvalidInput("expected " + std::to_string(D) + " parameter value(s), got " + std::to_string(t.size()));
  std::array<double, D> parameter{};
  std::copy(t.begin(), t.end(), parameter.begin());
  std::vector<double> row(static_cast<std::size_t>(s.dimension() * (derivatives ? D + 1 : 1)));
  s.evaluate_derivatives(parameter, derivatives ? 1 : 0, row.data());
  return row;
}

template <int D>
std::vector<std::vector<double>> grid_rows(const TensorSpline<D>& s, const std::vector<int>& counts, bool derivatives) {
  if (counts.size() != static_cast<std::size_t>(D))
    throw InvalidInput("expected " + std::to_string(D) + " sample count(s), got " + std::to_string(counts.size()));
  std::array<std::vector<double>, D> samples;
  std::size_t total = 1;
  for (int d = 0; d < D; ++d) {
    const auto dd = static_cast<std::size_t>(d);
    const int n = counts[dd];
    if (n < 2) throw InvalidInput("expected at least 2 samples per direction, got " + std::to_string(n));
    const double a = s.domain_min(d), b = s.domain_max(d);
    for (int i = 0; i < n; ++i) samples[dd].push_back(i == n - 1 ? b : a + (b - a) * i / (n - 1));
    total *= static_cast<std::size_t>(n);
  }
  const int order = derivatives ? 1 : 0;
  const auto k = static_cast<std::size_t>(s.dimension());
  const std::size_t blocks = derivatives ? D + 1 : 1;  // the point, then one block per first partial
  const auto values = s.evaluate_grid(samples, order);
  std::vector<std::vector<double>> rows;
  rows.reserve(total);
  for (std::size_t p = 0; p < total; ++p) {
    std::vector<double> row(blocks * k);
    for (std::size_t a = 0; a < blocks; ++a)
      for (std::size_t c = 0; c < k; ++c) row[a * k + c] = values[(a * total + p) * k + c];
    rows.push_back(std::move(row));
  }
  return rows;
}

Eigen::Vector3d simplex_point(const std::vector<double>& x) {
  if (x.size() != 3) throw InvalidInput("expected 3 coordinates x, y, z of a point of the domain, got " + std::to_string(x.size()) + " value(s)");
  return {x[0], x[1], x[2]};
}

std::vector<double> simplex_row(const DmsSplinePoint& p, bool derivatives) {
  const auto k = static_cast<std::size_t>(p.value.size());
  std::vector<double> row(k * (derivatives ? 4 : 1));
  for (std::size_t c = 0; c < k; ++c) row[c] = p.value[static_cast<Eigen::Index>(c)];
  if (derivatives)
    for (std::size_t d = 0; d < 3; ++d)
      for (std::size_t c = 0; c < k; ++c) row[(d + 1) * k + c] = p.gradient(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(d));
  return row;
}

}  // namespace

std::vector<double> evaluate_object_at(const ModelObject& object, const std::vector<double>& t, bool derivatives) {
  if (const auto* volume = std::get_if<DmsSplineVolume>(&object.spline)) {
    DmsSplineEvaluator evaluator(*volume);
    return simplex_row(evaluator.evaluate(simplex_point(t), derivatives ? 1 : 0), derivatives);
  }
  return visit_spline(object, "evaluation", "", [&](const auto& s) { return row_at(s, t, derivatives); });
}

std::vector<std::vector<double>> evaluate_object_at_each(const ModelObject& object, const std::vector<std::vector<double>>& points,
                                                         bool derivatives) {
  std::vector<std::vector<double>> rows;
  rows.reserve(points.size());
  if (const auto* volume = std::get_if<DmsSplineVolume>(&object.spline)) {
    // All points at once: the batch evaluation visits them in the order of the domain's cells.
    std::vector<Eigen::Vector3d> at(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      try {
        at[i] = simplex_point(points[i]);
      } catch (const InvalidInput& e) {
        throw e.located("points[" + std::to_string(i) + "]");
      }
    }
    DmsSplineEvaluator evaluator(*volume);
    std::vector<DmsSplinePoint> values;
    evaluator.evaluate(at, derivatives ? 1 : 0, values);
    for (const DmsSplinePoint& p : values) rows.push_back(simplex_row(p, derivatives));
    return rows;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    try {
      rows.push_back(evaluate_object_at(object, points[i], derivatives));
    } catch (const InvalidInput& e) {
      throw e.located("points[" + std::to_string(i) + "]");
    }
  }
  return rows;
}

std::vector<std::vector<double>> evaluate_object_on_grid(const ModelObject& object, const std::vector<int>& counts, bool derivatives) {
  if (const auto* volume = std::get_if<DmsSplineVolume>(&object.spline)) {
    if (counts.size() != 3) throw InvalidInput("expected 3 sample counts (x, y, z), got " + std::to_string(counts.size()));
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : volume->domain().points) box.extend(p);
    std::array<std::vector<double>, 3> samples;
    for (std::size_t d = 0; d < 3; ++d) {
      if (counts[d] < 2) throw InvalidInput("expected at least 2 samples per direction, got " + std::to_string(counts[d]));
      const double a = box.min()[static_cast<Eigen::Index>(d)], b = box.max()[static_cast<Eigen::Index>(d)];
      for (int i = 0; i < counts[d]; ++i) samples[d].push_back(i == counts[d] - 1 ? b : a + (b - a) * i / (counts[d] - 1));
    }
    std::vector<std::vector<double>> points;
    points.reserve(samples[0].size() * samples[1].size() * samples[2].size());
    for (double z : samples[2])
      for (double y : samples[1])
        for (double x : samples[0]) points.push_back({x, y, z});
    return evaluate_object_at_each(object, points, derivatives);
  }
  return visit_spline(object, "evaluation", "", [&](const auto& s) { return grid_rows(s, counts, derivatives); });
}

}  // namespace volspline
