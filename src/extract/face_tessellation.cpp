#include "volspline/extract/face_tessellation.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>

#include "volspline/core/error.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/parts.h"

namespace volspline {

std::vector<double> face_samples(const KnotVector& knots, int resolution) {
  if (resolution < 1) throw InvalidInput("the resolution must be at least 1");
  const double a = knots.domain_min(), b = knots.domain_max();
  std::vector<double> s = knots.breakpoints();
  for (int i = 1; i < resolution; ++i) s.push_back(a + (b - a) * i / resolution);
  std::sort(s.begin(), s.end());
  // Drop uniform samples that nearly coincide with a breakpoint: slivers help nobody.
  const double eps = 1e-3 * (b - a) / resolution;
  std::vector<double> unique;
  const auto breaks = knots.breakpoints();
  for (double x : s) {
    const bool is_break = std::binary_search(breaks.begin(), breaks.end(), x);
    if (!unique.empty() && x - unique.back() < eps) {
      if (is_break) unique.back() = x;  // keep the breakpoint itself
      continue;
    }
    unique.push_back(x);
  }
  return unique;
}

TriangleMesh tessellate_faces(const BSplineVolume& placed, const FaceTessellationOptions& options) {
  // Tessellated, welded and oriented at the local origin, where positions are as precise as the
  // solid's size allows (far from 0 they are rounded to ulp(|origin|), which would both split
  // coincident vertices and spoil the enclosed volume that decides the orientation); moved back
  // at the end.
  const BSplineVolume volume = placed.translated_to_local_origin();
  if (volume.dimension() != 3) {
    throw InvalidInput("boundary faces need control points in R^3, got " + std::to_string(volume.dimension()) +
                           " coordinates per point",
                       "control_points");
  }
  std::array<std::vector<double>, 3> samples;
  for (int d = 0; d < 3; ++d) samples[static_cast<std::size_t>(d)] = face_samples(volume.knot_vector(d), options.resolution);

  TriangleMesh mesh;
  std::map<std::array<double, 3>, int> vertex_of;  // weld by parameter: faces share edge samples
  for (int face = 0; face < 6; ++face) {
    const int fixed = face / 2;  // direction held constant
    const bool at_max = face % 2 == 1;
    const Part part = face_part(fixed, at_max);
    const int a = (fixed + 1) % 3, b = (fixed + 2) % 3;  // cyclic: (a, b, fixed) is right-handed
    auto grid = samples;
    const double value = at_max ? volume.domain_max(fixed) : volume.domain_min(fixed);
    grid[static_cast<std::size_t>(fixed)] = {value};
    const std::vector<double> points = volume.evaluate_grid(grid, 0);
    const auto& sa = samples[static_cast<std::size_t>(a)];
    const auto& sb = samples[static_cast<std::size_t>(b)];
    std::vector<int> ids(sa.size() * sb.size());
    for (std::size_t j = 0; j < sb.size(); ++j)
      for (std::size_t i = 0; i < sa.size(); ++i) {
        std::array<double, 3> t{};
        t[static_cast<std::size_t>(fixed)] = value;
        t[static_cast<std::size_t>(a)] = sa[i];
        t[static_cast<std::size_t>(b)] = sb[j];
        auto [it, inserted] = vertex_of.try_emplace(t, static_cast<int>(mesh.num_vertices()));
        if (inserted) {
          // grid order is u fastest; locate (t_u, t_v, t_w) in the face grid
          std::array<std::size_t, 3> idx{};
          idx[static_cast<std::size_t>(a)] = i;
          idx[static_cast<std::size_t>(b)] = j;
          const auto& g0 = grid[0];
          const auto& g1 = grid[1];
          const std::size_t linear = idx[0] + g0.size() * (idx[1] + g1.size() * idx[2]);
          mesh.add_vertex(Eigen::Vector3d(points[3 * linear], points[3 * linear + 1], points[3 * linear + 2]),
                          Eigen::Vector3d(t[0], t[1], t[2]));
        }
        ids[i + sa.size() * j] = it->second;
      }
    // (a, b) counter-clockwise has normal p_a x p_b, parallel to +p_fixed for a right-handed
    // map: outward on the max face, inward on the min face.
    for (std::size_t j = 0; j + 1 < sb.size(); ++j)
      for (std::size_t i = 0; i + 1 < sa.size(); ++i) {
        const int v00 = ids[i + sa.size() * j], v10 = ids[i + 1 + sa.size() * j];
        const int v01 = ids[i + sa.size() * (j + 1)], v11 = ids[i + 1 + sa.size() * (j + 1)];
        if (at_max) {
          mesh.add_triangle(v00, v10, v11, part);
          mesh.add_triangle(v00, v11, v01, part);
        } else {
          mesh.add_triangle(v00, v11, v10, part);
          mesh.add_triangle(v00, v01, v11, part);
        }
      }
  }
  if (options.weld_coincident) {
    const auto [lo, hi] = mesh.bounding_box();
    weld_by_position(mesh, 1e-10 * std::max((hi - lo).norm(), 1e-300));
  }
  // A left-handed parameterisation (J < 0, common in real files) turns every face inside out.
  if (enclosed_volume(mesh) < 0.0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  const std::vector<double>& origin = placed.local_origin();
  const Eigen::Vector3d shift(origin[0], origin[1], origin[2]);
  if (!shift.isZero())
    for (Eigen::Vector3d& p : mesh.positions) p += shift;
  return mesh;
}

}  // namespace volspline
