#include "volspline/mesh/point_cloud_domain.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <CGAL/convex_hull_3.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "exact_orientation.h"
#include "volspline/core/error.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"

namespace volspline {
namespace {

// A uniform grid of about one point per cell over the points' bounding box.
struct PointGrid {
  Eigen::Vector3d origin;
  double cell = 1;
  Eigen::Vector3i cells;
  std::vector<int> start, items;

  explicit PointGrid(std::span<const Eigen::Vector3d> points) {
    Eigen::Vector3d lo = points[0], hi = points[0];
    for (const auto& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Eigen::Vector3d extent = (hi - lo).cwiseMax(1e-300);
    const double largest = extent.maxCoeff();
    // Cells of side (volume / n)^(1/3), flat boxes counted by their largest side, at most 2^21
    // per axis product.
    const double volume = extent.cwiseMax(largest * 1e-3).prod();
    cell = std::max(std::cbrt(volume / static_cast<double>(points.size())), largest / 128.0);
    origin = lo;
    for (int a = 0; a < 3; ++a) cells[a] = std::max(1, static_cast<int>(std::floor(extent[a] / cell)) + 1);
    std::vector<int> count(static_cast<std::size_t>(cells.prod()) + 1, 0);
    for (const auto& p : points) ++count[static_cast<std::size_t>(index(of(p))) + 1];
    for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    start = count;
    items.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) items[static_cast<std::size_t>(count[static_cast<std::size_t>(index(of(points[i])))]++)] = static_cast<int>(i);
  }
  Eigen::Vector3i of(const Eigen::Vector3d& x) const {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) {
      const double t = std::floor((x[a] - origin[a]) / cell);
      c[a] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(cells[a] - 1)));
    }
    return c;
  }
  int index(const Eigen::Vector3i& c) const { return (c.z() * cells.y() + c.y()) * cells.x() + c.x(); }
};

}  // namespace

std::vector<int> convex_hull_vertices(std::span<const Eigen::Vector3d> points) {
  std::map<std::array<double, 3>, int> index;
  std::vector<exact::Kernel::Point_3> input;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (index.emplace(std::array<double, 3>{points[i].x(), points[i].y(), points[i].z()}, static_cast<int>(i)).second)
      input.emplace_back(points[i].x(), points[i].y(), points[i].z());
  if (input.size() < 4) return {};
  std::vector<exact::Kernel::Point_3> extreme;
  CGAL::extreme_points_3(input, std::back_inserter(extreme));
  std::vector<int> vertices;
  for (const auto& p : extreme) vertices.push_back(index.at({p.x(), p.y(), p.z()}));
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

std::vector<int> farthest_point_subsample(std::span<const Eigen::Vector3d> points, int count, std::span<const int> seeds,
                                          std::span<const double> spacing) {
  if (points.empty()) throw InvalidInput("no points to choose primary knots from");
  if (!spacing.empty() && spacing.size() != points.size())
    throw InvalidInput("expected one spacing per point (" + std::to_string(points.size()) + "), got " + std::to_string(spacing.size()), "spacing");
  for (std::size_t i = 0; i < spacing.size(); ++i)
    if (!(spacing[i] > 0 && std::isfinite(spacing[i])))
      throw InvalidInput("expected a positive finite spacing, got " + std::to_string(spacing[i]), "spacing[" + std::to_string(i) + "]");
  if (count < 1) throw InvalidInput("expected at least 1 primary knot, got " + std::to_string(count));
  for (int s : seeds)
    if (s < 0 || static_cast<std::size_t>(s) >= points.size())
      throw InvalidInput("seed " + std::to_string(s) + " is not one of the " + std::to_string(points.size()) + " points");
  std::size_t first = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (std::lexicographical_compare(points[i].data(), points[i].data() + 3, points[first].data(), points[first].data() + 3)) first = i;
  std::vector<double> distance(points.size(), std::numeric_limits<double>::infinity());
  std::vector<int> chosen;
  std::size_t next = first;
  std::size_t seed = 0;
  while (static_cast<int>(chosen.size()) < count) {
    if (seed < seeds.size()) {
      next = static_cast<std::size_t>(seeds[seed++]);
      if (distance[next] == 0) continue;
    }
    chosen.push_back(static_cast<int>(next));
    const Eigen::Vector3d c = points[next];
    double farthest = -1;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = (points[i] - c).squaredNorm();
      distance[i] = std::min(distance[i], spacing.empty() ? d : d / (spacing[i] * spacing[i]));
      if (distance[i] > farthest) farthest = distance[i], next = i;
    }
    if (farthest <= 0) break;  // every point coincides with a chosen one
  }
  return chosen;
}

OccupancyMap::OccupancyMap(std::span<const Eigen::Vector3d> points) : points_(points.begin(), points.end()) {
  if (points.empty()) throw InvalidInput("no points for the occupancy map");
  const PointGrid grid(points);
  radii_.assign(points.size(), 0);
  // The k nearest distinct neighbours: rings of cells around the point's cell until no closer
  // point can lie outside the rings searched.
  const int max_ring = grid.cells.maxCoeff();
  std::vector<double> nearest;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3i c = grid.of(points[i]);
    nearest.clear();
    for (int ring = 0; ring <= max_ring; ++ring) {
      for (int z = c.z() - ring; z <= c.z() + ring; ++z)
        for (int y = c.y() - ring; y <= c.y() + ring; ++y)
          for (int x = c.x() - ring; x <= c.x() + ring; ++x) {
            if (std::max({std::abs(x - c.x()), std::abs(y - c.y()), std::abs(z - c.z())}) != ring) continue;
            if (x < 0 || y < 0 || z < 0 || x >= grid.cells.x() || y >= grid.cells.y() || z >= grid.cells.z()) continue;
            const int cell = grid.index({x, y, z});
            for (int k = grid.start[static_cast<std::size_t>(cell)]; k < grid.start[static_cast<std::size_t>(cell) + 1]; ++k) {
              const double d = (points[static_cast<std::size_t>(grid.items[static_cast<std::size_t>(k)])] - points[i]).norm();
              if (d <= 0) continue;
              nearest.insert(std::upper_bound(nearest.begin(), nearest.end(), d), d);
              if (static_cast<int>(nearest.size()) > kOccupancyNeighbour) nearest.pop_back();
            }
          }
      if (static_cast<int>(nearest.size()) == kOccupancyNeighbour && nearest.back() <= ring * grid.cell) break;
    }
    radii_[i] = nearest.empty() ? 0 : nearest.back();
  }
  // Every ball is listed in each cell its bounding box meets, so contains() looks at one cell.
  origin_ = grid.origin;
  cell_ = grid.cell;
  cells_ = grid.cells;
  std::vector<int> count(static_cast<std::size_t>(cells_.prod()) + 1, 0);
  const auto for_each_cell = [&](std::size_t i, auto&& f) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(radii_[i]);
    const Eigen::Vector3i lo = cell_of(points_[i] - r), hi = cell_of(points_[i] + r);
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int x = lo.x(); x <= hi.x(); ++x) f((z * cells_.y() + y) * cells_.x() + x);
  };
  for (std::size_t i = 0; i < points_.size(); ++i) for_each_cell(i, [&](int cell) { ++count[static_cast<std::size_t>(cell) + 1]; });
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  cell_start_ = count;
  cell_points_.resize(static_cast<std::size_t>(count.back()));
  for (std::size_t i = 0; i < points_.size(); ++i)
    for_each_cell(i, [&](int cell) { cell_points_[static_cast<std::size_t>(count[static_cast<std::size_t>(cell)]++)] = static_cast<int>(i); });
  for (double r : radii_) largest_radius_ = std::max(largest_radius_, r);
}

Eigen::Vector3i OccupancyMap::cell_of(const Eigen::Vector3d& x) const {
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a) {
    const double t = std::floor((x[a] - origin_[a]) / cell_);
    c[a] = static_cast<int>(std::clamp(t, 0.0, static_cast<double>(cells_[a] - 1)));
  }
  return c;
}

bool OccupancyMap::contains(const Eigen::Vector3d& x) const {
  const Eigen::Vector3i c = cell_of(x);
  const std::size_t cell = static_cast<std::size_t>((c.z() * cells_.y() + c.y()) * cells_.x() + c.x());
  for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const auto i = static_cast<std::size_t>(cell_points_[static_cast<std::size_t>(k)]);
    if ((x - points_[i]).squaredNorm() <= radii_[i] * radii_[i]) return true;
  }
  return false;
}

std::vector<double> vertex_solid_angles(const TetrahedralMesh& mesh) {
  std::vector<double> angles(mesh.points.size(), 0);
  for (const auto& t : mesh.tetrahedra)
    for (int v = 0; v < 4; ++v) {
      const Eigen::Vector3d& o = mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>(v)])];
      const Eigen::Vector3d a = mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>((v + 1) % 4)])] - o;
      const Eigen::Vector3d b = mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>((v + 2) % 4)])] - o;
      const Eigen::Vector3d c = mesh.points[static_cast<std::size_t>(t[static_cast<std::size_t>((v + 3) % 4)])] - o;
      const double la = a.norm(), lb = b.norm(), lc = c.norm();
      // Van Oosterom and Strackee (1983): tan(Ω / 2) = |a·(b×c)| / (|a||b||c| + (a·b)|c| + (a·c)|b| + (b·c)|a|).
      const double numerator = std::abs(a.dot(b.cross(c)));
      const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
      angles[static_cast<std::size_t>(t[static_cast<std::size_t>(v)])] += 2 * std::atan2(numerator, denominator);
    }
  return angles;
}

std::vector<VertexKind> classify_vertices(const TetrahedralMesh& mesh) {
  const std::vector<double> angles = vertex_solid_angles(mesh);
  const std::vector<bool> boundary = boundary_vertices(mesh);
  constexpr double pi = std::numbers::pi;
  std::vector<VertexKind> kinds(mesh.points.size(), VertexKind::Interior);
  for (std::size_t v = 0; v < kinds.size(); ++v) {
    if (!boundary[v]) continue;
    const double deviation = std::abs(angles[v] - 2 * pi);
    kinds[v] = deviation <= pi / 2 + 1e-9 ? VertexKind::General : deviation <= 1.25 * pi + 1e-9 ? VertexKind::Curve : VertexKind::Corner;
  }
  return kinds;
}

namespace {

// Cells per axis of the body-centred cubic lattice of about `count` knots over a box of `size`:
// (m_x + 1)(m_y + 1)(m_z + 1) corners and m_x m_y m_z centres, cells of equal sides as near as
// the box allows: each m_a one less than the floor, the floor or the ceiling of size_a / cell,
// whichever combination comes nearest `count`, ties toward fewer (rounding each alone gave 91
// knots for 40 on a cube; the counts of cubic cells, (m + 1)^3 + m^3, are too far apart: 91,
// 189, 341, so sides from 2/3 to 3/2 of the ideal cell are allowed, and the plain rounding
// always, which a flat box needs).
Eigen::Vector3i lattice_cells(const Eigen::Vector3d& size, int count) {
  const double cell = std::cbrt(2 * size.prod() / std::max(count, 2));
  Eigen::Vector3i best = Eigen::Vector3i::Ones();
  long long best_gap = -1, best_knots = 0;
  for (int c = 0; c < 27; ++c) {
    Eigen::Vector3i m;
    for (int a = 0, code = c; a < 3; ++a, code /= 3) {
      const double cells = size[a] / cell;
      m[a] = std::max(1, static_cast<int>(std::floor(cells)) + (code % 3 == 0 ? -1 : 0) + (code % 3 == 2 && cells > std::floor(cells) ? 1 : 0));
    }
    bool near_cubic = true;
    for (int a = 0; a < 3; ++a) {
      const double side = size[a] / m[a];
      const bool rounded = m[a] == std::max(1, static_cast<int>(std::lround(size[a] / cell)));
      near_cubic = near_cubic && (rounded || (side >= (2.0 / 3.0) * cell && side <= 1.5 * cell));
    }
    if (!near_cubic) continue;
    const long long knots = 1LL * (m.x() + 1) * (m.y() + 1) * (m.z() + 1) + 1LL * m.x() * m.y() * m.z();
    const long long gap = std::abs(knots - count);
    if (best_gap < 0 || gap < best_gap || (gap == best_gap && knots < best_knots)) {
      best = m;
      best_gap = gap;
      best_knots = knots;
    }
  }
  return best;
}

}  // namespace

std::size_t lattice_primary_knots(std::span<const Eigen::Vector3d> points, int primary_knots) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  const int wanted = primary_knots > 0 ? primary_knots : std::max(4, static_cast<int>(points.size() / 24));
  const Eigen::Vector3i m = lattice_cells(box.sizes(), std::min<int>(wanted, static_cast<int>(points.size())));
  return static_cast<std::size_t>((m.x() + 1) * (m.y() + 1) * (m.z() + 1) + m.x() * m.y() * m.z());
}

std::optional<CompleteGrid> complete_grid_of(const std::vector<Eigen::Vector3d>& points) {
  CompleteGrid grid;
  for (int d = 0; d < 3; ++d) {
    auto& axis = grid.axes[static_cast<std::size_t>(d)];
    axis.reserve(points.size());
    for (const Eigen::Vector3d& p : points) axis.push_back(p[d]);
    std::sort(axis.begin(), axis.end());
    axis.erase(std::unique(axis.begin(), axis.end()), axis.end());
    if (axis.size() < 2) return std::nullopt;
  }
  const std::size_t nx = grid.axes[0].size(), ny = grid.axes[1].size();
  if (nx * ny * grid.axes[2].size() != points.size()) return std::nullopt;
  std::vector<char> seen(points.size(), 0);
  grid.node.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    std::array<std::size_t, 3> node{};
    for (int d = 0; d < 3; ++d) {
      const auto& axis = grid.axes[static_cast<std::size_t>(d)];
      node[static_cast<std::size_t>(d)] = static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), p[d]) - axis.begin());
    }
    const std::size_t index = node[0] + nx * (node[1] + ny * node[2]);
    if (seen[index]) return std::nullopt;
    seen[index] = 1;
    grid.node.push_back(index);
  }
  return grid;
}

PointCloudDomain point_cloud_domain(std::span<const Eigen::Vector3d> points, const PointCloudDomainOptions& options) {
  if (points.size() < 4) throw InvalidInput("expected at least 4 points for a tetrahedral domain, got " + std::to_string(points.size()), "points");
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput("coordinates are not finite numbers", "points[" + std::to_string(i) + "]");
  // Points that span no volume: exactly coplanar ones fail in Delaunay, but points on a plane
  // up to rounding give a Delaunay of slivers whose knot clouds cannot be valid.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p / static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(spread[0] > 1e-14 * spread[2]))  // thinner than 1e-7 of the extent: rounding of a plane
    throw InvalidInput("the points are coplanar or collinear (within rounding: their thickness is " +
                           std::to_string(std::sqrt(std::max(spread[0], 0.0) / std::max(spread[2], 1e-300))) +
                           " of their extent); they span no volume to fit",
                       "points");
  const int wanted = options.primary_knots > 0 ? options.primary_knots : std::max(4, static_cast<int>(points.size() / 24));
  const int count = std::min<int>(wanted, static_cast<int>(points.size()));
  std::vector<int> chosen;
  std::vector<Eigen::Vector3d> knots;
  if (options.lattice) {
    // Body-centred cubic: (m_x + 1)(m_y + 1)(m_z + 1) corners and m_x m_y m_z centres, cells of
    // equal sides as near as the box allows, about `count` in all.
    Eigen::AlignedBox3d box;
    for (const auto& p : points) box.extend(p);
    const Eigen::Vector3d size = box.sizes();
    const Eigen::Vector3i m = lattice_cells(size, count);
    const Eigen::Vector3d step = size.cwiseQuotient(m.cast<double>());
    for (int k = 0; k <= m.z(); ++k)
      for (int j = 0; j <= m.y(); ++j)
        for (int i = 0; i <= m.x(); ++i) {
          knots.push_back(box.min() + Eigen::Vector3d(i, j, k).cwiseProduct(step));
          chosen.push_back(-1);
          if (i < m.x() && j < m.y() && k < m.z()) {
            knots.push_back(box.min() + (Eigen::Vector3d(i, j, k) + Eigen::Vector3d::Constant(0.5)).cwiseProduct(step));
            chosen.push_back(-1);
          }
        }
  } else {
    std::vector<int> seeds = convex_hull_vertices(points);
    if (static_cast<int>(seeds.size()) > count / 2) seeds.clear();
    chosen = farthest_point_subsample(points, count, seeds, options.spacing);
    for (int i : chosen) knots.push_back(points[static_cast<std::size_t>(i)]);
  }
  TetrahedralMesh delaunay;
  try {
    delaunay = delaunay_tetrahedralization(knots);
    if (options.jitter > 0) {
      // Grid data are cospherical and coplanar in exact arithmetic, but their coordinates
      // (like 0.95) are rounded, so Delaunay keeps tetrahedra that are flat up to rounding,
      // for which no knot clouds are valid. The knots inside the hull move by `jitter` of their
      // shortest edge in a direction fixed by their index (deterministic); hull vertices stay,
      // so that Ω still spans the data's hull.
      const std::vector<bool> boundary = boundary_vertices(delaunay);
      std::vector<double> shortest(knots.size(), INFINITY);
      for (const auto& t : delaunay.tetrahedra)
        for (int a = 0; a < 4; ++a)
          for (int b = a + 1; b < 4; ++b) {
            const auto u = static_cast<std::size_t>(t[static_cast<std::size_t>(a)]), w = static_cast<std::size_t>(t[static_cast<std::size_t>(b)]);
            const double e = (knots[u] - knots[w]).norm();
            shortest[u] = std::min(shortest[u], e);
            shortest[w] = std::min(shortest[w], e);
          }
      for (std::size_t v = 0; v < knots.size(); ++v) {
        if (boundary[v] || !std::isfinite(shortest[v])) continue;
        // Spherical Fibonacci direction of the index: well spread, no randomness.
        const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
        const double z = 1 - 2 * (static_cast<double>(v % 1024) + 0.5) / 1024;
        const double r = std::sqrt(1 - z * z), angle = golden * static_cast<double>(v);
        knots[v] += options.jitter * shortest[v] * Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), z);
      }
      delaunay = delaunay_tetrahedralization(knots);
    }
  } catch (const InvalidInput& e) {
    throw InvalidInput("the primary knots: " + e.message(), "points");
  }
  PointCloudDomain domain;
  domain.delaunay_tetrahedra = delaunay.tetrahedra.size();
  std::vector<std::array<int, 4>> kept;
  if (options.clip_to_occupancy) {
    const OccupancyMap occupancy(points);
    for (const auto& t : delaunay.tetrahedra) {
      bool inside = true;
      for (int a = 0; a < 4 && inside; ++a)
        for (int b = a + 1; b < 4 && inside; ++b)
          inside = occupancy.contains(0.5 * (delaunay.points[static_cast<std::size_t>(t[static_cast<std::size_t>(a)])] +
                                             delaunay.points[static_cast<std::size_t>(t[static_cast<std::size_t>(b)])]));
      if (inside) kept.push_back(t);
    }
  } else {
    kept = delaunay.tetrahedra;
  }
  if (kept.empty()) throw InvalidInput("no Delaunay tetrahedron of the primary knots lies in the occupancy map of the points", "points");
  // Only the points the kept tetrahedra use, in their old order.
  std::vector<int> renumber(delaunay.points.size(), -1);
  for (const auto& t : kept)
    for (int v : t) renumber[static_cast<std::size_t>(v)] = 0;
  for (std::size_t v = 0; v < renumber.size(); ++v)
    if (renumber[v] == 0) {
      renumber[v] = static_cast<int>(domain.mesh.points.size());
      domain.mesh.points.push_back(delaunay.points[v]);
      domain.data_index.push_back(chosen[v]);
    }
  for (auto t : kept) {
    for (int& v : t) v = renumber[static_cast<std::size_t>(v)];
    domain.mesh.tetrahedra.push_back(t);
  }
  domain.kinds = classify_vertices(domain.mesh);
  return domain;
}

}  // namespace volspline
