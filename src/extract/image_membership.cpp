#include "volspline/extract/image_membership.h"

#include <algorithm>
#include <string>

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include "volspline/analysis/point_in_image.h"
#include "volspline/core/error.h"

namespace volspline {

template <int D>
ImageMembershipTest image_membership_test(const SplineImage<D>& image) {
  return [&image](const Eigen::Vector3d& x) -> std::optional<bool> {
    // The last preimage this thread found, and of which image (a test of another image, or an
    // image made later at the same address, must not use it: the search runs then).
    struct Hint {
      const SplineImage<D>* image = nullptr;
      std::uint64_t generation = 0;
      typename SplineImage<D>::Preimage preimage;
    };
    thread_local Hint hint;
    const typename SplineImage<D>::Query q =
        hint.image == &image && hint.generation == image.generation() ? image.query(x, hint.preimage) : image.query(x);
    if (q.preimage) hint = {&image, image.generation(), *q.preimage};
    switch (q.membership) {
      case ImageMembership::Inside: return true;
      case ImageMembership::Outside: return false;
      case ImageMembership::Undecided: break;
    }
    return std::nullopt;
  };
}

// The issue asks for every vertex tagged with its (u, v, w, t); vertices that came from Newton on
// a sheet have exact tags, others interpolated ones, which can lie on another part of the
// surface (0.2 of the diagonal off on the annulus's rims before this).
template <int D>
void correct_vertex_tags(const SplineImage<D>& image, const TriangleMesh& mesh, std::vector<std::array<double, D>>& parameters,
                         std::vector<int>& patches, double distance, SupersetTrimmingStats& stats) {
  const std::size_t n = mesh.num_vertices();
  if (parameters.size() != n || patches.size() != n)
    throw InvalidInput("expected one tag per vertex (" + std::to_string(n) + "), got " + std::to_string(parameters.size()) + " and " +
                           std::to_string(patches.size()),
                       "parameters");
  for (int p : patches)
    if (p < 0 || static_cast<std::size_t>(p) >= image.patches().size())
      throw InvalidInput("patch " + std::to_string(p) + " does not exist", "patches");
  std::vector<Eigen::Vector3d> normal(n, Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d area = (mesh.positions[static_cast<std::size_t>(t[1])] - a).cross(mesh.positions[static_cast<std::size_t>(t[2])] - a);
    for (int v : t) normal[static_cast<std::size_t>(v)] += area;
  }
  using Preimage = typename SplineImage<D>::Preimage;
  std::vector<char> corrected(n, 0), beyond(n, 0);
  std::vector<double> off(n, 0);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t v) {
    const Eigen::Vector3d& x = mesh.positions[v];
    auto offset = [&](const Preimage& p) {
      const Eigen::VectorXd y = image.patches()[p.patch].evaluate(p.parameter);
      return (Eigen::Vector3d(y[0], y[1], y[2]) - x).norm();
    };
    // Interpolated tags can lie a rounding outside the domain (barycentric sums of a bound).
    Preimage tag{static_cast<std::size_t>(patches[v]), parameters[v]};
    const auto& patch = image.patches()[tag.patch];
    for (int d = 0; d < D; ++d)
      tag.parameter[static_cast<std::size_t>(d)] = std::clamp(tag.parameter[static_cast<std::size_t>(d)], patch.domain_min(d), patch.domain_max(d));
    parameters[v] = tag.parameter;
    off[v] = offset(tag);
    if (off[v] <= distance) return;
    std::optional<Preimage> found = image.preimage_near(x, tag, distance);
    if (!found) found = image.query(x).preimage;
    const double length = normal[v].norm();
    for (const double step : {2.0, 8.0})
      if (!found && length > 0)
        if (const auto inner = image.query(x - step * distance / length * normal[v]).preimage) found = image.preimage_near(x, *inner, distance);
    if (!found) {
      beyond[v] = 1;
      return;
    }
    corrected[v] = 1;
    off[v] = offset(*found);
    patches[v] = static_cast<int>(found->patch);
    parameters[v] = found->parameter;
  });
  stats.tags_corrected = std::count(corrected.begin(), corrected.end(), 1);
  stats.tags_beyond_tolerance = std::count(beyond.begin(), beyond.end(), 1);
  stats.largest_tag_distance = n ? *std::max_element(off.begin(), off.end()) : 0.0;
}

template void correct_vertex_tags<3>(const SplineImage<3>&, const TriangleMesh&, std::vector<std::array<double, 3>>&, std::vector<int>&,
                                     double, SupersetTrimmingStats&);
template void correct_vertex_tags<4>(const SplineImage<4>&, const TriangleMesh&, std::vector<std::array<double, 4>>&, std::vector<int>&,
                                     double, SupersetTrimmingStats&);

template ImageMembershipTest image_membership_test<3>(const SplineImage<3>&);
template ImageMembershipTest image_membership_test<4>(const SplineImage<4>&);

}  // namespace volspline
