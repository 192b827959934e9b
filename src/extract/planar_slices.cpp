#include "volspline/extract/planar_slices.h"
#include "volspline/core/resource_limits.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "volspline/core/error.h"
#include "volspline/mesh/parts.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/marching_tetrahedra.h"

namespace volspline {
namespace {

void check_volume(const BSplineVolume& volume) {
  if (volume.dimension() != 3) {
    throw InvalidInput("slices need control points in R^3, got " + std::to_string(volume.dimension()) +
                           " coordinates per point",
                       "control_points");
  }
}

void check_plane(const Plane& plane, std::size_t index) {
  if (!plane.normal.allFinite() || !std::isfinite(plane.offset) || plane.normal.norm() == 0)
    throw InvalidInput("slice plane " + std::to_string(index) + " needs a finite nonzero normal and a finite offset");
}

// The sample grid and V on it, shared by every plane.
struct SampledVolume {
  std::array<std::vector<double>, 3> samples;
  std::vector<double> points;  // 3 per grid point, u fastest
  double scale = 0;            // largest |coordinate|, for the root tolerance

  SampledVolume(const BSplineVolume& volume, int resolution) {
    for (int d = 0; d < 3; ++d) samples[static_cast<std::size_t>(d)] = face_samples(volume.knot_vector(d), resolution);
    // The grid is the whole volume's: 3 coordinates per point and about as much again while
    // evaluate_grid builds it (docs/testing.md, "Hostile input").
    require_memory(saturating_product({samples[0].size(), samples[1].size(), samples[2].size(), 32}),
                   "sampling the volume on a " + std::to_string(samples[0].size()) + " x " + std::to_string(samples[1].size()) +
                       " x " + std::to_string(samples[2].size()) + " grid (--resolution " + std::to_string(resolution) + ")");
    points = volume.evaluate_grid(samples, 0);
    for (double x : points) scale = std::max(scale, std::abs(x));
  }
  std::array<std::size_t, 3> counts() const { return {samples[0].size(), samples[1].size(), samples[2].size()}; }
  Eigen::Vector3d parameter(std::int64_t id) const {
    const auto n = counts();
    const auto i = static_cast<std::size_t>(id) % n[0];
    const auto j = static_cast<std::size_t>(id) / n[0] % n[1];
    const auto k = static_cast<std::size_t>(id) / (n[0] * n[1]);
    return {samples[0][i], samples[1][j], samples[2][k]};
  }
};

// The root of g on the segment from a (g = ga) to b (g = gb), ga and gb of opposite signs
// (ga >= 0 > gb or the reverse), by regula falsi with the Illinois modification: superlinear on
// the smooth restriction of n·V − d, and it never leaves the bracket, so the domain point stays
// on the tetrahedron edge and inside the domain.
Eigen::Vector3d edge_root(const BSplineVolume& volume, const Plane& plane, const Eigen::Vector3d& a, double ga,
                          const Eigen::Vector3d& b, double gb, double tolerance) {
  if (ga == 0) return a;
  if (gb == 0) return b;
  double s0 = 0, s1 = 1, g0 = ga, g1 = gb;
  int side = 0;
  double x[3];
  for (int iteration = 0; iteration < 200; ++iteration) {
    double s = (s0 * g1 - s1 * g0) / (g1 - g0);
    if (!(s > s0 && s < s1)) s = 0.5 * (s0 + s1);
    const Eigen::Vector3d t = a + s * (b - a);
    volume.evaluate({t[0], t[1], t[2]}, x);
    const double g = plane.normal.dot(Eigen::Vector3d(x[0], x[1], x[2])) - plane.offset;
    if (std::abs(g) <= tolerance || s1 - s0 <= 4 * std::numeric_limits<double>::epsilon()) return t;
    if ((g >= 0) == (g0 >= 0)) {
      s0 = s;
      g0 = g;
      if (side == -1) g1 *= 0.5;
      side = -1;
    } else {
      s1 = s;
      g1 = g;
      if (side == 1) g0 *= 0.5;
      side = 1;
    }
  }
  const double s = std::abs(g0) < std::abs(g1) ? s0 : s1;
  return a + s * (b - a);
}

void slice_one(const BSplineVolume& volume, const SampledVolume& grid, const Plane& plane, TriangleMesh& mesh) {
  const auto n = grid.counts();
  const std::size_t total = n[0] * n[1] * n[2];
  std::vector<double> g(total);
  for (std::size_t p = 0; p < total; ++p)
    g[p] = plane.normal.dot(Eigen::Vector3d(grid.points[3 * p], grid.points[3 * p + 1], grid.points[3 * p + 2])) - plane.offset;

  // Kuhn's subdivision: the tetrahedra of a cube are the monotone paths from corner 000 to 111,
  // one per order of the three axes; neighbouring cubes cut their common face along the same
  // diagonal, so the tetrahedra form a conforming mesh and the surface has no cracks.
  static constexpr int kPaths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const std::array<std::size_t, 3> stride{1, n[0], n[0] * n[1]};
  MarchingTetrahedra marching;
  for (std::size_t k = 0; k + 1 < n[2]; ++k)
    for (std::size_t j = 0; j + 1 < n[1]; ++j)
      for (std::size_t i = 0; i + 1 < n[0]; ++i) {
        const std::size_t base = i + stride[1] * j + stride[2] * k;
        bool positive = false, negative = false;
        for (int c = 0; c < 8; ++c) {
          const std::size_t id = base + (c & 1 ? stride[0] : 0) + (c & 2 ? stride[1] : 0) + (c & 4 ? stride[2] : 0);
          (g[id] >= 0 ? positive : negative) = true;
        }
        if (!positive || !negative) continue;
        for (const auto& path : kPaths) {
          std::array<MarchingTetrahedra::Sample, 4> tetrahedron;
          std::size_t id = base;
          for (int corner = 0; corner < 4; ++corner) {
            if (corner > 0) id += stride[static_cast<std::size_t>(path[corner - 1])];
            tetrahedron[static_cast<std::size_t>(corner)] = {static_cast<std::int64_t>(id), grid.parameter(static_cast<std::int64_t>(id)), g[id]};
          }
          marching.add_tetrahedron_oriented_by_corners(tetrahedron);
        }
      }

  const double tolerance = 8 * std::numeric_limits<double>::epsilon() * (grid.scale + std::abs(plane.offset));
  // Vertices whose crossing is a sample point itself (g exactly 0 there, as for a plane through
  // grid points) come from several edges; they are welded by their domain point.
  std::map<std::array<double, 3>, int> vertex_of;
  std::vector<int> index(marching.vertices().size());
  double x[3];
  for (std::size_t v = 0; v < index.size(); ++v) {
    const auto& edge = marching.vertex_edges()[v];
    const Eigen::Vector3d root = edge_root(volume, plane, grid.parameter(edge[0]), g[static_cast<std::size_t>(edge[0])],
                                           grid.parameter(edge[1]), g[static_cast<std::size_t>(edge[1])], tolerance);
    auto [it, inserted] = vertex_of.try_emplace({root[0], root[1], root[2]}, static_cast<int>(mesh.num_vertices()));
    if (inserted) {
      volume.evaluate({root[0], root[1], root[2]}, x);
      Eigen::Vector3d point(x[0], x[1], x[2]);
      // The root leaves |n·V − d| at rounding level; removing that residue puts the vertex in
      // the plane while moving it by no more than the tolerance.
      point -= (plane.normal.dot(point) - plane.offset) * plane.normal;
      mesh.add_vertex(point, root);
    }
    index[v] = it->second;
  }
  for (const auto& t : marching.triangles()) {
    const int a = index[static_cast<std::size_t>(t[0])], b = index[static_cast<std::size_t>(t[1])],
              c = index[static_cast<std::size_t>(t[2])];
    if (a != b && b != c && a != c) mesh.add_triangle(a, b, c, Part::Slice);
  }
}

}  // namespace

TriangleMesh planar_slices(const BSplineVolume& placed, const std::vector<Plane>& planes, const SliceOptions& options) {
  check_volume(placed);
  if (options.resolution < 1) throw InvalidInput("the slice resolution must be at least 1");
  // Sliced at the local origin: signed distances n·x − c of points far from 0 would otherwise be
  // rounded to ulp(|x|), not to the solid's size; the planes move with the solid, the mesh back.
  const BSplineVolume volume = placed.translated_to_local_origin();
  const Eigen::Vector3d shift(placed.local_origin()[0], placed.local_origin()[1], placed.local_origin()[2]);
  std::vector<Plane> unit(planes.size());
  for (std::size_t p = 0; p < planes.size(); ++p) {
    check_plane(planes[p], p);
    const double length = planes[p].normal.norm();
    unit[p] = {planes[p].normal / length, (planes[p].offset - planes[p].normal.dot(shift)) / length};
  }
  TriangleMesh mesh;
  if (planes.empty()) return mesh;
  const SampledVolume grid(volume, options.resolution);
  for (const Plane& plane : unit) slice_one(volume, grid, plane, mesh);
  if (!shift.isZero())
    for (Eigen::Vector3d& p : mesh.positions) p += shift;
  return mesh;
}

TriangleMesh planar_slice(const BSplineVolume& volume, const Plane& plane, const SliceOptions& options) {
  return planar_slices(volume, {plane}, options);
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> sampled_bounding_box(const BSplineVolume& volume, int resolution) {
  check_volume(volume);
  if (resolution < 1) throw InvalidInput("the sampling resolution must be at least 1");
  const SampledVolume grid(volume, resolution);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t p = 0; 3 * p < grid.points.size(); ++p) {
    const Eigen::Vector3d x(grid.points[3 * p], grid.points[3 * p + 1], grid.points[3 * p + 2]);
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return {lo, hi};
}

std::vector<Plane> parallel_planes(int axis, int count, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (axis < 0 || axis > 2) throw InvalidInput("expected a slice axis 0..2 (x, y, z), got " + std::to_string(axis));
  if (count < 1) throw InvalidInput("expected at least 1 slice, got " + std::to_string(count));
  std::vector<Plane> planes;
  for (int i = 1; i <= count; ++i)
    planes.push_back({Eigen::Vector3d::Unit(axis), lo[axis] + (hi[axis] - lo[axis]) * i / (count + 1)});
  return planes;
}

std::vector<Plane> core_planes(const Eigen::Vector3d& point) {
  if (!point.allFinite()) throw InvalidInput("the core point must be finite");
  return {{Eigen::Vector3d::UnitX(), point.x()}, {Eigen::Vector3d::UnitY(), point.y()}, {Eigen::Vector3d::UnitZ(), point.z()}};
}

std::vector<Plane> paddlewheel_planes(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, int count) {
  if (count < 1) throw InvalidInput("expected at least 1 paddlewheel plane, got " + std::to_string(count));
  if (!axis.allFinite() || axis.norm() == 0 || !point.allFinite())
    throw InvalidInput("a paddlewheel needs a finite point and a finite nonzero axis");
  const Eigen::Vector3d a = axis.normalized();
  // A first normal perpendicular to the axis, from the coordinate axis least aligned with it.
  Eigen::Index least;
  a.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d first = a.cross(Eigen::Vector3d::Unit(least)).normalized();
  std::vector<Plane> planes;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d normal = Eigen::AngleAxisd(std::numbers::pi * i / count, a) * first;
    planes.push_back(plane_through(point, normal));
  }
  return planes;
}

}  // namespace volspline
