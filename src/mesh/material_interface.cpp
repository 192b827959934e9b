#include "volspline/mesh/material_interface.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <Eigen/Geometry>

#include "volspline/core/error.h"

namespace volspline {
// Named, not anonymous: MaterialInterface::Samples holds a NearestPoints.
namespace material_interface_search {

using NeighbourKernel = CGAL::Simple_cartesian<double>;
using NeighbourPoint = NeighbourKernel::Point_3;

// Point i of a vector, for CGAL's k-d tree over indices.
class IndexedPointMap {
 public:
  using value_type = NeighbourPoint;
  using reference = const NeighbourPoint&;
  using key_type = std::size_t;
  using category = boost::lvalue_property_map_tag;
  explicit IndexedPointMap(const std::vector<NeighbourPoint>* points) : points_(points) {}
  reference operator[](key_type k) const { return (*points_)[k]; }
  friend reference get(const IndexedPointMap& map, key_type k) { return map[k]; }

 private:
  const std::vector<NeighbourPoint>* points_;
};

using NeighbourTraits = CGAL::Search_traits_adapter<std::size_t, IndexedPointMap, CGAL::Search_traits_3<NeighbourKernel>>;
using NeighbourSearch = CGAL::Orthogonal_k_neighbor_search<NeighbourTraits>;

// A k-d tree over points, answering the k nearest (indices).
class NearestPoints {
 public:
  explicit NearestPoints(std::span<const Eigen::Vector3d> points) {
    points_.reserve(points.size());
    for (const Eigen::Vector3d& p : points) points_.emplace_back(p.x(), p.y(), p.z());
    std::vector<std::size_t> indices(points_.size());
    std::iota(indices.begin(), indices.end(), std::size_t{0});
    tree_ = std::make_unique<NeighbourSearch::Tree>(indices.begin(), indices.end(), NeighbourSearch::Tree::Splitter(),
                                                    NeighbourTraits(IndexedPointMap(&points_)));
    tree_->build();
  }
  void nearest(const Eigen::Vector3d& x, int k, std::vector<std::size_t>& out) const {
    out.clear();
    const NeighbourSearch search(*tree_, NeighbourPoint(x.x(), x.y(), x.z()), static_cast<unsigned int>(k), 0, true,
                                 NeighbourSearch::Distance(IndexedPointMap(&points_)));
    for (const auto& hit : search) out.push_back(hit.first);
  }

 private:
  std::vector<NeighbourPoint> points_;
  std::unique_ptr<NeighbourSearch::Tree> tree_;
};

// Every point's kJumpNeighbours nearest others, as pairs (i, j), i < j, sorted, without repeats.
std::vector<std::pair<int, int>> neighbour_pairs(std::span<const Eigen::Vector3d> points) {
  const NearestPoints nearest(points);
  std::vector<std::pair<int, int>> pairs;
  std::vector<std::size_t> found;
  for (std::size_t i = 0; i < points.size(); ++i) {
    nearest.nearest(points[i], kJumpNeighbours + 1, found);
    for (std::size_t j : found)
      if (j != i) pairs.emplace_back(static_cast<int>(std::min(i, j)), static_cast<int>(std::max(i, j)));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace material_interface_search


JumpRegions jump_regions(std::span<const Eigen::Vector3d> points, const Eigen::MatrixXd& values, double jump) {
  if (!(jump > 0)) throw InvalidInput("expected a jump above 0, got " + std::to_string(jump), "jump");
  if (values.rows() != static_cast<Eigen::Index>(points.size()))
    throw InvalidInput("expected a row of values for each of the " + std::to_string(points.size()) + " points, got " +
                       std::to_string(values.rows()));
  if (points.size() < 2) throw InvalidInput("expected at least 2 points for the jump regions");
  std::vector<int> parent(points.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  JumpRegions regions;
  for (const auto& [i, j] : material_interface_search::neighbour_pairs(points)) {
    if ((values.row(i) - values.row(j)).cwiseAbs().maxCoeff() > jump) {
      ++regions.jump_edges;
      continue;
    }
    const int a = root(i), b = root(j);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  std::vector<int> region_of_root(points.size(), -1);
  regions.label.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    int& r = region_of_root[static_cast<std::size_t>(root(static_cast<int>(i)))];
    if (r < 0) {
      r = static_cast<int>(regions.sizes.size());
      regions.sizes.push_back(0);
    }
    regions.label[i] = r;
    ++regions.sizes[static_cast<std::size_t>(r)];
  }
  return regions;
}

struct MaterialInterface::Samples {
  std::vector<Eigen::Vector3d> midpoints, directions;  // direction: from the point of 0 to that of 1
  std::vector<Eigen::Vector3d> from, to;                // the pair's points of 0 and of 1
  std::unique_ptr<material_interface_search::NearestPoints> nearest;
  int local = 48;
};

MaterialInterface::MaterialInterface(std::span<const Eigen::Vector3d> points, std::span<const int> label, int local_samples)
    : samples_(std::make_unique<Samples>()) {
  if (label.size() != points.size())
    throw InvalidInput("expected a label for each of the " + std::to_string(points.size()) + " points, got " + std::to_string(label.size()));
  samples_->local = std::max(3, local_samples);
  for (const auto& [i, j] : material_interface_search::neighbour_pairs(points)) {
    const int a = label[static_cast<std::size_t>(i)], b = label[static_cast<std::size_t>(j)];
    if (!((a == 0 && b == 1) || (a == 1 && b == 0))) continue;
    const Eigen::Vector3d& from = points[static_cast<std::size_t>(a == 0 ? i : j)];
    const Eigen::Vector3d& to = points[static_cast<std::size_t>(a == 0 ? j : i)];
    samples_->midpoints.push_back((from + to) / 2);
    samples_->from.push_back(from);
    samples_->to.push_back(to);
    samples_->directions.push_back((to - from).normalized());
  }
  if (samples_->midpoints.empty()) throw InvalidInput("no neighbouring points of the two materials: no interface between them");
  samples_->nearest = std::make_unique<material_interface_search::NearestPoints>(samples_->midpoints);
}

MaterialInterface::~MaterialInterface() = default;
MaterialInterface::MaterialInterface(MaterialInterface&&) noexcept = default;
MaterialInterface& MaterialInterface::operator=(MaterialInterface&&) noexcept = default;

std::size_t MaterialInterface::sample_count() const { return samples_->midpoints.size(); }

double MaterialInterface::level(const Eigen::Vector3d& x, Eigen::Vector3d* normal_out) const {
  thread_local std::vector<std::size_t> found;
  // The plane that separates the pairs' points of 0 from those of 1 with the widest gap (a local
  // hard-margin classifier): the gap along a unit normal n is min n·(points of 1) − max n·(points
  // of 0). Search starts from the mean direction of the pairs — a pair crosses the interface with
  // a probability proportional to |n·d| (d its direction), so on a grid and for isotropic
  // scattered points the mean of d points along n, except where the data's boundary leaves out
  // some directions (0.2 radians off, measured) — and rotates it about two tangent axes in
  // halving steps while the gap widens. The midpoints' principal components are no better: they
  // form a staircase half a spacing high, which tilts them where it is short (0.3 radians).
  const auto gap = [&](const Eigen::Vector3d& n, double* middle) {
    double highest_0 = -std::numeric_limits<double>::infinity(), lowest_1 = std::numeric_limits<double>::infinity();
    for (std::size_t s : found) {
      highest_0 = std::max(highest_0, n.dot(samples_->from[s]));
      lowest_1 = std::min(lowest_1, n.dot(samples_->to[s]));
    }
    if (middle != nullptr) *middle = (highest_0 + lowest_1) / 2;
    return lowest_1 - highest_0;
  };
  const auto widest = [&](Eigen::Vector3d normal) {
    double best = gap(normal, nullptr);
    for (double step = 0.2; step > 1e-4; step /= 2) {
      for (int round = 0; round < 4; ++round) {
        const Eigen::Vector3d t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
        bool improved = false;
        for (const Eigen::Vector3d& move : {t1, Eigen::Vector3d(-t1), t2, Eigen::Vector3d(-t2)}) {
          const Eigen::Vector3d candidate = (normal + step * move).normalized();
          const double g = gap(candidate, nullptr);
          if (g > best) {
            best = g;
            normal = candidate;
            improved = true;
          }
        }
        if (!improved) break;
      }
    }
    return normal;
  };
  const auto mean_direction = [&] {
    Eigen::Vector3d direction = Eigen::Vector3d::Zero();
    for (std::size_t s : found) direction += samples_->directions[s];
    return direction.norm() > 0 ? Eigen::Vector3d(direction.normalized()) : Eigen::Vector3d::UnitX();
  };
  // The neighbourhood: local_samples pairs, doubled while the plane still separates them all (a
  // planar interface is found from as many pairs as it has, up to kMostPairs; a curved one from
  // as many as a plane separates).
  constexpr std::size_t kMostPairs = 1536;
  std::size_t count = static_cast<std::size_t>(samples_->local);
  samples_->nearest->nearest(x, static_cast<int>(count), found);
  Eigen::Vector3d normal = widest(mean_direction());
  double middle = 0;
  bool separated = gap(normal, &middle) > 0;
  while (separated && count < kMostPairs && count < samples_->midpoints.size()) {
    count *= 2;
    samples_->nearest->nearest(x, static_cast<int>(count), found);
    const Eigen::Vector3d wider = widest(normal);
    double wider_middle = 0;
    if (!(gap(wider, &wider_middle) > 0)) break;
    normal = wider;
    middle = wider_middle;
  }
  if (normal_out != nullptr) *normal_out = normal;
  if (separated) return normal.dot(x) - middle;
  // No plane separates even the nearest pairs (a sharply curved interface, labels mixed): the
  // plane through the centroid of their midpoints.
  samples_->nearest->nearest(x, samples_->local, found);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t s : found) centroid += samples_->midpoints[s] / static_cast<double>(found.size());
  return normal.dot(x - centroid);
}

}  // namespace volspline
