// volspline make simplex-spline (--tetrahedra MESH | --points POINTS | --surface SURFACE) --degree N
//   [--control shared|per_tetrahedron] [--spread S] [--cell-size H]
//   [--skeleton SKELETON.json [--attribute NAME] [--assign least-squares|control-points]] -o OUT.json
// A trivariate DMS simplex spline volume (Hua–He–Qin §3.2) over a tetrahedral domain with
// generated knot clouds, identity geometry, and optionally an attribute from a skeleton (§4.3).
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/model_file.h"
#include "volspline/io/point_file.h"
#include "volspline/io/skeleton_file.h"
#include "volspline/mesh/delaunay_tetrahedralization.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/surface_tetrahedralization.h"
#include "volspline/mesh/tetrahedral_mesh_reader.h"
#include "volspline/simplex/attribute_assignment.h"
#include "volspline/simplex/knot_clouds.h"

namespace volspline::cli {

namespace {

struct SimplexSplineRequest {
  std::string tetrahedra, points, surface, control = "shared", skeleton, attribute = "density", assign = "least-squares", out;
  int degree = 2;
  double spread = KnotCloudOptions{}.spread;
  double cell_size = 0;
};

TetrahedralMesh domain_of(const SimplexSplineRequest& r) {
  const int given = !r.tetrahedra.empty() + !r.points.empty() + !r.surface.empty();
  if (given != 1) throw InvalidInput("give exactly one of --tetrahedra, --points and --surface (the domain)", "make simplex-spline");
  if (!r.tetrahedra.empty()) return read_tetrahedral_mesh(r.tetrahedra);
  if (!r.points.empty()) {
    const std::vector<Eigen::Vector3d> points = read_points(r.points);
    try {
      return delaunay_tetrahedralization(points);
    } catch (const InvalidInput& e) {
      throw e.located("--points " + r.points);
    }
  }
  SurfaceTetrahedralizationOptions options;
  options.cell_size = r.cell_size;
  try {
    return tetrahedralize_closed_surface(read_mesh(r.surface), options);
  } catch (const InvalidInput& e) {
    throw e.located("--surface " + r.surface);
  }
}

void make_simplex_spline_file(const SimplexSplineRequest& r) {
  if (r.control != "shared" && r.control != "per_tetrahedron")
    throw InvalidInput("expected shared or per_tetrahedron, got '" + r.control + "'", "--control");
  if (r.assign != "least-squares" && r.assign != "control-points")
    throw InvalidInput("expected least-squares or control-points, got '" + r.assign + "'", "--assign");
  if (r.skeleton.empty() && r.attribute != "density") throw InvalidInput("--attribute names the attribute a --skeleton sets", "--attribute");
  TetrahedralMesh domain = domain_of(r);
  KnotCloudOptions cloud_options;
  cloud_options.spread = r.spread;
  KnotClouds clouds = [&] {
    try {
      return generate_knot_clouds(domain, r.degree, cloud_options);
    } catch (const InvalidInput& e) {
      if (e.where().rfind("tetrahedra", 0) == 0) throw e.located("the domain");
      throw InvalidInput(e.message(), e.where().empty() ? "--degree" : e.where());
    }
  }();
  const std::size_t points = domain.points.size(), tetrahedra = domain.tetrahedra.size();
  DmsSplineVolume volume(std::move(domain), std::move(clouds), r.control == "shared" ? DmsControlSharing::Shared : DmsControlSharing::PerTetrahedron);
  std::string assigned;
  if (!r.skeleton.empty()) {
    const SkeletonField field = read_skeleton(r.skeleton);
    const AttributeAssignmentReport report =
        assign_attribute(volume, r.attribute, [&](const Eigen::Vector3d& x) { return field(x); },
                         r.assign == "least-squares" ? AttributeAssignment::LeastSquares : AttributeAssignment::ControlPoints);
    assigned = "; attribute " + r.attribute + " from " + r.skeleton + " (" + r.assign + "): max error " + format_double(report.max_error) +
               ", rms " + format_double(report.rms_error) + " over " + std::to_string(report.samples) + " samples";
  }
  Model model;
  const int controls = volume.control_vector_count();
  model.objects.push_back({"simplex spline volume", false, std::move(volume), nullptr});
  write_model(model, r.out);
  std::cout << "wrote " << r.out << ": degree " << r.degree << " simplex spline volume over " << tetrahedra << " tetrahedra on "
            << points << " points, " << controls << " control points (" << r.control << ")" << assigned << "\n";
}

}  // namespace

void add_make_simplex_spline_kind(CLI::App* make) {
  auto r = std::make_shared<SimplexSplineRequest>();
  auto* cmd = make->add_subcommand("simplex-spline", "A trivariate DMS simplex spline volume over a tetrahedral domain (Hua-He-Qin): "
                                                     "knot clouds generated, geometry the identity, attributes from a skeleton");
  cmd->add_option("--tetrahedra", r->tetrahedra, "the domain: a tetrahedral mesh (.mesh medit, .node/.ele TetGen, .vtu, .vtk)");
  cmd->add_option("--points", r->points, "the domain: the Delaunay tetrahedralisation of the points of this file (x, y, z per line)");
  cmd->add_option("--surface", r->surface, "the domain: the inside of this closed triangle mesh (.off, .obj, .ply, .stl), meshed by CGAL Mesh_3");
  cmd->add_option("--cell-size", r->cell_size, "with --surface: the largest tetrahedron size (default: bounding-box diagonal / 20)");
  cmd->add_option("--degree", r->degree, "the degree n, 0 to 5 (default 2)");
  cmd->add_option("--control", r->control, "shared (one control point per domain point, default) or per_tetrahedron");
  cmd->add_option("--spread", r->spread, "sub-knot distance as a fraction of each vertex's shortest edge (default 0.15)");
  cmd->add_option("--skeleton", r->skeleton, "a skeleton file (docs/skeleton-files.md) whose field sets an attribute");
  cmd->add_option("--attribute", r->attribute, "the attribute the skeleton sets (default density)");
  cmd->add_option("--assign", r->assign, "least-squares (default) or control-points (the paper's: the field at each control point)");
  cmd->add_option("-o,--output", r->out, "output model file (.json)")->required();
  cmd->callback([r] { make_simplex_spline_file(*r); });
}

}  // namespace volspline::cli
