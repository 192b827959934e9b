#include "volspline/extract/trimmed_solid_boundary.h"

#include "volspline/analysis/point_in_image.h"
#include "volspline/core/error.h"
#include "volspline/extract/solid_boundary.h"

namespace volspline {

TrimmedSolidBoundary trimmed_solid_boundary(const std::vector<BSplineVolume>& volumes, const BoundaryOptions& superset,
                                            const ImageContouringOptions& contouring) {
  if (volumes.empty()) throw InvalidInput("expected at least one volume", "volumes");
  TriangleMesh sheets;
  std::vector<int> volume_of_vertex;
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    const SolidBoundary b = solid_boundary(volumes[i], superset);
    sheets.append(b.mesh);
    volume_of_vertex.resize(sheets.num_vertices(), static_cast<int>(i));
  }
  const SplineImage<3> image(volumes);
  const ImageMembershipTest inside = [&](const Eigen::Vector3d& x) -> std::optional<bool> {
    switch (image.classify(x)) {
      case ImageMembership::Inside: return true;
      case ImageMembership::Outside: return false;
      case ImageMembership::Undecided: break;
    }
    return std::nullopt;
  };
  TrimmedBoundary trimmed = contour_image_boundary(sheets, {}, inside, contouring);
  TrimmedSolidBoundary out;
  out.superset_triangles = sheets.num_triangles();
  out.mesh = std::move(trimmed.mesh);
  out.stats = trimmed.stats;
  for (int v : trimmed.source_vertex) out.volumes.push_back(volume_of_vertex[static_cast<std::size_t>(v)]);
  return out;
}

}  // namespace volspline
