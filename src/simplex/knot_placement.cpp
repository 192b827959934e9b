#include "volspline/simplex/knot_placement.h"

#include <algorithm>
#include <cmath>

#include "volspline/core/error.h"

namespace volspline {

std::vector<double> error_equidistributing_spacing(const DmsSplineVolume& volume, const VolumeData& data,
                                                   const TetrahedronFitErrors& local, const KnotSpacingOptions& options) {
  if (!(options.ratio >= 1 && std::isfinite(options.ratio))) throw InvalidInput("expected a spacing ratio of at least 1", "ratio");
  if (local.point_tetrahedron.size() != data.size())
    throw InvalidInput("expected the tetrahedron errors of these " + std::to_string(data.size()) + " data points", "local");
  const TetrahedralMesh& domain = volume.domain();
  const int n = volume.degree();
  // The spacing each tetrahedron asks for, up to a common factor.
  std::vector<double> wanted(domain.tetrahedra.size(), INFINITY);
  for (std::size_t t = 0; t < domain.tetrahedra.size(); ++t) {
    if (local.points[t] == 0 || !(local.rms[t] > 0)) continue;
    const auto& tet = domain.tetrahedra[t];
    const Eigen::Vector3d& a = domain.points[static_cast<std::size_t>(tet[0])];
    const double volume6 = std::abs((domain.points[static_cast<std::size_t>(tet[1])] - a)
                                        .cross(domain.points[static_cast<std::size_t>(tet[2])] - a)
                                        .dot(domain.points[static_cast<std::size_t>(tet[3])] - a));
    const double h = std::cbrt(volume6);
    if (!(h > 0)) continue;
    const double g = local.rms[t] / std::pow(h, n + 1);
    wanted[t] = std::pow(g, -1.0 / (n + 3));
  }
  std::vector<double> spacing(data.size(), INFINITY);
  std::vector<double> finite;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const int t = local.point_tetrahedron[i];
    if (t >= 0) spacing[i] = wanted[static_cast<std::size_t>(t)];
    if (std::isfinite(spacing[i])) finite.push_back(spacing[i]);
  }
  if (finite.empty()) return std::vector<double>(data.size(), 1.0);
  const auto middle = finite.begin() + static_cast<std::ptrdiff_t>(finite.size() / 2);
  std::nth_element(finite.begin(), middle, finite.end());
  const double median = *middle;
  for (double& s : spacing) s = std::clamp(s / median, 1 / options.ratio, options.ratio);
  return spacing;
}

}  // namespace volspline
