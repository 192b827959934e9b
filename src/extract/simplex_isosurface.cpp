#include "volspline/extract/simplex_isosurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "simplex_sampling.h"
#include "volspline/core/error.h"
#include "volspline/mesh/marching_tetrahedra.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

SimplexIsosurface simplex_isosurface(const DmsSplineVolume& volume, const SimplexIsosurfaceOptions& options) {
  if (volume.attribute_names().empty()) throw InvalidInput("the volume has no attributes to take an isosurface of");
  const int column = options.attribute.empty() ? 3 : volume.attribute_column(options.attribute);
  const TetrahedralMesh& domain = volume.domain();
  SimplexSampling sampling = simplex_sampling(domain, options.subdivisions, options.target_edge);
  const std::vector<Eigen::Vector3d>& sample_points = sampling.points;
  const std::vector<std::array<std::int64_t, 4>>& sub_tetrahedra = sampling.tetrahedra;
  const int k = sampling.subdivisions;

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
  result.sampled_tetrahedra = static_cast<long long>(sub_tetrahedra.size());
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
