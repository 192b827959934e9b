#include "volspline/mesh/surface_tetrahedralization.h"

#include <cmath>
#include <string>
#include <map>
#include <vector>

// Boost.Graph's edge descriptors, copied inside CGAL's feature detection, trip GCC 12's
// -Wmaybe-uninitialized; the warning is about library code, not this file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/make_mesh_3.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/mesh/mesh_checks.h"

namespace volspline {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
// The variant with features: sharp edges (dihedral angle beyond kFeatureAngle) are protected,
// so a box stays a box instead of having its edges rounded off.
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<Kernel, Surface>;
constexpr double kFeatureAngle = 60;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;

// CGAL's default generator, replaced for the duration of a call and restored after (Mesh_3
// draws initial points from it).
class DefaultRandomScope {
 public:
  explicit DefaultRandomScope(unsigned seed) : saved_(CGAL::get_default_random()) { CGAL::get_default_random() = CGAL::Random(seed); }
  ~DefaultRandomScope() { CGAL::get_default_random() = saved_; }
  DefaultRandomScope(const DefaultRandomScope&) = delete;
  DefaultRandomScope& operator=(const DefaultRandomScope&) = delete;

 private:
  CGAL::Random saved_;
};

void check_size(double value, const char* name) {
  if (!(value >= 0) || !std::isfinite(value)) {
    throw InvalidInput(std::string(name) + " " + format_double(value) + " must be finite and >= 0 (0: the default)", name);
  }
}

}  // namespace

TetrahedralMesh tetrahedralize_closed_surface(const TriangleMesh& surface, const SurfaceTetrahedralizationOptions& options) {
  check_size(options.cell_size, "cell_size");
  check_size(options.facet_distance, "facet_distance");
  if (surface.triangles.empty()) throw InvalidInput("the surface has no triangles", "triangles");
  const EdgeStatistics edges = edge_statistics(surface);
  if (!edges.closed()) {
    throw InvalidInput("the surface is not closed: " + std::to_string(edges.boundary_edges) + " edges with one triangle, " +
                           std::to_string(edges.nonmanifold_edges) + " with more than two",
                       "triangles");
  }
  if (!edges.closed_and_oriented()) {
    throw InvalidInput("the surface is not consistently oriented: " + std::to_string(edges.inconsistently_oriented_edges) +
                           " edges are traversed twice in the same direction",
                       "triangles");
  }

  Surface polyhedron;
  std::vector<Surface::Vertex_index> vertex(surface.positions.size());
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    const auto& p = surface.positions[v];
    vertex[v] = polyhedron.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  }
  for (std::size_t f = 0; f < surface.triangles.size(); ++f) {
    const auto& t = surface.triangles[f];
    if (polyhedron.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == Surface::null_face()) {
      throw InvalidInput("CGAL cannot add this triangle to a manifold surface (repeated corner or non-manifold vertex)",
                         "triangles[" + std::to_string(f) + "]");
    }
  }
  const auto [lo, hi] = surface.bounding_box();
  const double diagonal = (hi - lo).norm();
  const double cell_size = options.cell_size > 0 ? options.cell_size : diagonal / 20;
  const double facet_distance = options.facet_distance > 0 ? options.facet_distance : cell_size / 10;

  const DefaultRandomScope random_scope(static_cast<unsigned>(options.seed));
  CGAL::Random domain_random(static_cast<unsigned>(options.seed));
  Domain domain(polyhedron, &domain_random);
  domain.detect_features(kFeatureAngle);
  namespace params = CGAL::parameters;
  const Criteria criteria(params::edge_size = cell_size, params::facet_angle = 25, params::facet_size = cell_size,
                          params::facet_distance = facet_distance, params::cell_radius_edge_ratio = 3,
                          params::cell_size = cell_size);
  // Exudation without a time limit: by default make_mesh_3 stops it after as many seconds as the
  // refinement took (refine_mesh_3.h), so a busy machine got a different mesh.
  const Complex complex = CGAL::make_mesh_3<Complex>(domain, criteria, params::no_perturb(), params::exude(params::time_limit = 0));

  TetrahedralMesh mesh;
  std::map<Triangulation::Vertex_handle, int> index;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end(); ++cell) {
    std::array<int, 4> t;
    for (int k = 0; k < 4; ++k) {
      const auto v = cell->vertex(k);
      const auto [slot, inserted] = index.try_emplace(v, static_cast<int>(mesh.points.size()));
      if (inserted) {
        const auto& p = complex.triangulation().point(v).point();
        mesh.points.emplace_back(p.x(), p.y(), p.z());
      }
      t[k] = slot->second;
    }
    mesh.tetrahedra.push_back(t);
  }
  if (mesh.tetrahedra.empty()) {
    throw InvalidInput("Mesh_3 made no tetrahedra inside the surface (cell size " + format_double(cell_size) +
                           " too coarse, or the surface encloses nothing)",
                       "triangles");
  }
  orient_positively(mesh);
  validate_tetrahedral_mesh(mesh);
  return mesh;
}

}  // namespace volspline
