// volspline ffd LATTICE.json IN.(obj|ply|stl) -o OUT.(obj|ply|stl) [--png IMAGE.png] [--ascii]
#include <iostream>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"
#include "volspline/deform/lattice.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void add_ffd_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("ffd", "Free-form deformation of a mesh by a lattice (see `volspline lattice`)");
  auto lattice_path = std::make_shared<std::string>();
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto png = std::make_shared<std::string>();
  auto ascii = std::make_shared<bool>(false);
  auto edges = std::make_shared<bool>(false);
  auto size = std::make_shared<std::string>("800,600");
  cmd->add_option("LATTICE", *lattice_path, "lattice model file (one volume with metadata.lattice)")->required();
  cmd->add_option("MESH", *in, "mesh file: .obj, .ply or .stl")->required();
  cmd->add_option("-o,--output", *out, "deformed mesh: .ply, .obj or .stl")->required();
  cmd->add_option("--png", *png, "also render a shaded picture of the deformed mesh");
  cmd->add_flag("--ascii", *ascii, "write PLY or STL as text");
  cmd->add_flag("--edges", *edges, "draw the triangle edges in the picture");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  cmd->callback([=] {
    mesh_format_from_path(*out);  // reject a bad extension before any work
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    const Lattice lattice = lattice_from_model(read_model(*lattice_path), *lattice_path);
    const TriangleMesh mesh = read_mesh(*in);
    const TriangleMesh deformed = deform_mesh(lattice, mesh);
    write_mesh(deformed, *out, {.ascii = *ascii});
    std::cout << "wrote " << *out << ": " << deformed.num_vertices() << " vertices, " << deformed.num_triangles() << " triangles\n";
    if (!png->empty()) {
      RenderOptions options;
      options.width = wh[0];
      options.height = wh[1];
      options.edges = *edges;
      options.color = ColorMode::Single;
      write_png(render_mesh(deformed, options), *png);
      std::cout << "wrote " << *png << "\n";
    }
  });
}

}  // namespace volspline::cli
