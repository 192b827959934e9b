#include "volspline/extract/jacobian_zero_surface.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <queue>
#include <string>

#include "volspline/analysis/jacobian_determinant.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/core/progress.h"
#include "volspline/mesh/conforming_tetrahedra.h"
#include "volspline/mesh/marching_tetrahedra.h"

namespace volspline {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void check_options(const BoundaryOptions& o) {
  if (!(o.tolerance > 0) || !std::isfinite(o.tolerance)) {
    throw InvalidInput("tolerance must be a finite number > 0, got " + format_double(o.tolerance));
  }
  if (o.max_cells < 1) throw InvalidInput("the cell budget must be at least 1");
  if (o.min_level < 0 || o.min_level > 20) throw InvalidInput("min_level must be in 0..20, got " + std::to_string(o.min_level));
  if (o.resolution < 1 || o.resolution > 1024) throw InvalidInput("resolution must be in 1..1024, got " + std::to_string(o.resolution));
  if (o.face_resolution < 1 || o.face_resolution > 4096) {
    throw InvalidInput("face resolution must be in 1..4096, got " + std::to_string(o.face_resolution));
  }
}

// Newton steps on J towards J = 0 from a vertex, staying in the domain and within `reach` of
// the start; kept only if |J| decreases.
Eigen::Vector3d snap_to_zero(const BSplineVolume& v, const Eigen::Vector3d& start, double reach) {
  Eigen::Vector3d x = start;
  double d[30];
  v.evaluate_derivatives({x[0], x[1], x[2]}, 2, d);
  JacobianWithGradient s = jacobian_with_gradient(d);
  const double first = std::abs(s.value);
  // A vertex on a face of the domain is where the implicit surface meets a face patch: it moves
  // within that face only.
  Eigen::Vector3d free = Eigen::Vector3d::Ones();
  for (int e = 0; e < 3; ++e) {
    if (start[e] == v.domain_min(e) || start[e] == v.domain_max(e)) free[e] = 0;
  }
  for (int iteration = 0; iteration < 8; ++iteration) {
    s.gradient = s.gradient.cwiseProduct(free);
    const double g2 = s.gradient.squaredNorm();
    if (!(g2 > 0)) break;
    Eigen::Vector3d next = x - s.value / g2 * s.gradient;
    for (int e = 0; e < 3; ++e) next[e] = std::clamp(next[e], v.domain_min(e), v.domain_max(e));
    if ((next - start).norm() > reach) break;
    v.evaluate_derivatives({next[0], next[1], next[2]}, 2, d);
    const JacobianWithGradient t = jacobian_with_gradient(d);
    if (!(std::abs(t.value) < std::abs(s.value))) break;
    x = next;
    s = t;
    if (std::abs(s.value) <= 1e-15 * first) break;
  }
  return x;
}

// Largest |J| over a 17^3 grid of the domain: the scale that relative figures refer to.
double sampled_jacobian_scale(const BSplineVolume& v) {
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i <= 16; ++i) samples[static_cast<std::size_t>(d)].push_back(v.domain_min(d) + (v.domain_max(d) - v.domain_min(d)) * i / 16);
  }
  const auto g = v.evaluate_grid(samples, 1);
  const std::size_t n = 17 * 17 * 17;
  double best = 0;
  for (std::size_t p = 0; p < n; ++p) best = std::max(best, std::abs(jacobian_determinant(g.data() + 3 * p, 3 * n)));
  return best;
}

// Maps the marching-tetrahedra result through the volume into `out` (Part::JacobianZero), with
// statistics.
void finish_surface(const BSplineVolume& volume, MarchingTetrahedra& mt, const BoundaryOptions& options,
                    SolidBoundary& out) {
  auto t = Clock::now();
  const auto& verts = mt.vertices();
  if (options.snap) {
    const ProgressPhase phase(options.progress, "snap", static_cast<double>(verts.size()));
    // A vertex may move at most 5% of the largest domain extent: Newton steps that go further
    // have left the basin of the zero set the vertex came from.
    double extent = 0;
    for (int d = 0; d < 3; ++d) extent = std::max(extent, volume.domain_max(d) - volume.domain_min(d));
    for (std::size_t i = 0; i < verts.size(); ++i) {
      mt.set_vertex(static_cast<int>(i), snap_to_zero(volume, verts[i], 0.05 * extent));
      phase.advance();
    }
  }
  out.stats.seconds_snap = options.snap ? since(t) : 0;
  const ProgressPhase phase(options.progress, "mapping");
  t = Clock::now();
  std::vector<std::array<double, 3>> params(verts.size());
  for (std::size_t i = 0; i < verts.size(); ++i) params[i] = {verts[i][0], verts[i][1], verts[i][2]};
  const std::vector<double> d = params.empty() ? std::vector<double>{} : volume.evaluate_points(params, 2);
  double scale = sampled_jacobian_scale(volume);
  double max_j = 0, max_distance = 0;
  TriangleMesh& mesh = out.mesh;
  const int base = static_cast<int>(mesh.num_vertices());
  for (std::size_t i = 0; i < verts.size(); ++i) {
    const double* di = d.data() + i * 30;
    const JacobianWithGradient s = jacobian_with_gradient(di);
    max_j = std::max(max_j, std::abs(s.value));
    const double g = s.gradient.norm();
    if (g > 0) max_distance = std::max(max_distance, std::abs(s.value) / g);
    mesh.add_vertex(Eigen::Vector3d(di[0], di[1], di[2]), verts[i]);
  }
  scale = std::max(scale, max_j);
  for (const auto& tri : mt.triangles()) mesh.add_triangle(base + tri[0], base + tri[1], base + tri[2], Part::JacobianZero);
  out.stats.triangles[static_cast<std::size_t>(part_number(Part::JacobianZero))] = static_cast<std::int64_t>(mt.triangles().size());
  out.stats.max_rel_jacobian_at_vertices = scale > 0 ? max_j / scale : 0;
  out.stats.max_domain_distance = max_distance;
  out.stats.seconds_isosurface += since(t);
}

// The adaptive subdivision (§6): the leaves, each with whether the zero set may cross it.
std::vector<LatticeBox> subdivide(const JacobianSubdivision& sub, const BoundaryOptions& options, SolidBoundary& out) {
  // How many cells the subdivision will examine is not known beforehand (the share of the
  // domain finished says little: the cells along the zero set take nearly all the time), so it
  // reports the count.
  const ProgressPhase phase(options.progress, "subdivision", 0, "cells");
  std::vector<LatticeBox> leaves;
  auto leaf_of = [](const JacobianCell& c, bool kept) {
    LatticeBox l{c.origin, {}, kept};
    for (int d = 0; d < 3; ++d) l.extent[static_cast<std::size_t>(d)] = JacobianSubdivision::extent(c, d);
    return l;
  };
  auto wider = [](const JacobianCell& a, const JacobianCell& b) { return a.width() < b.width(); };
  std::priority_queue<JacobianCell, std::vector<JacobianCell>, decltype(wider)> queue(wider);
  for (auto& cell : sub.roots()) {
    ++out.stats.cells_examined;
    phase.advance();
    if (cell.excludes_zero()) {
      leaves.push_back(leaf_of(cell, false));
    } else {
      queue.push(std::move(cell));
    }
  }
  const double stop = options.tolerance * sub.scale();
  const bool by_width = options.stop == StopCriterion::Width || options.bounds == JacobianBoundMethod::Cone;
  while (!queue.empty()) {
    JacobianCell cell = queue.top();
    queue.pop();
    int direction = sub.split_direction(cell, by_width);
    // Cells keep an even lattice extent so that centres of cells and faces are lattice points.
    if (direction >= 0 && cell.level[static_cast<std::size_t>(direction)] >= JacobianSubdivision::kMaxLevel - 1) direction = -1;
    bool done = by_width ? cell.width() <= stop : sub.nonlinearity(cell) <= 0.5 * stop;
    for (int d = 0; d < 3; ++d) {
      if (cell.level[static_cast<std::size_t>(d)] < options.min_level &&
          (direction < 0 || cell.level[static_cast<std::size_t>(d)] < cell.level[static_cast<std::size_t>(direction)] || done)) {
        direction = d;
        done = false;
      }
    }
    if (done || direction < 0 || out.stats.cells_examined + 2 > options.max_cells) {
      leaves.push_back(leaf_of(cell, true));
      continue;
    }
    auto [a, b] = sub.split(cell, direction);
    phase.advance(2);
    for (JacobianCell* child : {&a, &b}) {
      ++out.stats.cells_examined;
      if (child->excludes_zero()) {
        leaves.push_back(leaf_of(*child, false));
      } else {
        queue.push(std::move(*child));
      }
    }
  }
  for (const LatticeBox& l : leaves) out.stats.cells_kept += l.kept ? 1 : 0;
  return leaves;
}

// Marching tetrahedra (§7) on the conforming tetrahedra of the kept leaves, J evaluated once
// at each of their corners.
void march_kept_leaves(const BSplineVolume& volume, const JacobianSubdivision& sub, const std::vector<LatticeBox>& leaves,
                       const BoundaryOptions& options, MarchingTetrahedra& mt, SolidBoundary& out) {
  auto t = Clock::now();
  std::optional<ProgressPhase> phase(std::in_place, options.progress, "tetrahedra");
  const ConformingTetrahedralMesh tets = conforming_tetrahedra(leaves);
  std::vector<std::array<double, 3>> params(tets.points.size());
  std::vector<Eigen::Vector3d> domain(tets.points.size());
  for (std::size_t i = 0; i < tets.points.size(); ++i) {
    domain[i] = sub.parameter(tets.points[i]);
    params[i] = {domain[i][0], domain[i][1], domain[i][2]};
  }
  const std::vector<double> d = volume.evaluate_points(params, 1);
  std::vector<double> value(tets.points.size());
  for (std::size_t i = 0; i < tets.points.size(); ++i) value[i] = jacobian_determinant(d.data() + i * 12);
  out.stats.seconds_tetrahedra = since(t);
  phase.emplace(options.progress, "marching", static_cast<double>(tets.tetrahedra.size()));
  t = Clock::now();
  for (const auto& tet : tets.tetrahedra) {
    std::array<MarchingTetrahedra::Sample, 4> s;
    for (std::size_t k = 0; k < 4; ++k) {
      const auto i = static_cast<std::size_t>(tet[k]);
      s[k] = {tet[k], domain[i], value[i]};
    }
    mt.add_tetrahedron(s);
    phase->advance();
  }
  out.stats.seconds_isosurface = since(t);
}

SolidBoundary adaptive_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  SolidBoundary out;
  const auto t = Clock::now();
  const JacobianSubdivision sub(volume, options.bounds);
  const std::vector<LatticeBox> leaves = subdivide(sub, options, out);
  out.stats.seconds_subdivision = since(t);
  MarchingTetrahedra mt;
  if (out.stats.cells_kept > 0) march_kept_leaves(volume, sub, leaves, options, mt, out);
  finish_surface(volume, mt, options, out);
  return out;
}

SolidBoundary uniform_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  SolidBoundary out;
  auto t = Clock::now();
  std::optional<ProgressPhase> phase(std::in_place, options.progress, "sampling");
  const int n = options.resolution;
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i <= n; ++i) samples[static_cast<std::size_t>(d)].push_back(volume.domain_min(d) + (volume.domain_max(d) - volume.domain_min(d)) * i / n);
  }
  const auto g = volume.evaluate_grid(samples, 1);
  const std::size_t m = static_cast<std::size_t>(n + 1), count = m * m * m;
  std::vector<double> value(count);
  for (std::size_t p = 0; p < count; ++p) value[p] = jacobian_determinant(g.data() + 3 * p, 3 * count);
  out.stats.cells_examined = static_cast<std::int64_t>(n) * n * n;
  out.stats.seconds_subdivision = since(t);
  phase.emplace(options.progress, "marching", n);
  t = Clock::now();
  MarchingTetrahedra mt;
  // Six tetrahedra around the main diagonal of each cube (Kuhn): neighbouring cubes agree on
  // the diagonals of their common faces, so the mesh is conforming.
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        std::array<std::size_t, 8> c{};
        bool negative = false, positive = false;
        for (int q = 0; q < 8; ++q) {
          c[static_cast<std::size_t>(q)] = static_cast<std::size_t>(i + (q & 1)) + m * (static_cast<std::size_t>(j + ((q >> 1) & 1)) + m * static_cast<std::size_t>(k + ((q >> 2) & 1)));
          (value[c[static_cast<std::size_t>(q)]] < 0 ? negative : positive) = true;
        }
        if (!(negative && positive)) continue;
        ++out.stats.cells_kept;
        for (const auto& tet : kKuhnTetrahedra) {
          std::array<MarchingTetrahedra::Sample, 4> s;
          for (std::size_t q = 0; q < 4; ++q) {
            const std::size_t idx = c[static_cast<std::size_t>(tet[q])];
            const std::size_t ii = idx % m, jj = (idx / m) % m, kk = idx / (m * m);
            s[q] = {static_cast<std::int64_t>(idx), Eigen::Vector3d(samples[0][ii], samples[1][jj], samples[2][kk]), value[idx]};
          }
          mt.add_tetrahedron(s);
        }
      }
    }
    phase->advance();
  }
  out.stats.seconds_isosurface = since(t);
  phase.reset();
  finish_surface(volume, mt, options, out);
  return out;
}

}  // namespace

SolidBoundary jacobian_zero_surface(const BSplineVolume& volume, const BoundaryOptions& options) {
  check_options(options);
  if (volume.dimension() != 3) {
    throw InvalidInput("the boundary of a solid needs a volume in R^3, got control points of dimension " + std::to_string(volume.dimension()));
  }
  const auto start = Clock::now();
  SolidBoundary out = options.method == ZeroSurfaceMethod::Adaptive ? adaptive_zero_surface(volume, options)
                                                                    : uniform_zero_surface(volume, options);
  out.stats.seconds_total = since(start);
  return out;
}

}  // namespace volspline
