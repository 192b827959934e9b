#include "volspline/extract/isoparametric_surfaces.h"
#include "volspline/core/resource_limits.h"

#include <string>

#include "volspline/core/error.h"
#include "volspline/mesh/parts.h"
#include "volspline/core/format.h"
#include "volspline/extract/face_tessellation.h"

namespace volspline {

std::vector<double> isoparametric_values(const KnotVector& knots, int count) {
  if (count < 1) throw InvalidInput("expected at least 1 surface in a family, got " + std::to_string(count));
  const double a = knots.domain_min(), b = knots.domain_max();
  if (count == 1) return {0.5 * (a + b)};
  std::vector<double> values(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) values[static_cast<std::size_t>(i)] = i + 1 == count ? b : a + (b - a) * i / (count - 1);
  return values;
}

TriangleMesh isoparametric_surface(const BSplineVolume& volume, int direction, double value,
                                   const IsoparametricOptions& options) {
  if (volume.dimension() != 3) {
    throw InvalidInput("isoparametric surfaces need control points in R^3, got " + std::to_string(volume.dimension()) +
                           " coordinates per point",
                       "control_points");
  }
  if (direction < 0 || direction > 2) throw InvalidInput("expected a parameter direction 0..2, got " + std::to_string(direction));
  const char* names = "uvw";
  if (!(value >= volume.domain_min(direction) && value <= volume.domain_max(direction))) {
    throw InvalidInput(std::string(1, names[direction]) + " = " + format_double(value) + " lies outside the domain [" +
                       format_double(volume.domain_min(direction)) + ", " + format_double(volume.domain_max(direction)) + "]");
  }
  const int a = (direction + 1) % 3, b = (direction + 2) % 3;
  std::array<std::vector<double>, 3> grid;
  grid[static_cast<std::size_t>(direction)] = {value};
  grid[static_cast<std::size_t>(a)] = face_samples(volume.knot_vector(a), options.resolution);
  grid[static_cast<std::size_t>(b)] = face_samples(volume.knot_vector(b), options.resolution);
  const std::vector<double> points = volume.evaluate_grid(grid, 0);

  TriangleMesh mesh;
  const auto& sa = grid[static_cast<std::size_t>(a)];
  const auto& sb = grid[static_cast<std::size_t>(b)];
  const std::size_t na = sa.size();
  mesh.positions.reserve(na * sb.size());
  mesh.parameters.reserve(na * sb.size());
  // The grid of evaluate_grid runs u fastest; index the (a, b) sample pair through it.
  for (std::size_t j = 0; j < sb.size(); ++j)
    for (std::size_t i = 0; i < na; ++i) {
      std::array<std::size_t, 3> index{};
      index[static_cast<std::size_t>(a)] = i;
      index[static_cast<std::size_t>(b)] = j;
      const std::size_t linear = index[0] + grid[0].size() * (index[1] + grid[1].size() * index[2]);
      Eigen::Vector3d t;
      t[direction] = value;
      t[a] = sa[i];
      t[b] = sb[j];
      mesh.add_vertex(Eigen::Vector3d(points[3 * linear], points[3 * linear + 1], points[3 * linear + 2]), t);
    }
  const Part part = isoparametric_part(direction);
  for (std::size_t j = 0; j + 1 < sb.size(); ++j)
    for (std::size_t i = 0; i + 1 < na; ++i) {
      const int v00 = static_cast<int>(i + na * j), v10 = v00 + 1;
      const int v01 = static_cast<int>(i + na * (j + 1)), v11 = v01 + 1;
      // Counter-clockwise in (a, b): the normal is p_a x p_b, towards increasing `direction`
      // where the map is right-handed.
      mesh.add_triangle(v00, v10, v11, part);
      mesh.add_triangle(v00, v11, v01, part);
    }
  return mesh;
}

TriangleMesh isoparametric_family(const BSplineVolume& volume, int direction, int count,
                                  const IsoparametricOptions& options) {
  if (direction < 0 || direction > 2) throw InvalidInput("expected a parameter direction 0..2, got " + std::to_string(direction));
  if (count >= 1 && options.resolution >= 1) {
    // Each surface is a grid of face_samples in the other two directions: per vertex its position
    // and parameters (48 bytes) and two triangles with their parts (32 bytes), twice while the
    // family is appended to a bigger mesh.
    const auto a = static_cast<std::size_t>((direction + 1) % 3), b = static_cast<std::size_t>((direction + 2) % 3);
    const std::uint64_t vertices = saturating_product({face_samples(volume.knot_vector(static_cast<int>(a)), options.resolution).size(),
                                                       face_samples(volume.knot_vector(static_cast<int>(b)), options.resolution).size()});
    require_memory(saturating_product({static_cast<std::uint64_t>(count), vertices, 160}),
                   std::to_string(count) + " isoparametric surfaces of " + std::to_string(vertices) + " vertices each (--resolution " +
                       std::to_string(options.resolution) + ")");
  }
  TriangleMesh mesh;
  for (double value : isoparametric_values(volume.knot_vector(direction), count))
    mesh.append(isoparametric_surface(volume, direction, value, options));
  return mesh;
}

TriangleMesh isoparametric_surfaces_through(const BSplineVolume& volume, const std::array<double, 3>& t,
                                            const IsoparametricOptions& options) {
  TriangleMesh mesh;
  for (int d = 0; d < 3; ++d) mesh.append(isoparametric_surface(volume, d, t[static_cast<std::size_t>(d)], options));
  return mesh;
}

}  // namespace volspline
