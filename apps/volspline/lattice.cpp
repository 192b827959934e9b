// volspline lattice IN.(obj|ply|stl) --degree P,Q,R [--divisions A,B,C] [--margin M]
//                  [--axes Ux,Uy,Uz,Vx,Vy,Vz,Wx,Wy,Wz] -o LATTICE.json
#include <iostream>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/deform/lattice.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_reader.h"

namespace volspline::cli {

void add_lattice_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("lattice", "Make the undeformed free-form deformation lattice around a mesh (identity map)");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto degree = std::make_shared<std::string>();
  auto divisions = std::make_shared<std::string>("1,1,1");
  auto margin = std::make_shared<double>(0.05);
  auto axes = std::make_shared<std::string>();
  cmd->add_option("MESH", *in, "mesh file: .obj, .ply or .stl")->required();
  cmd->add_option("-o,--output", *out, "lattice model file (.json)")->required();
  cmd->add_option("--degree", *degree, "degrees P,Q,R of the lattice volume")->required();
  cmd->add_option("--divisions", *divisions, "Bézier cells A,B,C per direction (default 1,1,1)");
  cmd->add_option("--margin", *margin, "space added on every side, as a fraction of the box's longest edge (default 0.05)");
  cmd->add_option("--axes", *axes, "directions of the box edges U, V, W as 9 numbers (default the coordinate axes); need not be orthogonal");
  cmd->callback([=] {
    const auto p = parse_integers(*degree, 3, 1, "--degree");
    const auto n = parse_integers(*divisions, 3, 1, "--divisions");
    Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();
    if (!axes->empty()) {
      const auto a = parse_numbers(*axes, 9, "--axes");
      for (int d = 0; d < 3; ++d)
        for (int i = 0; i < 3; ++i) directions(i, d) = a[static_cast<std::size_t>(3 * d + i)];
    }
    const TriangleMesh mesh = read_mesh(*in);
    Lattice lattice = [&] {
      try {
        return undeformed_lattice(mesh, {p[0], p[1], p[2]}, {n[0], n[1], n[2]}, *margin, directions);
      } catch (const InvalidInput& e) {
        throw e.located(*in);
      }
    }();
    write_model(lattice_to_model(lattice), *out);
    const auto counts = lattice.volume.num_control_points();
    std::cout << "wrote " << *out << ": degree " << p[0] << "," << p[1] << "," << p[2] << ", " << counts[0] << "x" << counts[1]
              << "x" << counts[2] << " control points around " << mesh.num_vertices() << " vertices\n";
  });
}

}  // namespace volspline::cli
