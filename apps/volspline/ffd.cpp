// volspline ffd LATTICE.json IN.(obj|ply|stl|json) -o OUT.(obj|ply|stl|json) [--png IMAGE.png] [--ascii]
#include <iostream>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/deform/ffd.h"  // deform_mesh
#include "volspline/deform/lattice.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/mesh/mesh_reader.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/pipeline/model_deformation.h"
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
  cmd->add_option("INPUT", *in, "mesh file (.obj, .ply, .stl), or a model file (.json) whose curves and surfaces are composed exactly")->required();
  cmd->add_option("-o,--output", *out, "deformed mesh (.ply, .obj, .stl), or .json for a model input")->required();
  cmd->add_option("--png", *png, "also render a shaded picture of the deformed mesh");
  cmd->add_flag("--ascii", *ascii, "write PLY or STL as text");
  cmd->add_flag("--edges", *edges, "draw the triangle edges in the picture");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  const auto html = add_html_option(cmd);
  cmd->callback([=] {
    check_html_option(*html);
    if (std::filesystem::path(*in).extension() == ".json") {
      if (!html->empty()) throw InvalidInput("--html is for a mesh input; a model output opens in `volspline view --html`", "--html");
      // Spline curves and surfaces: exact functional composition through the lattice.
      if (std::filesystem::path(*out).extension() != ".json")
        throw InvalidInput("a model input needs a .json output, got '" + *out + "'", "--output");
      const Lattice lattice = lattice_from_model(read_model(*lattice_path), *lattice_path);
      const Model model = deform_model(lattice, read_model(*in), *in);
      write_model(model, *out);
      std::cout << "wrote " << *out << " (" << model.objects.size() << " object(s), composed exactly)\n";
      return;
    }
    const MeshFormat format = mesh_format_from_path(*out);  // reject a bad extension before any work
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + *size + "'", "--size");
    const Model lattice_model = read_model(*lattice_path);
    const Lattice lattice = lattice_from_model(lattice_model, *lattice_path);
    const TriangleMesh mesh = read_mesh(*in);
    const TriangleMesh deformed = deform_mesh(lattice, mesh);
    RenderOptions options;
    options.width = wh[0];
    options.height = wh[1];
    options.edges = *edges;
    options.color = ColorMode::Single;
    write_mesh_and_picture(deformed, *out, format, *ascii, *png, options);
    if (!html->empty()) {
      InteractivePage page;
      page.title = *in + " deformed by " + *lattice_path;
      page.mesh = deformed;
      page.info = {{"lattice", model_page_info(lattice_model, *lattice_path)}, {"input", *in}};
      write_html_page(*html, std::move(page));
    }
    std::cout << "wrote " << *out << ": " << deformed.num_vertices() << " vertices, " << deformed.num_triangles() << " triangles\n";
    if (!png->empty()) std::cout << "wrote " << *png << "\n";
  });
}

}  // namespace volspline::cli
