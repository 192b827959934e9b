#include "volspline/simplex/dms_spline_evaluator.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <tbb/parallel_for.h>

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
  // The compiled recurrence of every tetrahedron (its basis functions' knot subsets and
  // barycentric frames do not depend on the point).
  std::vector<DmsTetrahedronPlan> plans;
  std::vector<std::array<Eigen::Vector4d, 4>> support_planes;  // n·x <= h as (n, h)
  // The domain tetrahedra's face planes, lowered by a margin that covers the rounding of n·x, so
  // that n·x < h proves x inside.
  std::vector<std::array<Eigen::Vector4d, 4>> domain_planes;
  // The same planes raised by 1e-10 of the tetrahedron's size: a point computed on ∂Ω (a lattice
  // point, an edge midpoint) may land a rounding error outside; within this margin it is inside.
  std::vector<std::array<Eigen::Vector4d, 4>> outer_planes;
  BoxGrid supports;
  BoxGrid tetrahedra;
};

struct DmsSplineEvaluator::Scratch {
  explicit Scratch(int degree) : basis(degree) {}
  DmsTetrahedronBasis basis;
  DmsBasisValues values;
  std::vector<int> candidates;
};

DmsSplineEvaluator::DmsSplineEvaluator(const DmsSplineVolume& volume)
    : volume_(&volume), scratch_(std::make_unique<Scratch>(volume.degree())) {
  auto index = std::make_shared<Index>();
  const TetrahedralMesh& domain = volume.domain();
  const int per_cloud = volume.degree() + 1;
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
    support_boxes.push_back(support_box);
    // Widened by locate's margin, so that a point a rounding error outside ∂Ω still finds its tetrahedron.
    const Eigen::Vector3d margin = Eigen::Vector3d::Constant(2e-10 * tet_box.diagonal().norm());
    tetrahedron_boxes.emplace_back(tet_box.min() - margin, tet_box.max() + margin);
  }
  index->plans.resize(domain.tetrahedra.size());
  tbb::parallel_for(std::size_t{0}, domain.tetrahedra.size(), [&](std::size_t t) {
    const std::array<int, 4>& tet = domain.tetrahedra[t];
    index->plans[t] = DmsTetrahedronPlan(volume.degree(), {volume.knots().cloud(tet[0]), volume.knots().cloud(tet[1]),
                                                           volume.knots().cloud(tet[2]), volume.knots().cloud(tet[3])});
  });
  index->supports = BoxGrid(support_boxes);
  index->tetrahedra = BoxGrid(tetrahedron_boxes);
  index_ = std::move(index);
}

DmsSplineEvaluator::~DmsSplineEvaluator() = default;

DmsSplineEvaluator::DmsSplineEvaluator(const DmsSplineEvaluator& other)
    : volume_(other.volume_), index_(other.index_), scratch_(std::make_unique<Scratch>(other.volume_->degree())) {}

int DmsSplineEvaluator::locate(const Eigen::Vector3d& x) const { return locate(x, nullptr); }

int DmsSplineEvaluator::locate(const Eigen::Vector3d& x, bool* clearly_inside_out) const {
  const TetrahedralMesh& domain = volume_->domain();
  // A point inside a tetrahedron by a clear margin lies in no other (the mesh is proper): the
  // floating-point face planes decide it; only points near a face need the exact predicates.
  for (const int t : index_->tetrahedra.query(x)) {
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
  for (const int t : index_->tetrahedra.query(x)) {
    if (found >= 0 && t > found) continue;
    std::array<Eigen::Vector3d, 4> corner;
    for (int c = 0; c < 4; ++c)
      corner[static_cast<std::size_t>(c)] =
          domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)])];
    if (in_closed_tetrahedron(x, corner)) found = t;
  }
  if (found >= 0) return found;
  for (const int t : index_->tetrahedra.query(x)) {
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
  const TetrahedralMesh& domain = v.domain();
  if (v.degree() == 0) {
    // The half-open rule picks one tetrahedron inside Ω; a point of ∂Ω whose perturbation
    // leaves Ω keeps the closed tetrahedron that holds it.
    int chosen = located;
    for (const int t : index_->tetrahedra.query(x)) {
      const std::array<int, 4>& tet = domain.tetrahedra[static_cast<std::size_t>(t)];
      if (in_half_open_tetrahedron(x, domain.points[static_cast<std::size_t>(tet[0])], domain.points[static_cast<std::size_t>(tet[1])],
                                   domain.points[static_cast<std::size_t>(tet[2])], domain.points[static_cast<std::size_t>(tet[3])])) {
        chosen = t;
        break;
      }
    }
    f(v.control_row(chosen, 0), 1.0);
    return;
  }
  support_candidates(x, scratch_->candidates);
  for (const int t : scratch_->candidates) {
    scratch_->basis.evaluate(x, index_->plans[static_cast<std::size_t>(t)], 0, scratch_->values);
    for (int b = 0; b < v.basis_per_tetrahedron(); ++b) f(v.control_row(t, b), scratch_->values.values[static_cast<std::size_t>(b)]);
  }
}

bool DmsSplineEvaluator::leaves_domain(const Eigen::Vector3d& x, int located) const {
  const TetrahedralMesh& domain = volume_->domain();
  const auto corner = [&](int t, int c) -> const Eigen::Vector3d& {
    return domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)])];
  };
  if (in_half_open_tetrahedron(x, corner(located, 0), corner(located, 1), corner(located, 2), corner(located, 3))) return false;
  for (const int t : index_->tetrahedra.query(x))
    if (in_half_open_tetrahedron(x, corner(t, 0), corner(t, 1), corner(t, 2), corner(t, 3))) return false;
  return true;
}

void DmsSplineEvaluator::evaluate(const Eigen::Vector3d& x, int order, DmsSplinePoint& out) {
  if (order < 0 || order > 1) throw InvalidInput("expected derivative order 0 or 1, got " + std::to_string(order));
  const DmsSplineVolume& v = *volume_;
  const int dim = v.dimension();
  out.value.setZero(dim);
  if (order >= 1) out.gradient.setZero(dim, 3);
  bool clearly_inside = false;
  out.tetrahedron = locate(x, &clearly_inside);
  out.inside = out.tetrahedron >= 0;
  if (!out.inside) return;
  const Eigen::MatrixXd& control = v.control_vectors();
  if (v.degree() == 0) {
    for_each_basis_function(x, [&](int row, double value) { out.value += value * control.row(row).transpose(); });
    return;
  }
  const TetrahedralMesh& domain = v.domain();
  // Values are continuous (n >= 1), but derivatives may jump across knot planes, and the half-open
  // rule takes them from the side of the perturbation x + ε(1, ε, ε²). On ∂Ω that side may lie
  // outside Ω, where the basis no longer sums to 1; there the derivatives come from a point
  // 1e-9 of the tetrahedron's size inside, on the domain's side of every nearby knot plane.
  Eigen::Vector3d derivative_point = x;
  const bool near_face = !clearly_inside;
  if (order >= 1 && near_face && leaves_domain(x, out.tetrahedron)) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c)
      centroid += domain.points[static_cast<std::size_t>(domain.tetrahedra[static_cast<std::size_t>(out.tetrahedron)][static_cast<std::size_t>(c)])];
    derivative_point = x + 1e-9 * (centroid / 4 - x);
  }
  for (int pass = 0; pass < (derivative_point == x ? 1 : 2); ++pass) {
    const Eigen::Vector3d& at = pass == 0 ? x : derivative_point;
    const int pass_order = derivative_point == x ? order : (pass == 0 ? 0 : 1);
    support_candidates(at, scratch_->candidates);
    for (const int t : scratch_->candidates) index_->plans[static_cast<std::size_t>(t)].prefetch();
    for (const int t : scratch_->candidates) {
      scratch_->basis.evaluate(at, index_->plans[static_cast<std::size_t>(t)], pass_order, scratch_->values);
      // Plain loops over the control vector's entries: Eigen's products of a row of a dynamic
      // matrix would evaluate into heap temporaries here, once per basis function.
      const double* control_data = control.data();
      const Eigen::Index stride = control.rows();
      double* value_out = out.value.data();
      for (int b = 0; b < v.basis_per_tetrahedron(); ++b) {
        const double value = pass == 0 ? scratch_->values.values[static_cast<std::size_t>(b)] : 0.0;
        const Eigen::Vector3d* g = pass_order >= 1 ? &scratch_->values.gradients[static_cast<std::size_t>(b)] : nullptr;
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
}

DmsSplinePoint DmsSplineEvaluator::evaluate(const Eigen::Vector3d& x, int order) {
  DmsSplinePoint point;
  evaluate(x, order, point);
  return point;
}

}  // namespace volspline
