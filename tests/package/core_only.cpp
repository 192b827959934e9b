// Run by .ci/core-only against an installed volspline::core alone (no CGAL, Embree, VTK, stb,
// tinygltf): the tensor-product boundary of an exact ball lies on its sphere and is written as
// PLY, and the formats whose libraries are missing are refused by name. Exit 0 when every check
// holds, 1 otherwise.
#include <cmath>
#include <cstdio>
#include <string>

#include "volspline/construct/primitives.h"
#include "volspline/core/error.h"
#include "volspline/extract/solid_boundary.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"

namespace {

// True when `f` throws InvalidInput whose message names `option`.
template <class F>
bool refused_naming(F f, const std::string& option) {
  try {
    f();
  } catch (const volspline::InvalidInput& e) {
    return std::string(e.what()).find(option) != std::string::npos;
  }
  return false;
}

}  // namespace

int main() {
  const double radius = 1.5;
  const Eigen::Vector3d center(0.5, 0.0, -1.0);
  volspline::BoundaryOptions options;
  options.face_resolution = 6;
  const volspline::TriangleMesh mesh = volspline::solid_boundary(volspline::ball(radius, center), options).mesh;
  // u = 1 is the sphere (the other faces are the ball's degenerate axis and poles, inside it).
  double worst = 0, farthest = 0;
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const double r = (mesh.positions[v] - center).norm();
    farthest = std::max(farthest, r);
    if (mesh.parameters[v][0] == 1.0) worst = std::max(worst, std::abs(r - radius));
  }
  const bool ply = volspline::ply_bytes(mesh).size() > 100;
  const bool png_refused = refused_naming([] { volspline::png_bytes(volspline::Image(4, 4)); }, "VOLSPLINE_WITH_STB");
  const bool glb_refused = refused_naming([&] { volspline::glb_bytes(mesh); }, "VOLSPLINE_WITH_GLTF");
  std::printf("core alone: %zu boundary vertices, sphere distance %.2e, PLY %s, PNG %s, glTF %s\n", mesh.num_vertices(), worst,
              ply ? "written" : "FAILED", png_refused ? "refused" : "NOT REFUSED", glb_refused ? "refused" : "NOT REFUSED");
  return worst < 1e-12 && farthest < radius + 1e-12 && ply && png_refused && glb_refused ? 0 : 1;
}
