#pragma once
// What a user would fit instead of a DMS simplex spline (issue 14, docs/fitting.md "Baselines"):
// a tensor-product B-spline least-squares fit over the data's box with about the same number of
// coefficients, and, where the data is a regular grid, trilinear and nearest-neighbour
// interpolation. compare_volume_fits measures all of them and the simplex spline side by side,
// at the data points and, where the true function is known (generated data), against it at
// random points — the only fair measure for interpolants, which reproduce the data exactly.
//
// This is a pipeline: it joins io/ (the data), spline/ (the tensor-product kernel) and simplex/
// (the simplex spline and its least-squares solver).
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "volspline/io/volume_data.h"
#include "volspline/simplex/dms_spline_volume.h"
#include "volspline/spline/tensor_spline.h"

namespace volspline {

/// The attributes of volume data as one tensor-product B-spline function over the data's
/// bounding box: `volume` is the box (control points at the Greville abscissae, so the map is
/// the identity and a parameter is a point), `coefficients` holds one column per attribute, one
/// row per control point (first index fastest), minimising Σ_i |f(x_i) − d_i|² plus the same
/// small Tikhonov term as the simplex fit (a coefficient no data point sees stays near 0).
struct TensorProductFit {
  BSplineVolume volume;
  std::vector<std::string> attribute_names;
  Eigen::MatrixXd coefficients;

  /// The fitted attributes at a point of the box (clamped into it), one per attribute.
  Eigen::VectorXd operator()(const Eigen::Vector3d& x) const;
  std::size_t coefficient_count() const { return static_cast<std::size_t>(coefficients.rows()); }
};

/// A least-squares tensor-product fit of `degree` (1..5) with about `coefficients` control
/// points (per attribute), spans per direction proportional to the box's sides (at least 1).
/// \throw InvalidInput for bad data (validate_volume_data), no attributes, a flat box, a degree
/// outside 1..5 or fewer than 8 coefficients; Error if the system cannot be solved.
TensorProductFit fit_tensor_product_volume(const VolumeData& data, int degree, std::size_t coefficients);

/// Data on a regular grid: the distinct x, y and z coordinates, every combination present once,
/// and the attribute values at the grid nodes.
struct RegularGridData {
  std::array<std::vector<double>, 3> axes;
  std::vector<std::string> attribute_names;
  /// axes[0].size() * axes[1].size() * axes[2].size() rows (x fastest), one column per attribute.
  Eigen::MatrixXd values;

  /// Trilinear interpolation of the node values at x (clamped into the grid's box).
  Eigen::VectorXd trilinear(const Eigen::Vector3d& x) const;
  /// The value of the nearest node (ties toward the lower node).
  Eigen::VectorXd nearest(const Eigen::Vector3d& x) const;
};

/// The grid the data's points form, if they form one (at least 2 coordinates per axis, each
/// combination exactly once, each axis strictly increasing); nullopt for scattered data.
std::optional<RegularGridData> regular_grid_of(const VolumeData& data);

/// The errors of one method for one attribute, raw and divided by the data's range (data mapped
/// to [0, 1]).
struct MethodError {
  std::string method;
  std::string attribute;
  /// Coefficients the method stores for this attribute (data values for the interpolants).
  std::size_t coefficients = 0;
  /// At the data points inside the simplex spline's domain (every method at the same ones), and
  /// how many those are.
  double data_mean_square = 0, data_max_abs = 0;
  std::size_t data_points = 0;
  double normalised_data_mean_square = 0, normalised_data_max_abs = 0;
  /// Against the true function at the comparison points (NaN without one).
  double truth_mean_square = 0, truth_max_abs = 0;
  double normalised_truth_mean_square = 0, normalised_truth_max_abs = 0;
  double seconds = 0;
};

struct FitComparisonOptions {
  /// The true attributes at a point, one per attribute of the data, when known.
  std::function<Eigen::VectorXd(const Eigen::Vector3d&)> truth;
  /// Comparison points against the truth: uniformly random in the data's box (a fixed seed),
  /// keeping those inside the simplex spline's domain so that every method is measured on the
  /// same points.
  std::size_t truth_points = 20000;
  /// The tensor-product fit's degree; 0: the simplex spline's.
  int tensor_product_degree = 0;
};

/// The simplex spline `volume` (fitted to `data`) and the baselines, fitted to the same data now:
/// "dms simplex spline", "tensor-product least squares" (as many coefficients as the simplex
/// spline has control points), and for grid data "trilinear" and "nearest". One entry per method
/// and attribute, in that order. Errors at the data are taken at the data points inside the
/// simplex spline's domain for every method alike (the tensor product too).
/// \throw InvalidInput for data whose attributes the volume lacks; as fit_tensor_product_volume.
std::vector<MethodError> compare_volume_fits(const VolumeData& data, const DmsSplineVolume& volume,
                                             const FitComparisonOptions& options = {});

}  // namespace volspline
