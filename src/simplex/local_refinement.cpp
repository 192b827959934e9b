#include "volspline/simplex/local_refinement.h"

#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "control_fit.h"
#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool strictly_inside(const Eigen::Vector3d& x, const std::array<Eigen::Vector3d, 4>& t) {
  const auto P = [](const Eigen::Vector3d& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); };
  return CGAL::orientation(P(x), P(t[1]), P(t[2]), P(t[3])) == CGAL::POSITIVE &&
         CGAL::orientation(P(t[0]), P(x), P(t[2]), P(t[3])) == CGAL::POSITIVE &&
         CGAL::orientation(P(t[0]), P(t[1]), P(x), P(t[3])) == CGAL::POSITIVE &&
         CGAL::orientation(P(t[0]), P(t[1]), P(t[2]), P(x)) == CGAL::POSITIVE;
}

}  // namespace

DmsSplineVolume refine_tetrahedron(const DmsSplineVolume& volume, int tetrahedron, const Eigen::Vector3d& point,
                                   LocalRefinementReport* report) {
  const TetrahedralMesh& old_domain = volume.domain();
  if (tetrahedron < 0 || static_cast<std::size_t>(tetrahedron) >= old_domain.tetrahedra.size())
    throw InvalidInput("expected a tetrahedron from 0 to " + std::to_string(old_domain.tetrahedra.size() - 1) + ", got " +
                       std::to_string(tetrahedron));
  const std::array<int, 4> split = old_domain.tetrahedra[static_cast<std::size_t>(tetrahedron)];
  std::array<Eigen::Vector3d, 4> corner;
  for (int c = 0; c < 4; ++c) corner[static_cast<std::size_t>(c)] = old_domain.points[static_cast<std::size_t>(split[static_cast<std::size_t>(c)])];
  if (!point.allFinite() || !strictly_inside(point, corner))
    throw InvalidInput("expected a point strictly inside tetrahedron " + std::to_string(tetrahedron) + ", got (" + std::to_string(point.x()) +
                           ", " + std::to_string(point.y()) + ", " + std::to_string(point.z()) + ")",
                       "tetrahedra[" + std::to_string(tetrahedron) + "]");
  TetrahedralMesh domain = old_domain;
  const int x = static_cast<int>(domain.points.size());
  domain.points.push_back(point);
  domain.tetrahedra[static_cast<std::size_t>(tetrahedron)] = {x, split[1], split[2], split[3]};
  domain.tetrahedra.push_back({split[0], x, split[2], split[3]});
  domain.tetrahedra.push_back({split[0], split[1], x, split[3]});
  domain.tetrahedra.push_back({split[0], split[1], split[2], x});

  const int n = volume.degree();
  const KnotClouds generated = generate_knot_clouds(domain, n);
  KnotClouds kept = volume.knots();
  for (int l = 0; l <= n; ++l) kept.knots.push_back(generated.cloud(x)[l]);
  bool clouds_kept = true;
  try {
    validate_knot_clouds(domain, kept);
  } catch (const InvalidInput&) {
    clouds_kept = false;
  }
  DmsSplineVolume refined(domain, clouds_kept ? kept : generated, volume.sharing(), volume.attribute_names());

  // The old spline at the samples, and the prior: each new control vector starts from the old
  // spline at its control point's domain point.
  DmsSplineEvaluator old_evaluator(volume);
  const std::vector<Eigen::Vector3d> samples = lattice_samples(refined.domain(), n + 2);
  const int dim = volume.dimension();
  Eigen::MatrixXd targets(static_cast<Eigen::Index>(samples.size()), dim);
  for (std::size_t s = 0; s < samples.size(); ++s) targets.row(static_cast<Eigen::Index>(s)) = old_evaluator.evaluate(samples[s]).value.transpose();
  Eigen::MatrixXd prior(refined.control_vector_count(), dim);
  for (int r = 0; r < refined.control_vector_count(); ++r) {
    const DmsSplinePoint p = old_evaluator.evaluate(refined.domain_point(r));
    if (p.inside) prior.row(r) = p.value.transpose();
    else prior.row(r) = refined.control_vectors().row(r);
  }
  std::vector<int> columns(static_cast<std::size_t>(dim));
  for (int c = 0; c < dim; ++c) columns[static_cast<std::size_t>(c)] = c;
  if (n == 0) {
    refined.control_vectors() = prior;  // degree 0: the value of the old piece (exact)
  } else {
    fit_control_columns(refined, samples, targets, columns, prior);
  }

  if (report != nullptr) {
    report->new_vertex = x;
    report->clouds_kept = clouds_kept;
    report->samples = static_cast<int>(samples.size());
    DmsSplineEvaluator evaluator(refined);
    double squares = 0;
    report->max_error = 0;
    for (std::size_t s = 0; s < samples.size(); ++s) {
      const double e = (evaluator.evaluate(samples[s]).value - targets.row(static_cast<Eigen::Index>(s)).transpose()).norm();
      report->max_error = std::max(report->max_error, e);
      squares += e * e;
    }
    report->rms_error = samples.empty() ? 0 : std::sqrt(squares / static_cast<double>(samples.size()));
  }
  return refined;
}

}  // namespace volspline
