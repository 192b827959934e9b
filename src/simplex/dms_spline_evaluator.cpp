#include "volspline/simplex/dms_spline_evaluator.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <span>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "box_grid.h"
#include "volspline/core/error.h"
#include "volspline/simplex/dms_tetrahedron_basis.h"
#include "volspline/simplex/simplex_spline.h"

namespace volspline {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_3 cgal_point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// The closed tetrahedron (a, b, c, d), positively oriented, holds x: x replaces each corner in
// turn without turning the orientation negative (exact).
bool in_closed_tetrahedron(const Eigen::Vector3d& x, const std::array<Eigen::Vector3d, 4>& t) {
  const Kernel::Point_3 a = cgal_point(t[0]), b = cgal_point(t[1]), c = cgal_point(t[2]), d = cgal_point(t[3]), p = cgal_point(x);
  return CGAL::orientation(p, b, c, d) != CGAL::NEGATIVE && CGAL::orientation(a, p, c, d) != CGAL::NEGATIVE &&
         CGAL::orientation(a, b, p, d) != CGAL::NEGATIVE && CGAL::orientation(a, b, c, p) != CGAL::NEGATIVE;
}

}  // namespace

// Per tetrahedron I of Ω: the four planes parallel to I's faces that enclose every knot of I's
// clouds (so they enclose every support hull(V_β^I)), and the grids over the supports' and the
// domain tetrahedra's bounding boxes.
struct DmsSplineEvaluator::Index {
  // The compiled recurrence of every tetrahedron's degree-n basis (its basis functions' knot
  // subsets and barycentric frames do not depend on the point): for for_each_basis_function, and
  // for evaluate where the DMS step below does not apply (compiled by the constructor then, else
  // on first use).
  const std::vector<DmsTetrahedronPlan>& full_plans(const DmsSplineVolume& volume) const {
    std::call_once(full_plans_compiled, [&] {
      std::vector<DmsTetrahedronPlan> compiled = compile_plans(volume, volume.degree());
      plans = std::move(compiled);
    });
    return plans;
  }
  static std::vector<DmsTetrahedronPlan> compile_plans(const DmsSplineVolume& volume, int degree) {
    const TetrahedralMesh& domain = volume.domain();
    std::vector<DmsTetrahedronPlan> out(domain.tetrahedra.size());
    // Isolated: a thread waiting for its share must not pick up an outer task that calls
    // full_plans again (call_once is not reentrant).
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(std::size_t{0}, domain.tetrahedra.size(), [&](std::size_t t) {
        const std::array<int, 4>& tet = domain.tetrahedra[t];
        out[t] = DmsTetrahedronPlan(degree, {volume.knots().cloud(tet[0]), volume.knots().cloud(tet[1]),
                                             volume.knots().cloud(tet[2]), volume.knots().cloud(tet[3])});
      });
    });
    return out;
  }
  mutable std::once_flag full_plans_compiled;
  mutable std::vector<DmsTetrahedronPlan> plans;
  // The DMS evaluation step for shared control vectors (Hua–He–Qin §3.2, Dahmen–Micchelli–Seidel
  // 1992): s(x) = Σ_I Σ_{|γ| = n−1} N_γ^I(x) ĉ_γ^I(x), ĉ_γ^I(x) = Σ_m λ_m(x | W_γ) c_{γ+e^m}^I with
  // the degree-(n−1) basis over the first n knots of each cloud and W_γ = (p_i, q_j, r_k, s_l).
  // It holds for the whole spline, not per basis function (the last knots t_{v,n} drop out only
  // in the sum over the tetrahedra around a shared control vector), so only for Shared volumes.
  bool lower_degree_step = false;
  std::vector<DmsTetrahedronPlan> lower_plans;
  // Per γ (dms_multi_indices(n − 1) order): the β positions of γ + e^m, m = 0..3.
  std::vector<std::array<int, 4>> raised;
  std::vector<std::array<Eigen::Vector4d, 4>> support_planes;  // n·x <= h as (n, h)
  // The domain tetrahedra's face planes, lowered by a margin that covers the rounding of n·x, so
  // that n·x < h proves x inside.
  std::vector<std::array<Eigen::Vector4d, 4>> domain_planes;
  // The same planes raised by 1e-10 of the tetrahedron's size: a point computed on ∂Ω (a lattice
  // point, an edge midpoint) may land a rounding error outside; within this margin it is inside.
  std::vector<std::array<Eigen::Vector4d, 4>> outer_planes;
  BoxGrid supports;
  BoxGrid tetrahedra;
  // For evaluate, one query and one cache line per tetrahedron: four planes parallel to the faces
  // (single precision, shifted outwards past their rounding) that enclose both the knots the
  // evaluation reads (the first n of each cloud for the DMS step, all n + 1 otherwise) and the
  // outer planes. The tetrahedra whose reach holds x are the candidates of the evaluation and
  // include every tetrahedron locate may return, so one grid serves both.
  struct alignas(64) ReachPlanes {
    std::array<float, 4> nx, ny, nz, h;
  };
  std::vector<ReachPlanes> reach;
  BoxGrid reach_grid;
  // The part of every tetrahedron (tetrahedron_parts): parts that touch without sharing points
  // are separate splines, so a point takes only the basis functions of the part that holds it.
  std::vector<int> parts;
  bool several_parts = false;
  // Keeps the tetrahedra of `part` (order kept).
  void keep_part(std::vector<int>& tetrahedra, int part) const {
    if (!several_parts) return;
    std::erase_if(tetrahedra, [&](int t) { return parts[static_cast<std::size_t>(t)] != part; });
  }
};

struct DmsSplineEvaluator::Scratch {
  explicit Scratch(int degree) : basis(degree), lower_basis(std::max(degree - 1, 0)) {}
  DmsTetrahedronBasis basis;
  DmsTetrahedronBasis lower_basis;
  DmsBasisValues values;
  DmsLastKnotFrames frames;
  std::vector<int> candidates;
};

DmsSplineEvaluator::DmsSplineEvaluator(const DmsSplineVolume& volume)
    : volume_(&volume), scratch_(std::make_unique<Scratch>(volume.degree())) {
  auto index = std::make_shared<Index>();
  const TetrahedralMesh& domain = volume.domain();
  const int per_cloud = volume.degree() + 1;
  if (volume.sharing() == DmsControlSharing::Shared && volume.degree() >= 1) {
    index->lower_plans = Index::compile_plans(volume, volume.degree() - 1);
    index->lower_degree_step = std::all_of(index->lower_plans.begin(), index->lower_plans.end(),
                                           [](const DmsTetrahedronPlan& p) { return p.has_last_knot_frames(); });
    for (const std::array<int, 4>& gamma : dms_multi_indices(volume.degree() - 1)) {
      std::array<int, 4> positions{};
      for (int m = 0; m < 4; ++m) {
        std::array<int, 4> beta = gamma;
        ++beta[static_cast<std::size_t>(m)];
        positions[static_cast<std::size_t>(m)] = dms_multi_index_position(beta, volume.degree());
      }
      index->raised.push_back(positions);
    }
    if (!index->lower_degree_step) index->lower_plans.clear();
  }
  // The knots of each cloud that evaluate reads (the DMS step never reads t_{v,n}).
  const int evaluated_per_cloud = index->lower_degree_step ? volume.degree() : per_cloud;
  index->reach.reserve(domain.tetrahedra.size());
  std::vector<Eigen::AlignedBox3d> reach_boxes;
  std::vector<Eigen::AlignedBox3d> support_boxes, tetrahedron_boxes;
  support_boxes.reserve(domain.tetrahedra.size());
  tetrahedron_boxes.reserve(domain.tetrahedra.size());
  index->support_planes.reserve(domain.tetrahedra.size());
  for (const std::array<int, 4>& tet : domain.tetrahedra) {
    std::array<Eigen::Vector3d, 4> corner;
    Eigen::AlignedBox3d tet_box, support_box;
    for (int c = 0; c < 4; ++c) {
      corner[static_cast<std::size_t>(c)] = domain.points[static_cast<std::size_t>(tet[static_cast<std::size_t>(c)])];
      tet_box.extend(corner[static_cast<std::size_t>(c)]);
      const Eigen::Vector3d* cloud = volume.knots().cloud(tet[static_cast<std::size_t>(c)]);
      for (int m = 0; m < per_cloud; ++m) support_box.extend(cloud[m]);
    }
    std::array<Eigen::Vector4d, 4> planes;
    for (int f = 0; f < 4; ++f) {
      // Face opposite corner f; its outward normal points away from corner f.
      const Eigen::Vector3d& a = corner[static_cast<std::size_t>((f + 1) % 4)];
      const Eigen::Vector3d& b = corner[static_cast<std::size_t>((f + 2) % 4)];
      const Eigen::Vector3d& c = corner[static_cast<std::size_t>((f + 3) % 4)];
      Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
      if (normal.dot(corner[static_cast<std::size_t>(f)] - a) > 0) normal = -normal;
      double h = -std::numeric_limits<double>::infinity();
      for (int cc = 0; cc < 4; ++cc) {
        const Eigen::Vector3d* cloud = volume.knots().cloud(tet[static_cast<std::size_t>(cc)]);
        for (int m = 0; m < per_cloud; ++m) h = std::max(h, normal.dot(cloud[m]));
      }
      // A margin of a few ulps of the coordinates keeps rounding of n·x from rejecting a point
      // on the support's boundary.
      const double scale = support_box.max().cwiseAbs().maxCoeff() + support_box.min().cwiseAbs().maxCoeff();
      planes[static_cast<std::size_t>(f)] << normal, h + 16 * std::numeric_limits<double>::epsilon() * scale;
    }
    index->support_planes.push_back(planes);
    std::array<Eigen::Vector4d, 4> inner;
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d normal = planes[static_cast<std::size_t>(f)].head<3>();
      const Eigen::Vector3d& a = corner[static_cast<std::size_t>((f + 1) % 4)];
      const double scale = tet_box.max().cwiseAbs().maxCoeff() + tet_box.min().cwiseAbs().maxCoeff() + tet_box.diagonal().norm();
      inner[static_cast<std::size_t>(f)] << normal, normal.dot(a) - 1e-12 * scale;
    }
    index->domain_planes.push_back(inner);
    std::array<Eigen::Vector4d, 4> outer = inner;
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d& a = corner[static_cast<std::size_t>((f + 1) % 4)];
      outer[static_cast<std::size_t>(f)][3] = outer[static_cast<std::size_t>(f)].head<3>().dot(a) + 1e-10 * tet_box.diagonal().norm();
    }
    index->outer_planes.push_back(outer);
    Index::ReachPlanes reach{};
    Eigen::AlignedBox3d reach_box = tet_box;
    for (int cc = 0; cc < 4; ++cc) {
      const Eigen::Vector3d* cloud = volume.knots().cloud(tet[static_cast<std::size_t>(cc)]);
      for (int m = 0; m < evaluated_per_cloud; ++m) reach_box.extend(cloud[m]);
    }
    // Rounding the normal to float moves n·x by at most 2^-24 Σ|n_i x_i|; the margin covers that
    // many times over for every x in the box.
    const double reach_margin = 1e-6 * (reach_box.max().cwiseAbs().maxCoeff() + reach_box.min().cwiseAbs().maxCoeff() + reach_box.diagonal().norm());
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d normal = planes[static_cast<std::size_t>(f)].head<3>();
      double h = outer[static_cast<std::size_t>(f)][3];
      for (int cc = 0; cc < 4; ++cc) {
        const Eigen::Vector3d* cloud = volume.knots().cloud(tet[static_cast<std::size_t>(cc)]);
        for (int m = 0; m < evaluated_per_cloud; ++m) h = std::max(h, normal.dot(cloud[m]));
      }
      h += reach_margin;
      const auto k = static_cast<std::size_t>(f);
      reach.nx[k] = static_cast<float>(normal.x());
      reach.ny[k] = static_cast<float>(normal.y());
      reach.nz[k] = static_cast<float>(normal.z());
      reach.h[k] = static_cast<float>(h);
      if (static_cast<double>(reach.h[k]) < h) reach.h[k] = std::nextafter(reach.h[k], std::numeric_limits<float>::infinity());
    }
    index->reach.push_back(reach);
    const Eigen::Vector3d reach_widening = Eigen::Vector3d::Constant(2 * reach_margin);
    reach_boxes.emplace_back(reach_box.min() - reach_widening, reach_box.max() + reach_widening);
    support_boxes.push_back(support_box);
    // Widened by locate's margin, so that a point a rounding error outside ∂Ω still finds its tetrahedron.
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(2e-10 * tet_box.diagonal().norm());
    tetrahedron_boxes.emplace_back(tet_box.min() - margin, tet_box.max() + margin);
  }
  if (!index->lower_degree_step) index->full_plans(volume);
  index->parts = tetrahedron_parts(domain);
  index->several_parts = std::any_of(index->parts.begin(), index->parts.end(), [](int p) { return p != 0; });
  index->reach_grid = BoxGrid(reach_boxes);
  index->supports = BoxGrid(support_boxes);
  index->tetrahedra = BoxGrid(tetrahedron_boxes);
  index_ = std::move(index);
}

DmsSplineEvaluator::~DmsSplineEvaluator() = default;

DmsSplineEvaluator::DmsSplineEvaluator(const DmsSplineEvaluator& other)
    : volume_(other.volume_), index_(other.index_), scratch_(std::make_unique<Scratch>(other.volume_->degree())) {}

int DmsSplineEvaluator::locate(const Eigen::Vector3d& x) const { return locate(x, nullptr); }

int DmsSplineEvaluator::locate(const Eigen::Vector3d& x, bool* clearly_inside_out) const {
  return locate_among(x, index_->tetrahedra.query(x), clearly_inside_out);
}

void DmsSplineEvaluator::reaching_tetrahedra(const Eigen::Vector3d& x, std::vector<int>& out) const {
  out.clear();
  for (const int t : index_->reach_grid.query(x)) {
    const Index::ReachPlanes& r = index_->reach[static_cast<std::size_t>(t)];
    int outside = 0;  // counted rather than short-circuited: four independent tests, no branches
    for (std::size_t f = 0; f < 4; ++f) {
      const double d = static_cast<double>(r.nx[f]) * x.x() + static_cast<double>(r.ny[f]) * x.y() + static_cast<double>(r.nz[f]) * x.z();
      outside += d > static_cast<double>(r.h[f]) ? 1 : 0;
    }
    if (outside == 0) out.push_back(t);
  }
}

int DmsSplineEvaluator::locate_among(const Eigen::Vector3d& x, std::span<const int> tetrahedra, bool* clearly_inside_out) const {
  const TetrahedralMesh& domain = volume_->domain();
  // A point inside a tetrahedron by a clear margin lies in no other (the mesh is proper): the
  // floating-point face planes decide it; only points near a face need the exact predicates.
  for (const int t : tetrahedra) {
    const std::array<Eigen::Vector4d, 4>& planes = index_->domain_planes[static_cast<std::size_t>(t)];
    bool clearly_inside = true;
    for (const Eigen::Vector4d& p : planes) clearly_inside = clearly_inside && p.head<3>().dot(x) < p[3];
    if (clearly_inside) {
      if (clearly_inside_out != nullptr) *clearly_inside_out = true;
      return t;
    }
  }
  if (clearly_inside_out != nullptr) *clearly_inside_out = false;
  int found = -1;
  for (const int t : tetrahedra) {
    if (found >= 0 && t > found) continue;
    std::array<Eigen::Vector3d, 4> corner;
    for (int c = 0; c < 4; ++c)
      corner[static_cast<std::size_t>(c)] =
          domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)])];
    if (in_closed_tetrahedron(x, corner)) found = t;
  }
  if (found >= 0) return found;
  for (const int t : tetrahedra) {
    bool near = true;
    for (const Eigen::Vector4d& p : index_->outer_planes[static_cast<std::size_t>(t)]) near = near && p.head<3>().dot(x) <= p[3];
    if (near && (found < 0 || t < found)) found = t;
  }
  return found;
}

void DmsSplineEvaluator::support_candidates(const Eigen::Vector3d& x, std::vector<int>& out) const {
  out.clear();
  for (const int t : index_->supports.query(x)) {
    const std::array<Eigen::Vector4d, 4>& planes = index_->support_planes[static_cast<std::size_t>(t)];
    bool inside = true;
    for (const Eigen::Vector4d& p : planes) inside = inside && p.head<3>().dot(x) <= p[3];
    if (inside) out.push_back(t);
  }
}

void DmsSplineEvaluator::for_each_basis_function(const Eigen::Vector3d& x, const std::function<void(int, double)>& f) {
  const DmsSplineVolume& v = *volume_;
  const int located = locate(x);
  if (located < 0) return;
  if (v.degree() == 0) {
    f(v.control_row(degree_zero_tetrahedron(x, located), 0), 1.0);
    return;
  }
  add_basis_functions(x, located, 1, f);
}

void DmsSplineEvaluator::add_basis_functions(const Eigen::Vector3d& x, int located, double weight, const std::function<void(int, double)>& f) {
  const DmsSplineVolume& v = *volume_;
  const std::vector<DmsTetrahedronPlan>& full_plans = index_->full_plans(v);
  support_candidates(x, scratch_->candidates);
  index_->keep_part(scratch_->candidates, index_->parts[static_cast<std::size_t>(located)]);
  for (const int t : scratch_->candidates) {
    scratch_->basis.evaluate(x, full_plans[static_cast<std::size_t>(t)], 0, scratch_->values);
    for (int b = 0; b < v.basis_per_tetrahedron(); ++b) f(v.control_row(t, b), weight * scratch_->values.values[static_cast<std::size_t>(b)]);
  }
}

void DmsSplineEvaluator::for_each_collocation_weight(const Eigen::Vector3d& x, const std::function<void(int, double)>& f) {
  const DmsSplineVolume& v = *volume_;
  bool clearly_inside = false;
  const int located = locate(x, &clearly_inside);
  if (located < 0) return;
  if (v.degree() == 0) {
    f(v.control_row(degree_zero_tetrahedron(x, located), 0), 1.0);
    return;
  }
  if (index_->lower_degree_step && v.degree() == 1) {
    const int t = degree_zero_tetrahedron(x, located);
    const std::array<double, 4> lambda = linear_step_weights(x, t, nullptr);
    for (int m = 0; m < 4; ++m) {
      std::array<int, 4> beta{};
      beta[static_cast<std::size_t>(m)] = 1;
      f(v.control_row(t, dms_multi_index_position(beta, 1)), lambda[static_cast<std::size_t>(m)]);
    }
    return;
  }
  const auto terms = [&](const Eigen::Vector3d& at, double weight) {
    if (index_->lower_degree_step) {
      // The terms evaluate() sums, by the same DMS step from degree n − 1.
      reaching_tetrahedra(at, scratch_->candidates);
      index_->keep_part(scratch_->candidates, index_->parts[static_cast<std::size_t>(located)]);
      for (const int t : scratch_->candidates) {
        scratch_->lower_basis.evaluate(at, index_->lower_plans[static_cast<std::size_t>(t)], 0, scratch_->values, scratch_->frames);
        for (std::size_t g = 0; g < index_->raised.size(); ++g) {
          const double value = weight * scratch_->values.values[g];
          if (value == 0) continue;
          const std::array<double, 4>& lambda = scratch_->frames.lambdas[g];
          for (std::size_t m = 0; m < 4; ++m) f(v.control_row(t, index_->raised[g][m]), value * lambda[m]);
        }
      }
      return;
    }
    add_basis_functions(at, located, weight, f);
  };
  std::array<std::pair<Eigen::Vector3d, double>, 2> stencil;
  const int points = clearly_inside ? 1 : stencil_of(x, located, stencil);
  if (points == 1) {
    terms(x, 1);
    return;
  }
  for (const auto& [at, weight] : stencil) terms(at, weight);
}

std::array<double, 4> DmsSplineEvaluator::linear_step_weights(const Eigen::Vector3d& x, int t, Eigen::Matrix3d* inverse_out) const {
  const DmsSplineVolume& v = *volume_;
  const std::array<int, 4>& tet = v.domain().tetrahedra[static_cast<std::size_t>(t)];
  const auto corner = [&](int c) -> const Eigen::Vector3d& { return v.domain().points[static_cast<std::size_t>(tet[static_cast<std::size_t>(c)])]; };
  Eigen::Matrix3d edges;
  edges << corner(1) - corner(0), corner(2) - corner(0), corner(3) - corner(0);
  const Eigen::Matrix3d inverse = edges.inverse();  // rows: ∇λ_1..3
  if (inverse_out) *inverse_out = inverse;
  const Eigen::Vector3d l = inverse * (x - corner(0));
  return {1 - l.sum(), l[0], l[1], l[2]};
}

int DmsSplineEvaluator::degree_zero_tetrahedron(const Eigen::Vector3d& x, int located) const {
  // The half-open rule picks one tetrahedron inside Ω; a point of ∂Ω whose perturbation leaves Ω
  // keeps the closed tetrahedron that holds it.
  const TetrahedralMesh& domain = volume_->domain();
  for (const int t : index_->tetrahedra.query(x)) {
    if (index_->parts[static_cast<std::size_t>(t)] != index_->parts[static_cast<std::size_t>(located)]) continue;
    const std::array<int, 4>& tet = domain.tetrahedra[static_cast<std::size_t>(t)];
    if (in_half_open_tetrahedron(x, domain.points[static_cast<std::size_t>(tet[0])], domain.points[static_cast<std::size_t>(tet[1])],
                                 domain.points[static_cast<std::size_t>(tet[2])], domain.points[static_cast<std::size_t>(tet[3])])) {
      return t;
    }
  }
  return located;
}

bool DmsSplineEvaluator::leaves_domain(const Eigen::Vector3d& x, int located) const {
  const TetrahedralMesh& domain = volume_->domain();
  const auto corner = [&](int t, int c) -> const Eigen::Vector3d& {
    return domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)])];
  };
  if (in_half_open_tetrahedron(x, corner(located, 0), corner(located, 1), corner(located, 2), corner(located, 3))) return false;
  for (const int t : index_->tetrahedra.query(x))
    if (index_->parts[static_cast<std::size_t>(t)] == index_->parts[static_cast<std::size_t>(located)] &&
        in_half_open_tetrahedron(x, corner(t, 0), corner(t, 1), corner(t, 2), corner(t, 3)))
      return false;
  return true;
}

void DmsSplineEvaluator::evaluate(const Eigen::Vector3d& x, int order, DmsSplinePoint& out) {
  if (order < 0 || order > 1) throw InvalidInput("expected derivative order 0 or 1, got " + std::to_string(order));
  const DmsSplineVolume& v = *volume_;
  const int dim = v.dimension();
  out.value.setZero(dim);
  if (order >= 1) out.gradient.setZero(dim, 3);
  bool clearly_inside = false;
  // The tetrahedra that reach x, in increasing order: the candidates, and where x lies.
  reaching_tetrahedra(x, scratch_->candidates);
  out.tetrahedron = locate_among(x, scratch_->candidates, &clearly_inside);
  out.inside = out.tetrahedron >= 0;
  if (!out.inside) return;
  const int part = index_->parts[static_cast<std::size_t>(out.tetrahedron)];
  index_->keep_part(scratch_->candidates, part);
  const Eigen::MatrixXd& control = v.control_vectors();
  if (v.degree() == 0) {
    for_each_basis_function(x, [&](int row, double value) { out.value += value * control.row(row).transpose(); });
    return;
  }
  // Values are continuous (n >= 1), but the half-open rule takes them, and derivatives where they
  // jump across knot planes, from the side of the perturbation x + ε(1, ε, ε²). On ∂Ω that side
  // may lie outside Ω, where the basis need not sum to 1 (the tetrahedra outside Ω that would
  // complete it are missing): there the value is the limit from inside (value_stencil), and the
  // derivatives are those at x + d. Degree 1 needs neither (its step lands on the closed
  // tetrahedron that holds x).
  if (index_->lower_degree_step && v.degree() == 1) {
    add_linear_step(x, out.tetrahedron, order, true, out);
    return;
  }
  std::array<std::pair<Eigen::Vector3d, double>, 2> stencil;
  if (!clearly_inside && stencil_of(x, out.tetrahedron, stencil) == 2) {
    DmsSplinePoint far;
    far.value.setZero(dim);
    reaching_tetrahedra(stencil[1].first, scratch_->candidates);
    index_->keep_part(scratch_->candidates, part);
    add_values(stencil[1].first, 0, far);
    reaching_tetrahedra(stencil[0].first, scratch_->candidates);
    index_->keep_part(scratch_->candidates, part);
    add_values(stencil[0].first, order, out);
    out.value = stencil[0].second * out.value + stencil[1].second * far.value;
    return;
  }
  add_values(x, order, out);
}

void DmsSplineEvaluator::add_values(const Eigen::Vector3d& x, int order, DmsSplinePoint& out) {
  const DmsSplineVolume& v = *volume_;
  const int dim = v.dimension();
  const Eigen::MatrixXd& control = v.control_vectors();
  if (index_->lower_degree_step) {
    add_lower_degree_step(x, order, true, out);
    return;
  }
  for (const int t : scratch_->candidates) index_->plans[static_cast<std::size_t>(t)].prefetch();
  for (const int t : scratch_->candidates) {
    scratch_->basis.evaluate(x, index_->plans[static_cast<std::size_t>(t)], order, scratch_->values);
    // Plain loops over the control vector's entries: Eigen's products of a row of a dynamic
    // matrix would evaluate into heap temporaries here, once per basis function.
    const double* control_data = control.data();
    const Eigen::Index stride = control.rows();
    double* value_out = out.value.data();
    for (int b = 0; b < v.basis_per_tetrahedron(); ++b) {
      const double value = scratch_->values.values[static_cast<std::size_t>(b)];
      const Eigen::Vector3d* g = order >= 1 ? &scratch_->values.gradients[static_cast<std::size_t>(b)] : nullptr;
      const bool has_gradient = g != nullptr && (g->x() != 0 || g->y() != 0 || g->z() != 0);
      if (value == 0.0 && !has_gradient) continue;
      const double* c = control_data + v.control_row(t, b);
      for (int k = 0; k < dim; ++k) {
        const double ck = c[k * stride];
        value_out[k] += value * ck;
        if (has_gradient) {
          out.gradient(k, 0) += ck * g->x();
          out.gradient(k, 1) += ck * g->y();
          out.gradient(k, 2) += ck * g->z();
        }
      }
    }
  }
}

int DmsSplineEvaluator::stencil_of(const Eigen::Vector3d& x, int located, std::array<std::pair<Eigen::Vector3d, double>, 2>& out) const {
  out[0] = {x, 1.0};
  const DmsSplineVolume& v = *volume_;
  if (v.degree() == 0 || (index_->lower_degree_step && v.degree() == 1) || !leaves_domain(x, located)) return 1;
  const TetrahedralMesh& domain = v.domain();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c)
    centroid += domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(located)][static_cast<std::size_t>(c)])] / 4;
  const Eigen::Vector3d step = kBoundaryLimitStep * (centroid - x);
  // Both points strictly inside the closed tetrahedron that holds x (toward its centroid); where
  // the step vanishes in rounding (coordinates far larger than the tetrahedron) x stays.
  if (x + step == x || x + 2 * step == x + step) return 1;
  out[0] = {x + step, 2.0};
  out[1] = {x + 2 * step, -1.0};
  return 2;
}

int DmsSplineEvaluator::value_stencil(const Eigen::Vector3d& x, std::array<std::pair<Eigen::Vector3d, double>, 2>& out) const {
  bool clearly_inside = false;
  const int located = locate(x, &clearly_inside);
  if (located < 0) return 0;
  if (clearly_inside) {
    out[0] = {x, 1.0};
    return 1;
  }
  return stencil_of(x, located, out);
}

void DmsSplineEvaluator::add_linear_step(const Eigen::Vector3d& x, int located, int order, bool with_value, DmsSplinePoint& out) const {
  // Degree 1: the step lands on the degree-0 basis, the indicator of the tetrahedron the half-open
  // rule picks, which on ∂Ω (where the lower supports do not reach outside Ω, having no sub-knots)
  // is the closed tetrahedron that holds x. s is the piecewise linear interpolant of the control
  // vectors at the vertices of Ω, whatever the sub-knots t_{v,1}.
  const DmsSplineVolume& v = *volume_;
  const int t = degree_zero_tetrahedron(x, located);
  Eigen::Matrix3d inverse;
  const std::array<double, 4> lambda = linear_step_weights(x, t, &inverse);
  const std::array<Eigen::Vector3d, 4> gradient = {-inverse.colwise().sum().transpose(), inverse.row(0).transpose(),
                                                   inverse.row(1).transpose(), inverse.row(2).transpose()};
  for (int m = 0; m < 4; ++m) {
    std::array<int, 4> beta{};
    beta[static_cast<std::size_t>(m)] = 1;
    const auto c = v.control_vectors().row(v.control_row(t, dms_multi_index_position(beta, 1)));
    if (with_value) out.value += lambda[static_cast<std::size_t>(m)] * c.transpose();
    if (order >= 1) out.gradient += c.transpose() * gradient[static_cast<std::size_t>(m)].transpose();
  }
}

void DmsSplineEvaluator::add_lower_degree_step(const Eigen::Vector3d& x, int order, bool with_value, DmsSplinePoint& out) {
  const DmsSplineVolume& v = *volume_;
  const int dim = v.dimension();
  const double* control_data = v.control_vectors().data();
  const Eigen::Index stride = v.control_vectors().rows();
  double* value_out = out.value.data();
  const std::size_t gammas = index_->raised.size();
  for (const int t : scratch_->candidates) index_->lower_plans[static_cast<std::size_t>(t)].prefetch();
  for (const int t : scratch_->candidates) {
    scratch_->lower_basis.evaluate(x, index_->lower_plans[static_cast<std::size_t>(t)], order, scratch_->values, scratch_->frames);
    for (std::size_t g = 0; g < gammas; ++g) {
      const double value = scratch_->values.values[g];
      const Eigen::Vector3d* gradient = order >= 1 ? &scratch_->values.gradients[g] : nullptr;
      const bool has_gradient = gradient != nullptr && (gradient->x() != 0 || gradient->y() != 0 || gradient->z() != 0);
      if (value == 0.0 && !has_gradient) continue;
      const std::array<double, 4>& lambda = scratch_->frames.lambdas[g];
      const std::array<int, 4>& raised = index_->raised[g];
      const double* c[4];
      for (std::size_t m = 0; m < 4; ++m) c[m] = control_data + v.control_row(t, raised[m]);
      if (order == 0) {
        for (int k = 0; k < dim; ++k) {
          const Eigen::Index at = k * stride;
          value_out[k] += value * (lambda[0] * c[0][at] + lambda[1] * c[1][at] + lambda[2] * c[2][at] + lambda[3] * c[3][at]);
        }
        continue;
      }
      // ∇(N ĉ) = ĉ ∇N + Σ_m c_m N ∇λ_m.
      const std::array<Eigen::Vector3d, 4>& dl = scratch_->frames.gradients[g];
      const Eigen::Vector3d w0 = value * dl[0], w1 = value * dl[1], w2 = value * dl[2], w3 = value * dl[3];
      for (int k = 0; k < dim; ++k) {
        const Eigen::Index at = k * stride;
        const double c0 = c[0][at], c1 = c[1][at], c2 = c[2][at], c3 = c[3][at];
        const double lifted = lambda[0] * c0 + lambda[1] * c1 + lambda[2] * c2 + lambda[3] * c3;
        if (with_value) value_out[k] += value * lifted;
        const Eigen::Vector3d d = c0 * w0 + c1 * w1 + c2 * w2 + c3 * w3 + lifted * *gradient;
        out.gradient(k, 0) += d.x();
        out.gradient(k, 1) += d.y();
        out.gradient(k, 2) += d.z();
      }
    }
  }
}

void DmsSplineEvaluator::evaluate(std::span<const Eigen::Vector3d> points, int order, std::vector<DmsSplinePoint>& out) {
  out.resize(points.size());
  // (cell, position): points outside the grid (-1) first; a stable order within a cell.
  std::vector<std::pair<int, std::size_t>> order_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order_of[i] = {index_->reach_grid.cell_of(points[i]), i};
  std::sort(order_of.begin(), order_of.end());
  for (const std::pair<int, std::size_t>& entry : order_of) evaluate(points[entry.second], order, out[entry.second]);
}

DmsSplinePoint DmsSplineEvaluator::evaluate(const Eigen::Vector3d& x, int order) {
  DmsSplinePoint point;
  evaluate(x, order, point);
  return point;
}

}  // namespace volspline
