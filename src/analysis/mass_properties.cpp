// Mass properties by Gauss-Legendre quadrature of the Jacobian determinant over knot cells.
// Method and its guarantees: docs/mass-properties.md.
#include "volspline/analysis/mass_properties.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/core/error.h"
#include "volspline/spline/affine_map.h"

namespace volspline {

void gauss_legendre(int n, double* nodes, double* weights) {
  if (n < 1) throw InvalidInput("a Gauss-Legendre rule needs at least one point");
  // Newton's method on P_n from the Chebyshev-like first guess; the nodes are symmetric, so the
  // upper half is computed and mirrored (the middle node of an odd rule is exactly 0).
  // P_n(x) and P_n'(x) by the three-term recurrence.
  auto legendre = [n](double x) {
    double p0 = 1.0, p1 = x;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    return std::pair<double, double>{p1, n * (x * p1 - p0) / (x * x - 1.0)};
  };
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      const auto [p, derivative] = legendre(x);
      dp = derivative;
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-17) break;
    }
    dp = legendre(x).second;  // at the converged node, for the weight
    if (2 * i + 1 == n) x = 0.0;
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    nodes[n - 1 - i] = x;
    nodes[i] = -x;
    weights[n - 1 - i] = w;
    weights[i] = w;
  }
}

namespace {

// Integrated quantities relative to the reference point x0: |J|, x|J| (3), x x^T |J| (xx, xy,
// xz, yy, yz, zz), and J itself.
constexpr int kQ = 11;
using Quantities = std::array<double, kQ>;

struct Rule {
  std::vector<double> x, w;
};

struct Setup {
  Eigen::Vector3d x0;
  double length = 1.0;  // scale of |x - x0| over the solid
  std::array<int, 3> n_exact{}, n_high{};
  std::map<int, Rule> rules;
  bool rational = false;
  std::vector<std::optional<BSplineVolume>> cells;  // local spline of every knot cell
  std::vector<std::array<double, 6>> cell_boxes;     // lo0, hi0, lo1, hi1, lo2, hi2
};

struct GridResult {
  Quantities q{};
  bool sign_change = false;
  std::int64_t points = 0;
};

struct Region {
  int cell = 0;
  std::array<double, 3> lo{}, hi{};
  std::array<int, 3> depth{};
  Quantities value{};
  std::array<double, 3> direction_error{};
  double error = 0.0;
  bool final = true;
  bool folded = false;
  std::int64_t points = 0;
};

// The tensor Gauss rule with n[d] points in direction d over the box, evaluated on the knot
// cell's local spline by one sum-factorised grid evaluation with first derivatives.
GridResult integrate(const Setup& setup, const BSplineVolume& local, const std::array<double, 3>& lo,
                     const std::array<double, 3>& hi, const std::array<int, 3>& n) {
  std::array<std::vector<double>, 3> samples;
  std::array<std::vector<double>, 3> weights;
  for (std::size_t d = 0; d < 3; ++d) {
    const Rule& r = setup.rules.at(n[d]);
    const double mid = 0.5 * (lo[d] + hi[d]), half = 0.5 * (hi[d] - lo[d]);
    samples[d].resize(r.x.size());
    weights[d].resize(r.x.size());
    for (std::size_t i = 0; i < r.x.size(); ++i) {
      samples[d][i] = std::clamp(mid + half * r.x[i], lo[d], hi[d]);
      weights[d][i] = half * r.w[i];
    }
  }
  const std::size_t nx = samples[0].size(), ny = samples[1].size(), nz = samples[2].size();
  const std::size_t np = nx * ny * nz;
  thread_local std::vector<double> buffer;
  buffer.resize(4 * np * 3);
  local.evaluate_grid(samples, 1, buffer.data());
  const double* P = buffer.data();
  const double* Pu = P + np * 3;
  const double* Pv = P + 2 * np * 3;
  const double* Pw = P + 3 * np * 3;

  GridResult result;
  result.points = static_cast<std::int64_t>(np);
  double j_min = 0.0, j_max = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < nz; ++k) {
    Quantities plane{};
    for (std::size_t j = 0; j < ny; ++j) {
      Quantities row{};
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t pt = i + nx * (j + ny * k);
        const Eigen::Map<const Eigen::Vector3d> x(P + 3 * pt), xu(Pu + 3 * pt), xv(Pv + 3 * pt), xw(Pw + 3 * pt);
        const double J = jacobian_determinant(P + 3 * pt, static_cast<std::ptrdiff_t>(3 * np));
        j_min = std::min(j_min, J);
        j_max = std::max(j_max, J);
        scale = std::max(scale, xu.norm() * xv.norm() * xw.norm());
        const double a = std::abs(J) * weights[0][i];
        const Eigen::Vector3d r = x - setup.x0;
        row[0] += a;
        row[1] += a * r[0];
        row[2] += a * r[1];
        row[3] += a * r[2];
        row[4] += a * r[0] * r[0];
        row[5] += a * r[0] * r[1];
        row[6] += a * r[0] * r[2];
        row[7] += a * r[1] * r[1];
        row[8] += a * r[1] * r[2];
        row[9] += a * r[2] * r[2];
        row[10] += J * weights[0][i];
      }
      for (int c = 0; c < kQ; ++c) plane[static_cast<std::size_t>(c)] += row[static_cast<std::size_t>(c)] * weights[1][j];
    }
    for (int c = 0; c < kQ; ++c) result.q[static_cast<std::size_t>(c)] += plane[static_cast<std::size_t>(c)] * weights[2][k];
  }
  // A sign change counts when both signs exceed the rounding of J (relative to |p_u||p_v||p_w|,
  // which bounds |J| and its rounding error).
  const double threshold = 1e-12 * scale;
  result.sign_change = j_min < -threshold && j_max > threshold;
  return result;
}

// The size of a difference of quantities: volume, first moments / L, second moments / L^2.
double error_norm(const Setup& setup, const Quantities& a, const Quantities& b) {
  const double L = setup.length;
  double e = std::abs(a[0] - b[0]);
  for (int c = 1; c <= 3; ++c) e = std::max(e, std::abs(a[static_cast<std::size_t>(c)] - b[static_cast<std::size_t>(c)]) / L);
  for (int c = 4; c <= 9; ++c) e = std::max(e, std::abs(a[static_cast<std::size_t>(c)] - b[static_cast<std::size_t>(c)]) / (L * L));
  return e;
}

// Integrates one region: for a polynomial cell first with the exact rule, which is the answer if
// J keeps its sign; otherwise with the high and the low rule, whose difference is the error
// estimate of the low rule (conservative for the high rule's result, which is kept).
void evaluate(const Setup& setup, Region& region) {
  const BSplineVolume& local = *setup.cells[static_cast<std::size_t>(region.cell)];
  region.points = 0;
  if (!setup.rational) {
    const GridResult exact = integrate(setup, local, region.lo, region.hi, setup.n_exact);
    region.points += exact.points;
    if (!exact.sign_change) {
      region.value = exact.q;
      region.error = 0.0;
      region.direction_error = {};
      region.final = true;
      region.folded = false;
      return;
    }
    region.folded = true;
  }
  const GridResult high = integrate(setup, local, region.lo, region.hi, setup.n_high);
  region.points += high.points;
  region.folded = region.folded || high.sign_change;
  region.value = high.q;
  const GridResult low = integrate(setup, local, region.lo, region.hi, setup.n_exact);
  region.points += low.points;
  region.folded = region.folded || low.sign_change;
  region.error = error_norm(setup, high.q, low.q);
  region.final = region.error == 0.0;
}

// Before a region is split: the high rule with the low rule in one direction at a time; the
// differences from the high rule say which directions need halving.
void direction_errors(const Setup& setup, Region& region) {
  const BSplineVolume& local = *setup.cells[static_cast<std::size_t>(region.cell)];
  const GridResult high = integrate(setup, local, region.lo, region.hi, setup.n_high);
  region.points += high.points;
  for (std::size_t d = 0; d < 3; ++d) {
    auto n = setup.n_high;
    n[d] = setup.n_exact[d];
    const GridResult low = integrate(setup, local, region.lo, region.hi, n);
    region.points += low.points;
    region.direction_error[d] = error_norm(setup, high.q, low.q);
  }
}

template <class F>
void for_each_index(std::size_t n, bool parallel, F&& f) {
  if (!parallel || n < 2) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
  });
}

// Neumaier's compensated sum, so that many small cells add up without drift.
struct CompensatedSum {
  double sum = 0.0, compensation = 0.0;
  void add(double x) {
    const double t = sum + x;
    compensation += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  double value() const { return sum + compensation; }
};

std::int64_t rule_points(const std::array<int, 3>& n) {
  return static_cast<std::int64_t>(n[0]) * n[1] * n[2];
}

// The reference point x0 and length scale from a box around the solid (weight-0 control points
// are handled by bounding_box); moments are taken about x0 to avoid cancellation.
void set_reference(const BSplineVolume& volume, Setup& setup) {
  const auto [lo, hi] = bounding_box(volume, 0);
  setup.x0 = 0.5 * (lo + hi);
  setup.length = 0.5 * (hi - lo).norm();
  if (!(setup.length > 0.0) || !std::isfinite(setup.length)) setup.length = 1.0;
}

// The exact and the high Gauss-Legendre rule in each direction.
void add_rules(const BSplineVolume& volume, int extra_points, Setup& setup) {
  const auto degrees = volume.degrees();
  for (std::size_t d = 0; d < 3; ++d) {
    // x x^T |J| has degree 5p - 1 in this direction; n points integrate degree 2n - 1 exactly.
    const int p = degrees[d];
    setup.n_exact[d] = (5 * p + 1) / 2;
    setup.n_high[d] = setup.n_exact[d] + extra_points;
    for (int n : {setup.n_exact[d], setup.n_high[d]}) {
      if (setup.rules.count(n)) continue;
      Rule r;
      r.x.resize(static_cast<std::size_t>(n));
      r.w.resize(static_cast<std::size_t>(n));
      gauss_legendre(n, r.x.data(), r.w.data());
      setup.rules.emplace(n, std::move(r));
    }
  }
}

// Knot cells and their local splines: the (p+1)^3 control points of the cell with the 2p+2
// knots around its span in each direction; the local domain is exactly the cell.
void add_knot_cells(const BSplineVolume& volume, bool parallel, Setup& setup) {
  const auto degrees = volume.degrees();
  std::array<std::vector<double>, 3> breaks;
  std::array<std::vector<int>, 3> spans;
  for (std::size_t d = 0; d < 3; ++d) {
    const KnotVector& kv = volume.knot_vector(static_cast<int>(d));
    breaks[d] = kv.breakpoints();
    for (std::size_t i = 0; i + 1 < breaks[d].size(); ++i)
      spans[d].push_back(kv.find_span(0.5 * (breaks[d][i] + breaks[d][i + 1])));
  }
  const std::size_t n0 = spans[0].size(), n1 = spans[1].size(), n2 = spans[2].size();
  const std::size_t num_cells = n0 * n1 * n2;
  setup.cells.resize(num_cells);
  setup.cell_boxes.resize(num_cells);
  const int C = volume.coefficient_size();
  const auto counts = volume.num_control_points();
  for_each_index(num_cells, parallel, [&](std::size_t c) {
    const std::array<std::size_t, 3> idx{c % n0, (c / n0) % n1, c / (n0 * n1)};
    std::array<KnotVector, 3> knots{KnotVector::bezier(1), KnotVector::bezier(1), KnotVector::bezier(1)};
    std::array<int, 3> first{};
    for (std::size_t d = 0; d < 3; ++d) {
      const KnotVector& kv = volume.knot_vector(static_cast<int>(d));
      const int p = kv.degree(), s = spans[d][idx[d]];
      first[d] = s - p;
      knots[d] = KnotVector(p, std::vector<double>(kv.knots().begin() + (s - p), kv.knots().begin() + (s + p + 2)));
      setup.cell_boxes[c][2 * d] = breaks[d][idx[d]];
      setup.cell_boxes[c][2 * d + 1] = breaks[d][idx[d] + 1];
    }
    std::vector<double> coefficients;
    coefficients.reserve(static_cast<std::size_t>((degrees[0] + 1) * (degrees[1] + 1) * (degrees[2] + 1) * C));
    const auto& h = volume.homogeneous();
    for (int k = 0; k <= degrees[2]; ++k)
      for (int j = 0; j <= degrees[1]; ++j)
        for (int i = 0; i <= degrees[0]; ++i) {
          const std::size_t g = static_cast<std::size_t>((first[0] + i) + counts[0] * ((first[1] + j) + counts[1] * (first[2] + k)));
          coefficients.insert(coefficients.end(), h.begin() + static_cast<std::ptrdiff_t>(g * static_cast<std::size_t>(C)),
                              h.begin() + static_cast<std::ptrdiff_t>((g + 1) * static_cast<std::size_t>(C)));
        }
    setup.cells[c].emplace(BSplineVolume::from_homogeneous(std::move(knots), 3, setup.rational, std::move(coefficients)));
  });
}

// One region per knot cell, integrated.
std::vector<Region> initial_regions(const Setup& setup, bool parallel) {
  std::vector<Region> regions(setup.cells.size());
  for_each_index(regions.size(), parallel, [&](std::size_t c) {
    Region& r = regions[c];
    r.cell = static_cast<int>(c);
    for (std::size_t d = 0; d < 3; ++d) {
      r.lo[d] = setup.cell_boxes[c][2 * d];
      r.hi[d] = setup.cell_boxes[c][2 * d + 1];
    }
    evaluate(setup, r);
  });
  return regions;
}

constexpr int kMaxDepth = 52;  // halvings of a cell per direction: below that, rounding rules

// The children of a region split in the directions whose indicators are within a tenth of the
// largest (direction_errors must have run on it).
void split_region(const Region& r, std::vector<Region>& children) {
  std::array<bool, 3> split{};
  double top = 0.0;
  for (std::size_t d = 0; d < 3; ++d)
    if (r.depth[d] < kMaxDepth) top = std::max(top, r.direction_error[d]);
  for (std::size_t d = 0; d < 3; ++d) split[d] = r.depth[d] < kMaxDepth && r.direction_error[d] >= 0.1 * top;
  for (int mask = 0; mask < (1 << 3); ++mask) {
    bool valid = true;
    Region child;
    child.cell = r.cell;
    child.depth = r.depth;
    for (std::size_t d = 0; d < 3; ++d) {
      const bool upper = (mask >> d) & 1;
      if (!split[d]) {
        if (upper) valid = false;
        child.lo[d] = r.lo[d];
        child.hi[d] = r.hi[d];
        continue;
      }
      const double mid = 0.5 * (r.lo[d] + r.hi[d]);
      child.lo[d] = upper ? mid : r.lo[d];
      child.hi[d] = upper ? r.hi[d] : mid;
      ++child.depth[d];
    }
    if (valid) children.push_back(child);
  }
}

enum class Refinement { Converged, Stuck, Continue };

// One round of adaptive refinement: split the regions with the largest error estimates (in the
// directions whose indicators dominate) unless the summed estimate meets the tolerance already
// or the budget of quadrature points allows no split.
Refinement refine_once(const Setup& setup, const MassPropertiesOptions& options, std::vector<Region>& regions,
                       MassProperties& result) {
  const std::int64_t child_cost = (setup.rational ? 0 : rule_points(setup.n_exact)) + rule_points(setup.n_high) + rule_points(setup.n_exact);
  std::int64_t direction_cost = rule_points(setup.n_high);
  for (std::size_t d = 0; d < 3; ++d) {
    auto n = setup.n_high;
    n[d] = setup.n_exact[d];
    direction_cost += rule_points(n);
  }
  double volume_sum = 0.0, error_sum = 0.0;
  for (const Region& r : regions) volume_sum += r.value[0], error_sum += r.error;
  const double target = options.relative_tolerance * std::abs(volume_sum);
  if (error_sum <= target) return Refinement::Converged;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < regions.size(); ++i)
    if (!regions[i].final && regions[i].error > 0.0) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return regions[a].error > regions[b].error; });
  // Split the fewest regions whose errors make up the excess over half the target.
  const double excess = error_sum - 0.5 * target;
  double picked_error = 0.0;
  std::vector<std::size_t> parents;
  std::int64_t reserved = 0;  // upper bound of the points this round will take
  for (std::size_t i : order) {
    if (picked_error >= excess) break;
    const Region& r = regions[i];
    if (r.depth[0] >= kMaxDepth && r.depth[1] >= kMaxDepth && r.depth[2] >= kMaxDepth) continue;
    const std::int64_t cost = direction_cost + 8 * child_cost;
    if (result.quadrature_points + reserved + cost > options.max_quadrature_points) break;
    reserved += cost;
    picked_error += r.error;
    parents.push_back(i);
  }
  for_each_index(parents.size(), options.parallel, [&](std::size_t k) { direction_errors(setup, regions[parents[k]]); });
  std::vector<Region> children;
  for (std::size_t i : parents) {
    Region& r = regions[i];
    result.quadrature_points += r.points;  // the direction indicators
    r.points = 0;
    split_region(r, children);
  }
  if (parents.empty()) return Refinement::Stuck;
  for_each_index(children.size(), options.parallel, [&](std::size_t c) { evaluate(setup, children[c]); });
  for (const Region& c : children) result.quadrature_points += c.points;
  // Replace the parents (in place, keeping the order deterministic) and append the rest.
  std::vector<bool> is_parent(regions.size(), false);
  for (std::size_t i : parents) is_parent[i] = true;
  std::vector<Region> next;
  next.reserve(regions.size() + children.size());
  for (std::size_t i = 0; i < regions.size(); ++i)
    if (!is_parent[i]) next.push_back(regions[i]);
  for (Region& c : children) next.push_back(c);
  regions = std::move(next);
  return Refinement::Continue;
}

// Volume, centroid and inertia from the regions' integrals, summed without drift.
void add_totals(const Setup& setup, const std::vector<Region>& regions, const MassPropertiesOptions& options, MassProperties& result) {
  std::array<CompensatedSum, kQ> sums;
  CompensatedSum error_sum;
  for (const Region& r : regions) {
    for (std::size_t c = 0; c < static_cast<std::size_t>(kQ); ++c) sums[c].add(r.value[c]);
    error_sum.add(r.error);
  }
  Quantities q{};
  for (std::size_t c = 0; c < static_cast<std::size_t>(kQ); ++c) q[c] = sums[c].value();
  result.volume = q[0];
  result.signed_volume = q[10];
  if (result.volume > 0.0) {
    result.estimated_relative_error = error_sum.value() / result.volume;
    if (result.estimated_relative_error > options.relative_tolerance) result.converged = false;
    const Eigen::Vector3d m(q[1], q[2], q[3]);
    const Eigen::Vector3d c = m / result.volume;  // centroid relative to x0
    Eigen::Matrix3d S;                            // integral of x x^T |J| relative to x0
    S << q[4], q[5], q[6], q[5], q[7], q[8], q[6], q[8], q[9];
    const Eigen::Matrix3d central = S - result.volume * c * c.transpose();  // about the centroid
    result.centroid = setup.x0 + c;
    result.inertia = central.trace() * Eigen::Matrix3d::Identity() - central;
  } else {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    result.centroid.setConstant(nan);
    result.inertia.setConstant(nan);
    result.estimated_relative_error = error_sum.value() > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  }
}

}  // namespace

MassProperties mass_properties(const BSplineVolume& placed, const MassPropertiesOptions& options) {
  if (placed.dimension() != 3)
    throw InvalidInput("mass properties need a volume in R^3, got one in R^" + std::to_string(placed.dimension()));
  if (options.extra_points < 1) throw InvalidInput("mass properties: extra_points must be >= 1");
  // Volume and inertia are invariant under translation: integrate the solid moved to its local
  // origin, so that x − x0 and the Jacobian are rounded relative to its size, not to its
  // distance from 0; only the centroid is moved back.
  const BSplineVolume volume = placed.translated_to_local_origin();

  Setup setup;
  setup.rational = volume.is_rational();
  set_reference(volume, setup);
  add_rules(volume, options.extra_points, setup);
  add_knot_cells(volume, options.parallel, setup);
  std::vector<Region> regions = initial_regions(setup, options.parallel);

  MassProperties result;
  result.knot_cells = static_cast<int>(setup.cells.size());
  for (const Region& r : regions) {
    result.folded_cells += r.folded ? 1 : 0;
    result.quadrature_points += r.points;
  }
  for (int round = 0; round < 10000; ++round) {
    const Refinement step = refine_once(setup, options, regions, result);
    if (step == Refinement::Converged) break;
    if (step == Refinement::Stuck) {
      result.converged = false;
      break;
    }
  }
  add_totals(setup, regions, options, result);
  result.centroid += Eigen::Map<const Eigen::Vector3d>(placed.local_origin().data());
  return result;
}

}  // namespace volspline
