#include "volspline/pipeline/object_evaluation.h"

#include <algorithm>
#include <array>
#include <string>

#include "volspline/core/error.h"

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

}  // namespace

std::vector<double> evaluate_object_at(const ModelObject& object, const std::vector<double>& t, bool derivatives) {
  return visit_spline(object, "evaluation", "", [&](const auto& s) { return row_at(s, t, derivatives); });
}

std::vector<std::vector<double>> evaluate_object_on_grid(const ModelObject& object, const std::vector<int>& counts, bool derivatives) {
  return visit_spline(object, "evaluation", "", [&](const auto& s) { return grid_rows(s, counts, derivatives); });
}

}  // namespace volspline
