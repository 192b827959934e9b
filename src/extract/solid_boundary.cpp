#include "volspline/extract/solid_boundary.h"

#include <chrono>
#include <utility>

#include "volspline/core/progress.h"
#include "volspline/extract/face_tessellation.h"

namespace volspline {

SolidBoundary solid_boundary(const BSplineVolume& volume, const BoundaryOptions& options) {
  using Clock = std::chrono::steady_clock;
  const auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  const auto start = Clock::now();
  SolidBoundary out = jacobian_zero_surface(volume, options);
  auto t = Clock::now();
  const ProgressPhase phase(options.progress, "faces");
  FaceTessellationOptions face_options;
  face_options.resolution = options.face_resolution;
  TriangleMesh faces = tessellate_faces(volume, face_options);
  for (int part : faces.parts) ++out.stats.triangles[static_cast<std::size_t>(part)];
  faces.append(out.mesh);
  out.mesh = std::move(faces);
  out.stats.seconds_faces = since(t);
  out.stats.seconds_total = since(start);
  return out;
}

}  // namespace volspline
