#include "volspline/boxspline/zero_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "volspline/boxspline/lattice_isosurface.h"
#include "volspline/core/error.h"
#include "volspline/core/progress.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {

namespace {

struct Region {
  Eigen::Vector3d lo, hi;
  bool contains(const Eigen::Vector3d& x, double slack) const {
    return (x.array() >= lo.array() - slack).all() && (x.array() <= hi.array() + slack).all();
  }
};

/// Stencils for the node kinds of the doubled grid, indexed by parity bits x + 2y + 4z.
const std::array<std::vector<std::pair<std::array<int, 3>, double>>, 8>& node_stencils() {
  static const auto stencils = [] {
    std::array<std::vector<std::pair<std::array<int, 3>, double>>, 8> s;
    for (int bits = 0; bits < 8; ++bits) {
      const int odd = (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1);
      if (odd == 1) continue;  // edge midpoints are not partition vertices
      s[bits] = point_value_stencil(Eigen::Vector3d(0.5 * (bits & 1), 0.5 * ((bits >> 1) & 1), 0.5 * ((bits >> 2) & 1)));
    }
    return s;
  }();
  return stencils;
}

// What one meshing pass works on: the refined lattice, the box where the spline defines the
// surface, the region beyond it where the primitives do (if any), and the grid cubes covering it.
struct Pass {
  const LatticeField& coarse;
  LatticeField fine;
  const SceneNode* root;
  Region box;
  std::optional<Region> exterior;
  double slack;
  std::array<int, 3> first_cell{}, cells{};

  // f at a point: the spline in the box, the primitives outside.
  double function(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
    if (box.contains(x, slack) && coarse.in_domain(x)) return coarse.evaluate(x, gradient);
    return root != nullptr ? scene_value(*root, x, gradient) : coarse.evaluate(x, gradient);
  }
  double exterior_value(const Eigen::Vector3d& x) const {
    return root != nullptr ? scene_value(*root, x) : std::numeric_limits<double>::quiet_NaN();
  }
  bool lattice_index_valid(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < fine.size[0] && j < fine.size[1] && k < fine.size[2];
  }
};

// Grid cubes: inside the box only, or covering the whole meshed region.
void place_cells(Pass& pass) {
  const double g = pass.fine.spacing;
  for (int d = 0; d < 3; ++d) {
    double first, last;
    if (pass.exterior) {
      first = std::floor((pass.exterior->lo[d] - pass.fine.origin[d]) / g + 1e-9);
      last = std::ceil((pass.exterior->hi[d] - pass.fine.origin[d]) / g - 1e-9);
    } else {
      first = std::ceil((pass.box.lo[d] - pass.fine.origin[d]) / g - 1e-9);
      last = std::floor((pass.box.hi[d] - pass.fine.origin[d]) / g + 1e-9);
    }
    if (!(last - first >= 1.0))
      throw InvalidInput("the box is narrower than one lattice cell after refinement; enlarge it or refine more");
    if (last - first > 1e6) throw InvalidInput("the meshed region has too many grid cells for the spacing");
    pass.first_cell[d] = static_cast<int>(first);
    pass.cells[d] = static_cast<int>(last - first);
  }
}

// Control method: the refined coefficients at the cube corners (face and cube centres are
// averaged by march_tetrahedra), the CSG function outside the box.
void set_control_values(const Pass& pass, TetrahedralGrid& grid, const ProgressPhase& phase) {
  const auto nodes = grid.nodes();
  const auto& m0 = pass.first_cell;
  for (int c = 0; c < nodes[2]; c += 2)
    for (int b = 0; b < nodes[1]; b += 2)
      for (int a = 0; a < nodes[0]; a += 2) {
        const Eigen::Vector3d x = grid.node_position(a, b, c);
        const int i = m0[0] + a / 2, j = m0[1] + b / 2, k = m0[2] + c / 2;
        grid.corner(a / 2, b / 2, c / 2) =
            pass.box.contains(x, pass.slack) && pass.lattice_index_valid(i, j, k) ? pass.fine.at(i, j, k) : pass.exterior_value(x);
        if (a == 0 && b == 0) phase.advance(2);
      }
}

// Exact method: the spline's values at every partition vertex (fixed stencils of the refined
// coefficients), the CSG function outside the box.
void set_exact_values(const Pass& pass, TetrahedralGrid& grid, const ProgressPhase& phase) {
  const auto nodes = grid.nodes();
  const auto& m0 = pass.first_cell;
  const auto& stencils = node_stencils();
  for (int c = 0; c < nodes[2]; ++c)
    for (int b = 0; b < nodes[1]; ++b)
      for (int a = 0; a < nodes[0]; ++a) {
        if (a == 0 && b == 0) phase.advance();
        const int bits = (a & 1) + 2 * (b & 1) + 4 * (c & 1);
        if ((a & 1) + (b & 1) + (c & 1) == 1) continue;
        const Eigen::Vector3d x = grid.node_position(a, b, c);
        if (!pass.box.contains(x, pass.slack)) {
          grid.value(a, b, c) = pass.exterior_value(x);
          continue;
        }
        const int i = m0[0] + a / 2, j = m0[1] + b / 2, k = m0[2] + c / 2;
        double sum = 0.0;
        bool complete = true;
        for (const auto& [m, w] : stencils[static_cast<std::size_t>(bits)]) {
          if (!pass.lattice_index_valid(i - m[0], j - m[1], k - m[2])) {
            complete = false;
            break;
          }
          sum += w * pass.fine.at(i - m[0], j - m[1], k - m[2]);
        }
        grid.value(a, b, c) = complete ? sum : pass.coarse.value(x);
      }
}

// Cubes whose centre lies in the box are the spline's, the others the primitives'.
void set_cube_parts(const Pass& pass, TetrahedralGrid& grid) {
  const auto& cells = pass.cells;
  grid.cube_parts.resize(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2]);
  std::size_t n = 0;
  for (int c = 0; c < cells[2]; ++c)
    for (int b = 0; b < cells[1]; ++b)
      for (int a = 0; a < cells[0]; ++a)
        grid.cube_parts[n++] =
            pass.box.contains(grid.node_position(2 * a + 1, 2 * b + 1, 2 * c + 1), pass.slack) ? Part::BlendSpline : Part::BlendPrimitive;
}

// Exact method with projection: each vertex moves onto f = 0 by at most 8 Newton steps, never
// farther than one grid spacing from where marching put it.
void project_vertices(const Pass& pass, TriangleMesh& mesh, Progress* progress) {
  const double g = pass.fine.spacing;
  const ProgressPhase phase(progress, "projection", static_cast<double>(mesh.positions.size()));
  for (Eigen::Vector3d& x : mesh.positions) {
    phase.advance();
    const Eigen::Vector3d start_point = x;
    Eigen::Vector3d y = x;
    for (int step = 0; step < 8; ++step) {
      Eigen::Vector3d gradient;
      const double f = pass.function(y, &gradient);
      const double length2 = gradient.squaredNorm();
      if (!(length2 > 0.0) || !std::isfinite(f)) break;
      const Eigen::Vector3d next = y - f / length2 * gradient;
      if ((next - start_point).norm() > g) break;
      const bool done = (next - y).norm() < 1e-15 * (1.0 + y.norm());
      y = next;
      if (done) break;
    }
    x = y;
  }
  mesh.parameters = mesh.positions;
}

// The largest |spline − CSG function| at box nodes of cubes crossing both the box boundary and
// the surface.
double seam_value_difference(const Pass& pass, const TetrahedralGrid& grid, bool control) {
  double worst = 0.0;
  const auto& cells = pass.cells;
  for (int c = 0; c < cells[2]; ++c)
    for (int b = 0; b < cells[1]; ++b)
      for (int a = 0; a < cells[0]; ++a) {
        int in_box = 0, negative = 0;
        for (int q = 0; q < 8; ++q) {
          const int x = 2 * a + 2 * (q & 1), y = 2 * b + (q & 2), z = 2 * c + ((q & 4) >> 1);
          in_box += pass.box.contains(grid.node_position(x, y, z), pass.slack);
          negative += (control ? grid.corner(x / 2, y / 2, z / 2) : grid.value(x, y, z)) < 0.0;
        }
        if (in_box == 0 || in_box == 8 || negative == 0 || negative == 8) continue;
        for (int q = 0; q < 8; ++q) {
          const Eigen::Vector3d x = grid.node_position(2 * a + 2 * (q & 1), 2 * b + (q & 2), 2 * c + ((q & 4) >> 1));
          if (pass.box.contains(x, pass.slack) && pass.coarse.in_domain(x))
            worst = std::max(worst, std::abs(pass.coarse.value(x) - scene_value(*pass.root, x)));
        }
      }
  return worst;
}

// ZeroSetStats beyond counts and seconds: edges, values and distances at the vertices, the seam.
void add_statistics(const Pass& pass, const TetrahedralGrid& grid, bool control, ZeroSet& out) {
  const EdgeStatistics edges = edge_statistics(out.mesh);
  out.stats.boundary_edges = edges.boundary_edges;
  out.stats.nonmanifold_edges = edges.nonmanifold_edges;
  out.stats.closed = edges.closed();
  const SceneNode* root = pass.root;
  const bool single_primitive = root != nullptr && root->operation == SceneOperation::Primitive &&
                                primitive_distance(root->primitive, Eigen::Vector3d::Zero()).has_value();
  double worst_distance = 0.0;
  for (const Eigen::Vector3d& x : out.mesh.positions) {
    out.stats.max_abs_value = std::max(out.stats.max_abs_value, std::abs(pass.function(x, nullptr)));
    if (single_primitive) worst_distance = std::max(worst_distance, *primitive_distance(root->primitive, x));
  }
  if (single_primitive) out.stats.max_distance = worst_distance;
  if (pass.exterior && root != nullptr) out.stats.seam_value_difference = seam_value_difference(pass, grid, control);
}

ZeroSet build(const LatticeField& coarse, const SceneNode* root, const Region& box, const std::optional<Region>& exterior,
              const ZeroSetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.levels < 0 || options.levels > 8)
    throw InvalidInput("expected between 0 and 8 refinement levels, got " + std::to_string(options.levels), "--levels");
  std::optional<ProgressPhase> phase(std::in_place, options.progress, "refinement");
  Pass pass{coarse, refine(coarse, options.levels), root, box, exterior, 0.0};
  const double g = pass.fine.spacing;
  pass.slack = 1e-9 * g;
  place_cells(pass);
  const bool control = options.method == ZeroSetMethod::Control;
  const auto& m0 = pass.first_cell;
  TetrahedralGrid grid(pass.fine.origin + g * Eigen::Vector3d(m0[0], m0[1], m0[2]), g, pass.cells,
                       control ? TetrahedralGrid::Layout::CornersAveraged : TetrahedralGrid::Layout::AllNodes);
  phase.emplace(options.progress, "values", grid.nodes()[2]);
  if (control) {
    set_control_values(pass, grid, *phase);
  } else {
    set_exact_values(pass, grid, *phase);
  }
  if (exterior) set_cube_parts(pass, grid);

  ZeroSet out;
  phase.emplace(options.progress, "marching");
  out.mesh = march_tetrahedra(grid);
  phase.reset();
  out.stats.grid_spacing = g;
  if (options.method == ZeroSetMethod::Exact && options.project) project_vertices(pass, out.mesh, options.progress);

  out.stats.vertices = out.mesh.num_vertices();
  out.stats.triangles = out.mesh.num_triangles();
  if (options.statistics) {
    phase.emplace(options.progress, "statistics");
    add_statistics(pass, grid, control, out);
  }
  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace

std::optional<double> primitive_distance(const ImplicitPrimitive& p, const Eigen::Vector3d& x) {
  const Eigen::Vector3d y = p.rotation.transpose() * (x - p.origin);
  const double rho = std::hypot(y.x(), y.y());
  switch (p.kind) {
    case PrimitiveKind::Sphere:
      return std::abs(y.norm() - p.radius);
    case PrimitiveKind::Plane:
      return std::abs(y.z());
    case PrimitiveKind::Cylinder:
      return std::abs(rho - p.radius);
    case PrimitiveKind::Torus:
      return std::abs(std::hypot(rho - p.radius, y.z()) - p.minor_radius);
    default:
      return std::nullopt;
  }
}

TriangleMesh implicit_zero_set(const SceneNode& node, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double spacing) {
  if (!((hi.array() > lo.array()).all())) throw InvalidInput("expected a nonempty box");
  if (!(spacing > 0.0) || !std::isfinite(spacing)) throw InvalidInput("expected a positive, finite spacing");
  std::array<int, 3> cells{};
  for (int d = 0; d < 3; ++d) {
    const double n = std::ceil((hi[d] - lo[d]) / spacing - 1e-9);
    if (n > 1e6) throw InvalidInput("the region has too many grid cells for the spacing");
    cells[d] = std::max(1, static_cast<int>(n));
  }
  TetrahedralGrid grid(lo, spacing, cells);
  const auto nodes = grid.nodes();
  for (int c = 0; c < nodes[2]; ++c)
    for (int b = 0; b < nodes[1]; ++b)
      for (int a = 0; a < nodes[0]; ++a)
        if ((a & 1) + (b & 1) + (c & 1) != 1) grid.value(a, b, c) = scene_value(node, grid.node_position(a, b, c));
  grid.cube_parts.assign(static_cast<std::size_t>(cells[0]) * cells[1] * cells[2], Part::BlendPrimitive);
  return march_tetrahedra(grid);
}

ZeroSet scene_zero_set(const Scene& scene, const ZeroSetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const LatticeField field = scene_field(scene);
  std::optional<Region> exterior;
  if (scene.domain) exterior = Region{scene.domain->first.cwiseMin(scene.box_min), scene.domain->second.cwiseMax(scene.box_max)};
  ZeroSet out = build(field, &scene.root, Region{scene.box_min, scene.box_max}, exterior, options);
  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

ZeroSet field_zero_set(const LatticeField& field, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       const ZeroSetOptions& options) {
  if (!field.in_domain(lo) || !field.in_domain(hi) || !((hi.array() > lo.array()).all()))
    throw InvalidInput("expected a nonempty box inside the field's domain");
  return build(field, nullptr, Region{lo, hi}, std::nullopt, options);
}

}  // namespace volspline
