#pragma once
// Volume data sets made in code, for fitting tests and measurements (docs/fitting.md).
#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "volspline/io/volume_data.h"

namespace volspline {

/// The Marschner–Lobb test function (Marschner and Lobb 1994) on [−1, 1]³:
/// ρ(x, y, z) = [1 − sin(π z / 2) + α (1 + cos(2π f_M cos(π r / 2)))] / (2 (1 + α)),
/// r = √(x² + y²), f_M = 6, α = 0.25. Values lie in [0, 1].
double marschner_lobb(const Eigen::Vector3d& x);

/// ρ sampled on the n × n × n grid of [−1, 1]³ (both ends included, x fastest), attribute
/// `rho`. \throw InvalidInput for n < 2.
VolumeData marschner_lobb_data(int n);

/// The two-material field of two_material_data at x: 1 + 0.1 (y + z) where x + tilt·y < 0.5,
/// else 2 + 0.1 (y + z).
double two_material(const Eigen::Vector3d& x, double tilt = 0);

/// A solid of two materials with a sharp jump: the n × n × n grid of [0, 1]³, attribute
/// `material` = 1 + 0.1 (y + z) where x + tilt·y < 0.5 and 2 + 0.1 (y + z) elsewhere: a jump
/// of 1 across the plane x + tilt·y = 0.5 on a smooth background.
/// \throw InvalidInput for n < 2.
VolumeData two_material_data(int n, double tilt = 0);

/// Samples f at `points`: one attribute `name`.
VolumeData sampled_volume_data(const std::vector<Eigen::Vector3d>& points, const std::string& name,
                               const std::function<double(const Eigen::Vector3d&)>& f);

/// The data a generated-data name stands for: `marschner-lobb:N` (N in 2..400) or
/// `two-material:N[:TILT]` (N in 2..400, a finite tilt, 0 when absent); nothing for any other
/// name (a file). The command line and Python take these wherever they take data files.
/// \throw InvalidInput (where "DATA") for a name with one of those prefixes that is malformed.
std::optional<VolumeData> generated_volume_data(const std::string& name);

/// The true field of a generated-data name (one value per point), for errors against the truth;
/// an empty function for any other name. \throw InvalidInput as generated_volume_data.
std::function<Eigen::VectorXd(const Eigen::Vector3d&)> generated_volume_truth(const std::string& name);

}  // namespace volspline
