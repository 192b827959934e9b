#include "volspline/extract/simplex_isosurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

// A lattice point (a_0, a_1, a_2, a_3)/k of a domain tetrahedron, named by its nonzero
// barycentric numerators and the global vertex indices they belong to (sorted), so that the same
// point reached from two tetrahedra gets the same name.
using LatticeKey = std::array<std::int64_t, 8>;

LatticeKey lattice_key(const std::array<int, 4>& sorted_vertices, const std::array<int, 4>& numerators) {
  LatticeKey key;
  key.fill(-1);
  int at = 0;
  for (int c = 0; c < 4; ++c)
    if (numerators[static_cast<std::size_t>(c)] > 0) {
      key[static_cast<std::size_t>(2 * at)] = sorted_vertices[static_cast<std::size_t>(c)];
      key[static_cast<std::size_t>(2 * at + 1)] = numerators[static_cast<std::size_t>(c)];
      ++at;
    }
  return key;
}

// The edgewise subdivision of the Kuhn simplex {k >= y1 >= y2 >= y3 >= 0}: the Freudenthal
// simplices of the unit cubes of [0, k]^3 that lie in it (k^3 of them), as lattice points y.
std::vector<std::array<Eigen::Vector3i, 4>> edgewise_subdivision(int k) {
  std::vector<std::array<Eigen::Vector3i, 4>> simplices;
  std::array<int, 3> order{0, 1, 2};
  auto in_simplex = [k](const Eigen::Vector3i& y) { return k >= y[0] && y[0] >= y[1] && y[1] >= y[2] && y[2] >= 0; };
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c) {
        order = {0, 1, 2};
        do {
          std::array<Eigen::Vector3i, 4> s;
          s[0] = Eigen::Vector3i(a, b, c);
          for (int m = 0; m < 3; ++m) s[static_cast<std::size_t>(m + 1)] = s[static_cast<std::size_t>(m)] + Eigen::Vector3i::Unit(order[static_cast<std::size_t>(m)]);
          if (std::all_of(s.begin(), s.end(), in_simplex)) simplices.push_back(s);
        } while (std::next_permutation(order.begin(), order.end()));
      }
  return simplices;
}

}  // namespace

SimplexIsosurface simplex_isosurface(const DmsSplineVolume& volume, const SimplexIsosurfaceOptions& options) {
  if (volume.attribute_names().empty()) throw InvalidInput("the volume has no attributes to take an isosurface of");
  const int column = options.attribute.empty() ? 3 : volume.attribute_column(options.attribute);
  const TetrahedralMesh& domain = volume.domain();
  int k = options.subdivisions;
  if (k == 0) {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : domain.points) box.extend(p);
    const double target = options.target_edge > 0 ? options.target_edge : box.diagonal().norm() / 40.0;
    double longest = 0;
    for (const auto& t : domain.tetrahedra)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          longest = std::max(longest, (domain.points[static_cast<std::size_t>(t[static_cast<std::size_t>(a)])] -
                                       domain.points[static_cast<std::size_t>(t[static_cast<std::size_t>(b)])]).norm());
    k = std::clamp(static_cast<int>(std::ceil(longest / target)), 1, std::max(1, options.max_subdivisions));
  }
  if (k < 1 || k > 64) throw InvalidInput("expected 1 to 64 subdivisions per tetrahedron edge, got " + std::to_string(k));

  // The lattice points of every tetrahedron, named once.
  const std::vector<std::array<Eigen::Vector3i, 4>> pieces = edgewise_subdivision(k);
  std::map<LatticeKey, std::int64_t> ids;
  std::vector<Eigen::Vector3d> sample_points;
  std::vector<std::array<std::int64_t, 4>> sub_tetrahedra;
  sub_tetrahedra.reserve(domain.tetrahedra.size() * pieces.size());
  for (const std::array<int, 4>& tet : domain.tetrahedra) {
    std::array<int, 4> w = tet;
    std::sort(w.begin(), w.end());
    const auto P = [&](int c) -> const Eigen::Vector3d& { return domain.points[static_cast<std::size_t>(w[static_cast<std::size_t>(c)])]; };
    for (const auto& piece : pieces) {
      std::array<std::int64_t, 4> corners;
      for (int c = 0; c < 4; ++c) {
        const Eigen::Vector3i& y = piece[static_cast<std::size_t>(c)];
        const std::array<int, 4> numerators{k - y[0], y[0] - y[1], y[1] - y[2], y[2]};
        const auto [it, added] = ids.emplace(lattice_key(w, numerators), static_cast<std::int64_t>(sample_points.size()));
        if (added) {
          Eigen::Vector3d x = Eigen::Vector3d::Zero();
          for (int m = 0; m < 4; ++m) x += numerators[static_cast<std::size_t>(m)] * P(m);
          sample_points.push_back(x / k);
        }
        corners[static_cast<std::size_t>(c)] = it->second;
      }
      sub_tetrahedra.push_back(corners);
    }
  }

  // The attribute at every sample.
  std::vector<double> samples(sample_points.size());
  const DmsSplineEvaluator prototype(volume);
  tbb::enumerable_thread_specific<DmsSplineEvaluator> evaluators(prototype);
  tbb::parallel_for(std::size_t{0}, sample_points.size(), [&](std::size_t i) {
    samples[i] = evaluators.local().evaluate(sample_points[i]).value[column] - options.value;
  });
  const auto [lo, hi] = std::minmax_element(samples.begin(), samples.end());
  const double range = std::max(*hi - *lo, 1e-300);

  MarchingTetrahedra marching;
  for (const auto& t : sub_tetrahedra) {
    std::array<MarchingTetrahedra::Sample, 4> s;
    for (int c = 0; c < 4; ++c) {
      const std::int64_t id = t[static_cast<std::size_t>(c)];
      s[static_cast<std::size_t>(c)] = {id, sample_points[static_cast<std::size_t>(id)], samples[static_cast<std::size_t>(id)]};
    }
    marching.add_tetrahedron_oriented_by_corners(s);
  }

  SimplexIsosurface result;
  result.subdivisions = k;
  const std::size_t vertices = marching.vertices().size();
  std::vector<Eigen::Vector3d> domain_points(vertices), positions(vertices), normals(vertices);
  std::vector<double> residuals(vertices, 0.0);
  std::vector<long long> steps(vertices, 0);
  tbb::parallel_for(std::size_t{0}, vertices, [&](std::size_t v) {
    DmsSplineEvaluator& evaluator = evaluators.local();
    const auto& edge = marching.vertex_edges()[v];
    const Eigen::Vector3d a = sample_points[static_cast<std::size_t>(edge[0])], b = sample_points[static_cast<std::size_t>(edge[1])];
    double fa = samples[static_cast<std::size_t>(edge[0])], fb = samples[static_cast<std::size_t>(edge[1])];
    Eigen::Vector3d x = marching.vertices()[v];
    if (options.exact_vertices && fa != fb && (fa < 0) != (fb < 0)) {
      // Illinois regula falsi on the bracket [0, 1] of the edge: superlinear, never leaves it.
      double s0 = 0, s1 = 1;
      int side = 0;
      for (int iteration = 0; iteration < 60; ++iteration) {
        const double s = (s0 * fb - s1 * fa) / (fb - fa);
        x = a + s * (b - a);
        const double f = evaluator.evaluate(x).value[column] - options.value;
        ++steps[v];
        if (f == 0 || std::abs(s1 - s0) < 1e-15) break;
        if ((f < 0) == (fa < 0)) {
          s0 = s, fa = f;
          if (side == -1) fb /= 2;
          side = -1;
        } else {
          s1 = s, fb = f;
          if (side == 1) fa /= 2;
          side = 1;
        }
        if (std::abs(f) < 1e-14 * range) break;
      }
    }
    const DmsSplinePoint p = evaluator.evaluate(x, 1);
    ++steps[v];
    domain_points[v] = x;
    positions[v] = p.value.head<3>();
    residuals[v] = std::abs(p.value[column] - options.value) / range;
    const Eigen::Matrix3d jacobian = p.gradient.topRows<3>();
    const Eigen::Vector3d gradient = p.gradient.row(column).transpose();
    Eigen::Vector3d n = jacobian.transpose().fullPivLu().solve(gradient);
    normals[v] = n.norm() > 0 && n.allFinite() ? n.normalized() : Eigen::Vector3d::Zero();
  });
  for (std::size_t v = 0; v < vertices; ++v) {
    result.mesh.add_vertex(positions[v], domain_points[v]);
    result.evaluations += steps[v];
    result.largest_residual = std::max(result.largest_residual, residuals[v]);
  }
  result.evaluations += static_cast<long long>(sample_points.size());
  result.normals = std::move(normals);
  for (const auto& t : marching.triangles()) result.mesh.add_triangle(t[0], t[1], t[2], Part::AttributeIsosurface);
  return result;
}

}  // namespace volspline
