#include "volspline/simplex/attribute_assignment.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {
namespace {

// The points (a_0 p + a_1 q + a_2 r + a_3 s) / m, Σ a = m, of every domain tetrahedron, slightly
// pulled toward its centroid so that no sample lies on a face (where it would be counted by the
// tetrahedra on both sides alike, which is harmless, but pulled samples also never sit on ∂Ω's
// half-open side).
std::vector<Eigen::Vector3d> lattice_samples(const TetrahedralMesh& domain, int m) {
  std::vector<Eigen::Vector3d> samples;
  for (const auto& t : domain.tetrahedra) {
    std::array<Eigen::Vector3d, 4> p;
    for (int c = 0; c < 4; ++c) p[static_cast<std::size_t>(c)] = domain.points[static_cast<std::size_t>(t[static_cast<std::size_t>(c)])];
    const Eigen::Vector3d centroid = (p[0] + p[1] + p[2] + p[3]) / 4;
    for (int a = 0; a <= m; ++a)
      for (int b = 0; a + b <= m; ++b)
        for (int c = 0; a + b + c <= m; ++c) {
          const int d = m - a - b - c;
          const Eigen::Vector3d x = (a * p[0] + b * p[1] + c * p[2] + d * p[3]) / m;
          samples.push_back(x + 1e-3 * (centroid - x));
        }
  }
  return samples;
}

}  // namespace

AttributeAssignmentReport assign_attribute(DmsSplineVolume& volume, const std::string& name,
                                           const std::function<double(const Eigen::Vector3d&)>& f, AttributeAssignment method) {
  const auto& names = volume.attribute_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) volume.add_attribute(name);
  const int column = volume.attribute_column(name);
  Eigen::MatrixXd& control = volume.control_vectors();
  const int rows = volume.control_vector_count();
  // The paper's assignment, also the regularisation's target.
  Eigen::VectorXd at_control_points(rows);
  for (int r = 0; r < rows; ++r) at_control_points[r] = f(control.row(r).head<3>().transpose());
  control.col(column) = at_control_points;

  DmsSplineEvaluator evaluator(volume);
  const std::vector<Eigen::Vector3d> samples = lattice_samples(volume.domain(), volume.degree() + 2);
  std::vector<double> targets(samples.size());
  for (std::size_t s = 0; s < samples.size(); ++s) targets[s] = f(evaluator.evaluate(samples[s]).value.head<3>());

  if (method == AttributeAssignment::LeastSquares) {
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(samples.size()));
    for (std::size_t s = 0; s < samples.size(); ++s) {
      evaluator.for_each_basis_function(samples[s], [&](int row, double value) {
        if (value != 0) entries.emplace_back(static_cast<int>(s), row, value);
      });
      rhs[static_cast<Eigen::Index>(s)] = targets[s];
    }
    Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(samples.size()), rows);
    a.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseMatrix<double> normal = a.transpose() * a;
    const double lambda = 1e-8 * std::max(normal.diagonal().mean(), 1e-300);
    Eigen::SparseMatrix<double> identity(rows, rows);
    identity.setIdentity();
    normal += lambda * identity;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) throw Error("the least-squares system of attribute " + name + " could not be factored");
    const Eigen::VectorXd solution = solver.solve(a.transpose() * rhs + lambda * at_control_points);
    control.col(column) = solution;
  }

  AttributeAssignmentReport report;
  report.samples = static_cast<int>(samples.size());
  double squares = 0;
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const double error = std::abs(evaluator.evaluate(samples[s]).value[column] - targets[s]);
    report.max_error = std::max(report.max_error, error);
    squares += error * error;
  }
  report.rms_error = samples.empty() ? 0 : std::sqrt(squares / static_cast<double>(samples.size()));
  return report;
}

}  // namespace volspline
