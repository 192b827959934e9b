#include "volspline/analysis/point_in_image.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <utility>

#include "newton_in_domain.h"
#include "unit_roundoff.h"
#include "volspline/core/error.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/degree_elevation.h"

namespace volspline {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A query tries Newton again in a cell once its box is this fraction of the box where the
// previous try in its line of ancestors started: a few tries per halving of the cells' size
// in each direction, so a start close enough for convergence is reached soon after the cells
// get small, and failing tries (x outside) cost little next to the splitting.
constexpr double kNewtonShrink = 0.25;
constexpr int kLeafCells = 4;
constexpr int kRememberedMinima = 8;

template <int D>
bool has_zero_weight(const TensorSpline<D>& s) {
  return std::any_of(s.weights().begin(), s.weights().end(), [](double w) { return w <= 0; });
}

// Euclidean control points (3 numbers each) of homogeneous Bernstein coefficients with 3
// (polynomial) or 4 (rational, weight last and positive) components.
template <int D>
void euclidean_points(const BernsteinTensor<D>& f, std::vector<double>& points) {
  const std::size_t n = f.count();
  points.resize(3 * n);
  const double* h = f.coefficients.data();
  if (f.components == 3) {
    std::copy(h, h + 3 * n, points.begin());
    return;
  }
  for (std::size_t i = 0; i < n; ++i, h += 4) {
    for (std::size_t k = 0; k < 3; ++k) points[3 * i + k] = h[k] / h[3];
  }
}

Eigen::AlignedBox3d box_of(const std::vector<double>& points) {
  if (points.empty()) return Eigen::AlignedBox3d();
  std::array<double, 3> low{points[0], points[1], points[2]}, high = low;
  for (std::size_t i = 3; i < points.size(); i += 3)
    for (std::size_t k = 0; k < 3; ++k) {
      low[k] = std::min(low[k], points[i + k]);
      high[k] = std::max(high[k], points[i + k]);
    }
  return Eigen::AlignedBox3d(Eigen::Vector3d(low[0], low[1], low[2]), Eigen::Vector3d(high[0], high[1], high[2]));
}

bool box_encloses(const Eigen::AlignedBox3d& box, double margin, const Eigen::Vector3d& x) {
  return (x.array() >= box.min().array() - margin).all() && (x.array() <= box.max().array() + margin).all();
}

// True unless every control point lies strictly below the plane through x with unit normal n
// (then so does the cell's image, a convex combination of them, and x is not in it).
bool below_plane_excludes(const std::vector<double>& points, double margin, const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
  for (std::size_t i = 0; i < points.size(); i += 3) {
    const double height = n.x() * (points[i] - x.x()) + n.y() * (points[i + 1] - x.y()) + n.z() * (points[i + 2] - x.z());
    if (height >= -margin) return false;
  }
  return true;
}

// The direction whose control polygon legs are longest (max-norm, in space): halving it shrinks
// the cell's box the most. Directions of degree 0 are constant and never chosen unless all are.
template <int D>
int longest_direction(const BernsteinTensor<D>& f, const std::vector<double>& points) {
  int best = 0;
  double longest = -1;
  const std::size_t n = f.count();
  for (int d = 0; d < D; ++d) {
    if (f.degrees[static_cast<std::size_t>(d)] == 0) continue;
    const std::size_t step = f.stride(d), size = static_cast<std::size_t>(f.size(d));
    double leg = 0;
    // Every point but the last of its line along d, block by block (no division per point: this
    // runs at each split of every membership query).
    for (std::size_t block = 0; block < n; block += step * size) {
      const double* a = points.data() + 3 * block;
      const double* b = a + 3 * step;
      for (std::size_t j = 0; j < 3 * step * (size - 1); ++j) leg = std::max(leg, std::abs(b[j] - a[j]));
    }
    if (leg > longest) {
      longest = leg;
      best = d;
    }
  }
  return best;
}

// With a plane through x that should separate x from the cell (normal n, from Newton's closest
// point), the cell survives the plane test while some control point is above it. For the
// polynomial g = sum w_a (n . (P_a - x)) B_a (the height times the denominator: its sign is that
// of n . (s - x)) the largest coefficient exceeds the largest value by at most
// sum_d floor(n_d / 2) ceil(n_d / 2) / (2 n_d) max |second difference along d| (the control
// polygon's distance from the curve, one direction at a time). When that bound says the cell is
// in fact below the plane, the direction with the largest such term is split: splitting a
// direction in which g is linear (a sweep's t, a ball's radius) never lowers the largest
// coefficient. Otherwise -1: the cell crosses the plane and must shrink (longest_direction).
template <int D>
int curved_direction(const BernsteinTensor<D>& f, const std::vector<double>& points, const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                     std::vector<double>& heights) {
  const std::size_t count = f.count();
  heights.resize(count);
  double highest = -kInfinity;
  for (std::size_t i = 0; i < count; ++i) {
    const double* p = points.data() + 3 * i;
    const double weight = f.components == 4 ? f.coefficients[4 * i + 3] : 1.0;
    heights[i] = weight * (n.x() * (p[0] - x.x()) + n.y() * (p[1] - x.y()) + n.z() * (p[2] - x.z()));
    highest = std::max(highest, heights[i]);
  }
  int best = -1;
  double largest = 0, overshoot = 0;
  for (int d = 0; d < D; ++d) {
    const int degree = f.degrees[static_cast<std::size_t>(d)];
    if (degree < 2) continue;
    const std::size_t step = f.stride(d), size = static_cast<std::size_t>(degree + 1);
    double second = 0;
    // Every point but the first and last of its line along d.
    for (std::size_t block = 0; block < count; block += step * size)
      for (std::size_t i = block + step; i < block + step * (size - 1); ++i)
        second = std::max(second, std::abs(heights[i - step] - 2 * heights[i] + heights[i + step]));
    const double term = (degree / 2) * ((degree + 1) / 2) / (2.0 * degree) * second;
    overshoot += term;
    if (term > largest) {
      largest = term;
      best = d;
    }
  }
  return highest - overshoot < 0 ? best : -1;
}

// The control point nearest x, and its Greville point in the cell's parameter box: where Newton
// starts (the control net approximates the map there to O(h^2)).
template <int D>
std::pair<std::array<double, D>, double> nearest_control_parameter(const BernsteinTensor<D>& f, const std::vector<double>& points,
                                                                   const std::array<double, D>& low,
                                                                   const std::array<double, D>& high, const Eigen::Vector3d& x) {
  std::size_t nearest = 0;
  double distance = kInfinity;
  for (std::size_t i = 0; i < f.count(); ++i) {
    const double d = (Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]) - x).squaredNorm();
    if (d < distance) {
      distance = d;
      nearest = i;
    }
  }
  const std::array<int, D> a = f.multi_index(nearest);
  std::array<double, D> p{};
  for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
    const double local = f.degrees[d] == 0 ? 0.5 : static_cast<double>(a[d]) / f.degrees[d];
    p[d] = low[d] + local * (high[d] - low[d]);
  }
  return {p, std::sqrt(distance)};
}

}  // namespace

// Per-thread scratch of a query: cells on the depth-first stack keep their storage between
// queries, so splitting allocates nothing once the stack has grown to the depth needed.
template <int D>
struct SplineImage<D>::Search {
  std::vector<Cell> stack;
  std::vector<double> newton_box;  // per stack slot: the box diagonal of the last Newton start above it
  Cell current;
  std::vector<double> points, heights;
  std::vector<std::pair<double, int>> candidates;
};

template <int D>
SplineImage<D>::SplineImage(std::vector<TensorSpline<D>> patches, PointInImageOptions options) : patches_(std::move(patches)) {
  static std::atomic<std::uint64_t> next_generation{1};
  generation_ = next_generation++;
  if (patches_.empty()) throw InvalidInput("the image of no map is empty; give at least one patch", "patches");
  if (options.max_depth < 0 || options.max_depth > 60 * D) {
    throw InvalidInput("max_depth must be in [0, " + std::to_string(60 * D) + "], got " + std::to_string(options.max_depth), "max_depth");
  }
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance)) {
    throw InvalidInput("tolerance must be positive and finite", "tolerance");
  }
  if (options.max_cells < 1) throw InvalidInput("max_cells must be at least 1, got " + std::to_string(options.max_cells), "max_cells");
  max_depth_ = options.max_depth == 0 ? 26 * D : options.max_depth;
  max_cells_ = options.max_cells;

  std::vector<Cell> roots;
  std::vector<double> points;
  for (std::size_t index = 0; index < patches_.size(); ++index) {
    const TensorSpline<D>& patch = patches_[index];
    const std::string where = "patches[" + std::to_string(index) + "]";
    if (patch.dimension() != 3) {
      throw InvalidInput("a map into R^3 is needed, got control points of dimension " + std::to_string(patch.dimension()), where);
    }
    // Knot insertions of the extraction: each forms convex combinations (a few roundings of
    // the largest coefficient, earlier errors not grown); midpoint splits add one rounding per
    // degree per level (bernstein_split).
    double roundings = 8;
    int largest_degree = 0;
    for (int d = 0; d < D; ++d) {
      const KnotVector& kv = patch.knot_vector(d);
      const double interior = static_cast<double>(kv.breakpoints().size()) - 2;
      roundings += 8.0 * (kv.degree() + 1) * (interior + (kv.is_clamped() ? 0 : 2));
      largest_degree = std::max(largest_degree, kv.degree());
    }
    roundings += static_cast<double>(max_depth_) * largest_degree;
    for (TensorSpline<D> piece : bezier_pieces(patch)) {
      // Lasser: "infinite control points can be eliminated by degree elevation"; each round
      // shortens every run of zero weights by one.
      for (int round = 0; round < 64 && has_zero_weight(piece); ++round) {
        for (int d = 0; d < D; ++d) piece = elevate_degree(piece, d, 1);
      }
      if (has_zero_weight(piece)) {
        throw InvalidInput("a Bézier piece keeps a weight-0 control point after degree elevation; its control points do not bound it",
                           where + ".weights");
      }
      Cell cell;
      cell.patch = index;
      for (int d = 0; d < D; ++d) {
        cell.low[static_cast<std::size_t>(d)] = piece.domain_min(d);
        cell.high[static_cast<std::size_t>(d)] = piece.domain_max(d);
      }
      cell.coefficients = BernsteinTensor<D>(piece.degrees(), piece.coefficient_size());
      cell.coefficients.coefficients = piece.homogeneous();
      euclidean_points(cell.coefficients, points);
      cell.box = box_of(points);
      double largest = 0;
      for (double c : points) largest = std::max(largest, std::abs(c));
      double weight_ratio = 1;
      if (piece.is_rational()) {
        const auto [lightest, heaviest] = std::minmax_element(piece.weights().begin(), piece.weights().end());
        weight_ratio = *heaviest / *lightest;
      }
      // The Euclidean point (w x) / w: both numerator and denominator carry the relative errors
      // above, which the division by the smallest weight scales by the weight ratio.
      cell.margin = 4 * kUnitRoundoff * roundings * largest * weight_ratio;
      bounds_.extend(cell.box);
      roots.push_back(std::move(cell));
    }
  }
  const double diagonal = bounds_.diagonal().norm();
  size_ = diagonal > 0 ? diagonal : 1.0;
  tolerance_ = options.tolerance * size_;
  precompute(std::move(roots), options.precomputed_bytes);
  cell_order_.resize(cells_.size());
  for (std::size_t i = 0; i < cells_.size(); ++i) cell_order_[i] = static_cast<int>(i);
  nodes_.reserve(2 * cells_.size() / kLeafCells + 2);
  build_hierarchy(0, static_cast<int>(cells_.size()));
}

template <int D>
void SplineImage<D>::precompute(std::vector<Cell> heap, std::size_t budget) {
  // Largest box first, so the cells kept are of about one size across the model.
  auto smaller = [](const Cell& a, const Cell& b) { return a.box.diagonal().squaredNorm() < b.box.diagonal().squaredNorm(); };
  std::make_heap(heap.begin(), heap.end(), smaller);
  std::size_t bytes = 0;
  for (const Cell& c : heap) bytes += c.coefficients.coefficients.size() * sizeof(double);
  std::vector<double> points;
  while (true) {
    const Cell& top = heap.front();
    const std::size_t cell_bytes = top.coefficients.coefficients.size() * sizeof(double);
    if (bytes + cell_bytes > budget || top.depth >= max_depth_ / 2 || top.box.diagonal().norm() <= size_ / 1024) break;
    std::pop_heap(heap.begin(), heap.end(), smaller);
    Cell parent = std::move(heap.back());
    heap.pop_back();
    euclidean_points(parent.coefficients, points);
    const int direction = longest_direction(parent.coefficients, points);
    Cell lower = parent, upper = parent;
    bernstein_split(parent.coefficients, direction, 0.5, lower.coefficients, upper.coefficients);
    const std::size_t d = static_cast<std::size_t>(direction);
    const double middle = 0.5 * (parent.low[d] + parent.high[d]);
    lower.high[d] = middle;
    upper.low[d] = middle;
    for (Cell* half : {&lower, &upper}) {
      half->depth = parent.depth + 1;
      euclidean_points(half->coefficients, points);
      half->box = box_of(points);
      heap.push_back(std::move(*half));
      std::push_heap(heap.begin(), heap.end(), smaller);
    }
    bytes += cell_bytes;
  }
  cells_ = std::move(heap);
}

template <int D>
int SplineImage<D>::build_hierarchy(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (int i = first; i < first + count; ++i) {
    const Cell& c = cells_[static_cast<std::size_t>(cell_order_[static_cast<std::size_t>(i)])];
    box.extend(Eigen::AlignedBox3d(c.box.min().array() - c.margin, c.box.max().array() + c.margin));
    centres.extend(c.box.center());
  }
  nodes_[static_cast<std::size_t>(index)].box = box;
  if (count <= kLeafCells) {
    nodes_[static_cast<std::size_t>(index)].left = first;
    nodes_[static_cast<std::size_t>(index)].count = count;
    return index;
  }
  // Median split of the centres along their widest axis.
  Eigen::Index axis = 0;
  centres.diagonal().maxCoeff(&axis);
  const auto begin = cell_order_.begin() + first;
  const auto middle = begin + count / 2;
  std::nth_element(begin, middle, begin + count, [&](int a, int b) {
    return cells_[static_cast<std::size_t>(a)].box.center()(axis) < cells_[static_cast<std::size_t>(b)].box.center()(axis);
  });
  const int left = build_hierarchy(first, count / 2);
  const int right = build_hierarchy(first + count / 2, count - count / 2);
  nodes_[static_cast<std::size_t>(index)].left = left;
  nodes_[static_cast<std::size_t>(index)].right = right;
  return index;
}

template <int D>
typename SplineImage<D>::Query SplineImage<D>::query(const Eigen::Vector3d& x) const {
  if (!x.allFinite()) throw InvalidInput("the point must be finite", "x");
  Query result;
  search(x, result);
  return result;
}

template <int D>
typename SplineImage<D>::Query SplineImage<D>::query(const Eigen::Vector3d& x, const Preimage& hint) const {
  if (!x.allFinite()) throw InvalidInput("the point must be finite", "x");
  Query result;
  if (hint.patch < patches_.size()) {
    const detail::DomainNewtonResult<D> newton = detail::newton_in_domain<D>(patches_[hint.patch], x, hint.parameter, tolerance_, 12);
    ++result.newton_runs;
    if (newton.converged) {
      result.membership = ImageMembership::Inside;
      result.preimage = Preimage{hint.patch, newton.parameter};
      result.residual = newton.residual;
      return result;
    }
  }
  search(x, result);
  return result;
}

template <int D>
std::optional<typename SplineImage<D>::Preimage> SplineImage<D>::preimage_near(const Eigen::Vector3d& x, const Preimage& start,
                                                                                double distance) const {
  if (!x.allFinite()) throw InvalidInput("the point must be finite", "x");
  if (start.patch >= patches_.size())
    throw InvalidInput("patch " + std::to_string(start.patch) + " does not exist (" + std::to_string(patches_.size()) + " patches)", "start");
  if (!(distance > 0)) throw InvalidInput("the distance must be positive", "distance");
  // Towards the closest point (a tight tolerance), accepted anywhere within `distance`.
  const detail::DomainNewtonResult<D> newton = detail::newton_in_domain<D>(patches_[start.patch], x, start.parameter, 1e-6 * distance);
  if (!(newton.residual <= distance)) return std::nullopt;
  return Preimage{start.patch, newton.parameter};
}

template <int D>
ImageMembership SplineImage<D>::classify(const Eigen::Vector3d& x) const {
  return query(x).membership;
}

template <int D>
std::optional<typename SplineImage<D>::Preimage> SplineImage<D>::preimage(const Eigen::Vector3d& x) const {
  return query(x).preimage;
}

template <int D>
void SplineImage<D>::search(const Eigen::Vector3d& x, Query& result) const {
  thread_local Search scratch;
  Search& s = scratch;

  // Precomputed cells whose (widened) box holds x, the one whose centre is nearest (relative to
  // its size) first.
  s.candidates.clear();
  // Depth-first over the hierarchy: at most its depth + 1 nodes wait, and median splits keep
  // the depth at log2(cells / kLeafCells) + 1 (about 20 for a million cells).
  std::array<int, 64> nodes{};
  int pending = 0;
  nodes[static_cast<std::size_t>(pending++)] = 0;
  while (pending > 0) {
    const Node& node = nodes_[static_cast<std::size_t>(nodes[static_cast<std::size_t>(--pending)])];
    if (!node.box.contains(x)) continue;
    if (node.right >= 0) {
      nodes[static_cast<std::size_t>(pending++)] = node.left;
      nodes[static_cast<std::size_t>(pending++)] = node.right;
      continue;
    }
    for (int i = node.left; i < node.left + node.count; ++i) {
      const int c = cell_order_[static_cast<std::size_t>(i)];
      const Cell& cell = cells_[static_cast<std::size_t>(c)];
      ++result.cells_tested;
      if (!box_encloses(cell.box, cell.margin, x)) continue;
      // Relative distance to the box centre: cheap, and the smallest boxes around x first.
      s.candidates.emplace_back((x - cell.box.center()).squaredNorm() / (cell.box.diagonal().squaredNorm() + 1e-300), c);
    }
  }
  if (s.candidates.empty()) {
    result.membership = ImageMembership::Outside;
    return;
  }
  // The stack is processed from its end: the nearest candidate goes last.
  std::sort(s.candidates.begin(), s.candidates.end(), std::greater<>());
  std::size_t top = 0;
  auto reserve = [&](std::size_t slots) {
    if (s.stack.size() < slots) {
      s.stack.resize(slots);
      s.newton_box.resize(slots);
    }
  };
  reserve(s.candidates.size());
  for (const auto& [distance, c] : s.candidates) {
    s.stack[top] = cells_[static_cast<std::size_t>(c)];
    s.newton_box[top] = kInfinity;
    ++top;
  }

  double best_residual = kInfinity, best_minimum = kInfinity;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool has_normal = false;
  double undecided = kInfinity;
  bool gave_up = false;
  // Where earlier Newton runs ended without converging (local minima of |s - x|): a start in a
  // cell holding one would most likely end there again.
  std::array<Preimage, kRememberedMinima> minima{};
  int minima_count = 0;
  while (top > 0) {
    --top;
    std::swap(s.current, s.stack[top]);
    double newton_box = s.newton_box[top];
    Cell& cell = s.current;
    if (result.cells_tested >= max_cells_) {
      gave_up = true;
      break;
    }
    ++result.cells_tested;
    euclidean_points(cell.coefficients, s.points);
    cell.box = box_of(s.points);
    if (!box_encloses(cell.box, cell.margin, x)) continue;
    if (has_normal && below_plane_excludes(s.points, cell.margin, x, normal)) continue;
    const double diagonal = cell.box.diagonal().norm() + 2 * cell.margin;
    const auto [start, nearest] = nearest_control_parameter<D>(cell.coefficients, s.points, cell.low, cell.high, x);
    auto holds_a_minimum = [&] {
      for (int m = 0; m < std::min(minima_count, kRememberedMinima); ++m) {
        const Preimage& p = minima[static_cast<std::size_t>(m)];
        if (p.patch != cell.patch) continue;
        bool inside = true;
        for (std::size_t d = 0; d < static_cast<std::size_t>(D); ++d) {
          const double extent = cell.high[d] - cell.low[d];
          inside = inside && p.parameter[d] >= cell.low[d] - extent && p.parameter[d] <= cell.high[d] + extent;
        }
        if (inside) return true;
      }
      return false;
    };
    // Newton again only from a control point nearer x than half the best minimum so far (for
    // x outside the image none comes nearer than the closest point Newton found already; a
    // stall at a kink does not count) and not within a cell's width of where an earlier run
    // ended.
    if (diagonal <= kNewtonShrink * newton_box && nearest < 0.5 * best_minimum && !holds_a_minimum()) {
      const detail::DomainNewtonResult<D> newton = detail::newton_in_domain<D>(patches_[cell.patch], x, start, tolerance_);
      ++result.newton_runs;
      newton_box = diagonal;
      if (newton.converged) {
        result.membership = ImageMembership::Inside;
        result.preimage = Preimage{cell.patch, newton.parameter};
        result.residual = newton.residual;
        return;
      }
      minima[static_cast<std::size_t>(minima_count++ % kRememberedMinima)] = Preimage{cell.patch, newton.parameter};
      if (newton.residual < best_residual) {
        // The residual of a local minimum of |s(p) - x| points from the image towards x: the
        // plane through x normal to it leaves the image's nearby part below.
        if (newton.stationary) best_minimum = newton.residual;
        best_residual = newton.residual;
        normal = (x - newton.value) / newton.residual;
        has_normal = true;
        if (below_plane_excludes(s.points, cell.margin, x, normal)) continue;
      }
    }
    if (cell.depth >= max_depth_) {
      undecided = std::min(undecided, diagonal);
      continue;
    }
    int direction = has_normal ? curved_direction(cell.coefficients, s.points, x, normal, s.heights) : -1;
    if (direction < 0) direction = longest_direction(cell.coefficients, s.points);
    reserve(top + 2);
    Cell& lower = s.stack[top];
    Cell& upper = s.stack[top + 1];
    bernstein_split(cell.coefficients, direction, 0.5, lower.coefficients, upper.coefficients);
    const std::size_t d = static_cast<std::size_t>(direction);
    const double middle = 0.5 * (cell.low[d] + cell.high[d]);
    for (Cell* half : {&lower, &upper}) {
      half->patch = cell.patch;
      half->low = cell.low;
      half->high = cell.high;
      half->depth = cell.depth + 1;
      half->margin = cell.margin;
    }
    lower.high[d] = middle;
    upper.low[d] = middle;
    // The half holding the nearest control point is searched first (it is on top).
    if (start[d] < middle) std::swap(lower, upper);
    s.newton_box[top] = s.newton_box[top + 1] = newton_box;
    top += 2;
  }
  if (undecided == kInfinity && !gave_up) {
    result.membership = ImageMembership::Outside;
    return;
  }
  result.membership = ImageMembership::Undecided;
  result.distance_bound = std::min(best_residual, undecided);
}

template class SplineImage<3>;
template class SplineImage<4>;

}  // namespace volspline
