#include "volspline/analysis/jacobian_validity.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/core/resource_limits.h"

namespace volspline {

namespace {

struct WiderFirst {
  bool operator()(const JacobianCell& a, const JacobianCell& b) const { return a.width() < b.width(); }
};

// A corner of the domain where, along some direction, the first two control points coincide:
// with a clamped knot vector the derivative there is a multiple of their difference, exactly
// zero, so J = 0 exactly at that corner (the poles of a ball, the apex of a cone).
std::optional<std::array<double, 3>> collapsed_corner(const BSplineVolume& v) {
  const auto n = v.num_control_points();
  const int dim = v.dimension();
  for (int corner = 0; corner < 8; ++corner) {
    std::array<int, 3> idx{};
    for (int d = 0; d < 3; ++d) idx[static_cast<std::size_t>(d)] = (corner & (1 << d)) ? n[static_cast<std::size_t>(d)] - 1 : 0;
    for (int d = 0; d < 3; ++d) {
      if (!v.knot_vector(d).is_clamped()) continue;
      std::array<int, 3> next = idx;
      next[static_cast<std::size_t>(d)] += (corner & (1 << d)) ? -1 : 1;
      const std::size_t a = static_cast<std::size_t>(v.linear_index(idx) * dim), b = static_cast<std::size_t>(v.linear_index(next) * dim);
      bool same = true;
      for (int c = 0; c < dim; ++c) same = same && v.points()[a + static_cast<std::size_t>(c)] == v.points()[b + static_cast<std::size_t>(c)];
      if (v.is_rational()) {
        // A point at infinity has a direction, not a position: equal directions are no collapse.
        same = same && v.weights()[static_cast<std::size_t>(v.linear_index(idx))] > 0 &&
               v.weights()[static_cast<std::size_t>(v.linear_index(next))] > 0;
      }
      if (same) {
        std::array<double, 3> t{};
        for (int e = 0; e < 3; ++e) t[static_cast<std::size_t>(e)] = (corner & (1 << e)) ? v.domain_max(e) : v.domain_min(e);
        return t;
      }
    }
  }
  return std::nullopt;
}

std::array<double, 3> to_array(const Eigen::Vector3d& p) { return {p[0], p[1], p[2]}; }

// A certified point of one sign and its value of J.
using SignedPoint = std::optional<std::pair<Eigen::Vector3d, double>>;

// The verdict from what the subdivision found (docs/jacobian.md, "Validity").
void set_verdict(JacobianValidity& result, const SignedPoint& positive, const SignedPoint& negative,
                 const std::optional<std::array<double, 3>>& collapse, double signed_mass, bool unresolved) {
  if (positive && negative) {
    result.verdict = JacobianVerdict::Invalid;
    const bool positive_bulk = signed_mass >= 0;
    const auto& witness = positive_bulk ? *negative : *positive;
    const auto& reference = positive_bulk ? *positive : *negative;
    result.witness = to_array(witness.first);
    result.witness_value = witness.second;
    result.reference_point = to_array(reference.first);
  } else if (collapse) {
    result.verdict = JacobianVerdict::Invalid;
    result.witness = *collapse;
    result.witness_value = 0;
    if (positive) result.reference_point = to_array(positive->first);
    if (negative) result.reference_point = to_array(negative->first);
  } else if (!unresolved) {
    result.verdict = JacobianVerdict::Valid;
    result.orientation = result.lower > 0 ? 1 : -1;
  }
}

}  // namespace

const char* verdict_name(JacobianVerdict verdict) {
  switch (verdict) {
    case JacobianVerdict::Valid: return "valid";
    case JacobianVerdict::Invalid: return "invalid";
    case JacobianVerdict::Undecided: return "undecided";
  }
  return "undecided";
}

namespace {

// What a check costs, estimated from the degrees before it starts (docs/testing.md, "Hostile
// input: output files and limits"). A cell holds the Bernstein coefficients of J, of degree 3p - 1
// per direction (4p - 1 for w^4 J of a rational volume), or for the cone method the 3 coordinates
// of its (p + 1)^3 control points. Computing J on a Bézier cell multiplies tensors of about
// (p + 1)^3 coefficients pairwise: some 30 (p + 1)^6 multiply-adds (60 when rational); a split is
// one de Casteljau step over every coefficient along a direction.
struct JacobianCheckCost {
  std::uint64_t roots = 1, cell_bytes = 0, root_operations = 0, split_operations = 0;
};

JacobianCheckCost jacobian_check_cost(const BSplineVolume& volume, JacobianBoundMethod bounds) {
  JacobianCheckCost cost;
  const std::uint64_t factor = volume.is_rational() ? 4 : 3;
  std::uint64_t coefficients = 1, control = 1, longest = 1;
  for (int d = 0; d < 3; ++d) {
    const auto p = static_cast<std::uint64_t>(volume.knot_vector(d).degree());
    cost.roots = saturating_product({cost.roots, static_cast<std::uint64_t>(std::max(1, volume.knot_vector(d).num_spans()))});
    const std::uint64_t n = bounds == JacobianBoundMethod::Bezier ? factor * p + (p == 0 ? 1 : 0) : p + 1;
    coefficients = saturating_product({coefficients, n});
    control = saturating_product({control, p + 1});
    longest = std::max(longest, n);
  }
  cost.cell_bytes = saturating_product({bounds == JacobianBoundMethod::Bezier ? coefficients : 3 * coefficients, sizeof(double)});
  cost.root_operations = saturating_product({volume.is_rational() ? 60u : 30u, control, control});
  cost.split_operations = saturating_product({bounds == JacobianBoundMethod::Bezier ? coefficients : 3 * coefficients, longest});
  return cost;
}

}  // namespace

std::int64_t jacobian_cells_within_limits(const BSplineVolume& volume, JacobianBoundMethod bounds) {
  const JacobianCheckCost cost = jacobian_check_cost(volume, bounds);
  const std::uint64_t memory = memory_limit(), work = work_limit();
  const std::uint64_t root_bytes = saturating_product({cost.roots, cost.cell_bytes});
  const std::uint64_t root_work = saturating_product({cost.roots, cost.root_operations});
  if (root_bytes > memory || root_work > work) return 0;
  const std::uint64_t by_memory = (memory - root_bytes) / std::max<std::uint64_t>(cost.cell_bytes, 1);
  const std::uint64_t by_work = (work - root_work) / std::max<std::uint64_t>(cost.split_operations, 1);
  const std::uint64_t cells = std::min({by_memory, by_work, std::uint64_t{1} << 62});
  return static_cast<std::int64_t>(cells);
}

JacobianValidity check_jacobian(const BSplineVolume& volume, const JacobianValidityOptions& options) {
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance)) {
    throw InvalidInput("tolerance must be a finite number >= 0, got " + format_double(options.tolerance));
  }
  if (options.max_cells < 1) throw InvalidInput("the cell budget must be at least 1");
  // The budget shrinks to what the memory and work limits allow (the command line refuses an
  // explicit --max-cells above it); Bézier cells beyond the limits on their own are refused.
  std::int64_t max_cells = options.max_cells;
  if (volume.dimension() == 3) {
    const JacobianCheckCost cost = jacobian_check_cost(volume, options.bounds);
    const std::string request = "checking the Jacobian of a degree (" + std::to_string(volume.knot_vector(0).degree()) + ", " +
                                std::to_string(volume.knot_vector(1).degree()) + ", " + std::to_string(volume.knot_vector(2).degree()) +
                                ") volume of " + std::to_string(cost.roots) + " Bezier cell(s)";
    require_memory(saturating_product({cost.roots, cost.cell_bytes}), request);
    require_work(saturating_product({cost.roots, cost.root_operations}), request);
    max_cells = std::min(max_cells, std::max<std::int64_t>(1, jacobian_cells_within_limits(volume, options.bounds)));
  }
  const auto start = std::chrono::steady_clock::now();
  // The number of cells needed is not known beforehand: the phase counts them.
  const ProgressPhase phase(options.progress, "certification", 0, "cells");
  JacobianSubdivision subdivision(volume, options.bounds);
  JacobianValidity result;
  result.lower = std::numeric_limits<double>::infinity();
  result.upper = -result.lower;

  // Certified points of each sign, with their values.
  SignedPoint positive, negative;
  bool unresolved = false;
  double signed_mass = 0;  // sign of the bulk of J, for choosing which sign is the witness
  auto finish = [&](const JacobianCell& cell) {
    const auto [lo, hi] = subdivision.jacobian_bounds(cell);
    result.lower = std::min(result.lower, lo);
    result.upper = std::max(result.upper, hi);
  };
  auto record = [&](const JacobianCell& cell) {
    if (options.bounds == JacobianBoundMethod::Bezier) {
      for (int c = 0; c < 8 && !(positive && negative); ++c) {
        const int s = subdivision.corner_sign(cell, c);
        if (s > 0 && !positive) positive.emplace(subdivision.corner_parameter(cell, c), subdivision.corner_value(cell, c));
        if (s < 0 && !negative) negative.emplace(subdivision.corner_parameter(cell, c), subdivision.corner_value(cell, c));
      }
    } else if (cell.excludes_zero()) {
      // Cone bounds give no point values; a cell of one certified sign supplies its centre.
      const Eigen::Vector3d centre = 0.5 * (subdivision.corner_parameter(cell, 0) + subdivision.corner_parameter(cell, 7));
      if (cell.lower > 0 && !positive) positive.emplace(centre, cell.lower);
      if (cell.upper < 0 && !negative) negative.emplace(centre, cell.upper);
    }
  };

  std::priority_queue<JacobianCell, std::vector<JacobianCell>, WiderFirst> queue;
  const auto collapse = collapsed_corner(volume);
  for (auto& cell : subdivision.roots()) {
    ++result.cells;
    phase.advance();
    record(cell);
    double size = 1;
    const Eigen::Vector3d a = subdivision.corner_parameter(cell, 0), b = subdivision.corner_parameter(cell, 7);
    for (int d = 0; d < 3; ++d) size *= b[d] - a[d];
    signed_mass += 0.5 * (cell.lower + cell.upper) * size;
    if (cell.excludes_zero() || collapse) {
      finish(cell);
    } else {
      queue.push(std::move(cell));
    }
  }
  const double stop_width = options.tolerance * subdivision.scale();
  while (!queue.empty() && !(positive && negative) && result.cells < max_cells) {
    JacobianCell cell = queue.top();
    queue.pop();
    const int direction = subdivision.split_direction(cell, true);
    if (cell.width() <= stop_width || direction < 0) {
      unresolved = true;
      finish(cell);
      continue;
    }
    auto [a, b] = subdivision.split(cell, direction);
    phase.advance(2);
    for (JacobianCell* child : {&a, &b}) {
      ++result.cells;
      record(*child);
      if (child->excludes_zero()) {
        finish(*child);
      } else {
        queue.push(std::move(*child));
      }
    }
  }
  while (!queue.empty()) {
    unresolved = true;
    finish(queue.top());
    queue.pop();
  }

  set_verdict(result, positive, negative, collapse, signed_mass, unresolved);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace volspline
