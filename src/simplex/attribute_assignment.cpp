#include "volspline/simplex/attribute_assignment.h"

#include <algorithm>
#include <cmath>

#include "control_fit.h"
#include "volspline/core/error.h"
#include "volspline/simplex/dms_spline_evaluator.h"

namespace volspline {

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
    Eigen::MatrixXd target_matrix(static_cast<Eigen::Index>(samples.size()), 1);
    for (std::size_t i = 0; i < samples.size(); ++i) target_matrix(static_cast<Eigen::Index>(i), 0) = targets[i];
    fit_control_columns(volume, samples, target_matrix, {column}, at_control_points);
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
