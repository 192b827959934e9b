#include "volspline/extract/trimmed_solid_boundary.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>

#include "volspline/analysis/point_in_image.h"
#include "volspline/core/error.h"
#include "volspline/extract/image_membership.h"
#include "volspline/extract/sheet_line_crossing.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/mesh/parts.h"

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
  const ImageMembershipTest inside = image_membership_test(image);
  // Vertices onto the true sheets (extract/sheet_line_crossing.h), as for swept solids: a face
  // (part UMin ... WMax: one parameter fixed at a domain bound) or J = 0 (a fold, all three
  // free), by Newton from the (u, v, w) interpolated in the superset triangle.
  auto face_or_fold = [&](std::size_t triangle) -> std::optional<SupersetSheet> {
    const int part = sheets.parts[triangle];
    if (part == part_number(Part::JacobianZero)) return SupersetSheet{0, true};
    if (part >= part_number(Part::UMin) && part <= part_number(Part::WMax)) return SupersetSheet{static_cast<std::uint8_t>(1 << (part / 2)), false};
    return std::nullopt;
  };
  const SupersetSheetCrossing exact = [&](std::size_t triangle, const Eigen::Vector3d& barycentric, double lambda,
                                          const Eigen::Vector3d& a, const Eigen::Vector3d& b) -> std::optional<SheetCrossing> {
    const std::optional<SupersetSheet> sheet = face_or_fold(triangle);
    if (!sheet) return std::nullopt;
    const auto& tri = sheets.triangles[triangle];
    const auto v0 = static_cast<std::size_t>(tri[0]);
    const BSplineVolume& volume = volumes[static_cast<std::size_t>(volume_of_vertex[v0])];
    std::array<double, 3> p{};
    for (int d = 0; d < 3; ++d) {
      const auto du = static_cast<std::size_t>(d);
      if ((sheet->fixed >> d) & 1) {
        // Exactly at the bound the face lies on.
        const int part = sheets.parts[triangle];
        p[du] = part % 2 == 0 ? volume.domain_min(d) : volume.domain_max(d);
      } else {
        for (int j = 0; j < 3; ++j) p[du] += barycentric[j] * sheets.parameters[static_cast<std::size_t>(tri[static_cast<std::size_t>(j)])][d];
      }
    }
    const auto c = sheet_line_crossing<3>(volume, *sheet, p, lambda, a, b);
    if (!c) return std::nullopt;
    SheetCrossing x;
    x.lambda = c->lambda;
    x.parameters = Eigen::Vector3d(c->parameter[0], c->parameter[1], c->parameter[2]);
    x.normal = c->normal;
    return x;
  };
  // One number per sheet: the volume and the part (each face and J = 0 of each volume).
  std::vector<int> sheet_of_triangle(sheets.num_triangles());
  for (std::size_t t = 0; t < sheets.num_triangles(); ++t)
    sheet_of_triangle[t] = volume_of_vertex[static_cast<std::size_t>(sheets.triangles[t][0])] * 64 + sheets.parts[t];
  TrimmedBoundary trimmed = contour_image_boundary(sheets, {}, inside, contouring, exact, sheet_of_triangle);
  TrimmedSolidBoundary out;
  out.superset_triangles = sheets.num_triangles();
  out.mesh = std::move(trimmed.mesh);
  out.stats = trimmed.stats;
  for (int v : trimmed.source_vertex) out.volumes.push_back(volume_of_vertex[static_cast<std::size_t>(v)]);
  // Tags within the superset's error of their vertices (docs/envelopes.md, "Vertex tags").
  std::vector<std::array<double, 3>> tags(out.mesh.num_vertices());
  for (std::size_t v = 0; v < tags.size(); ++v) tags[v] = {out.mesh.parameters[v][0], out.mesh.parameters[v][1], out.mesh.parameters[v][2]};
  const auto [low, high] = sheets.bounding_box();
  correct_vertex_tags<3>(image, out.mesh, tags, out.volumes, std::max(contouring.superset_error, 1e-6) * (high - low).norm(), out.stats);
  for (std::size_t v = 0; v < tags.size(); ++v) out.mesh.parameters[v] = Eigen::Vector3d(tags[v][0], tags[v][1], tags[v][2]);
  return out;
}

}  // namespace volspline
