// volspline faces MODEL -o OUT.(ply|obj|stl) [--png IMAGE.png] [--resolution N] [--ascii]
#include <iostream>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_volumes.h"
#include "volspline/extract/face_tessellation.h"
#include "volspline/mesh/mesh_checks.h"
#include "volspline/mesh/mesh_writer.h"
#include "volspline/pipeline/interactive_model_page.h"
#include "volspline/render/image.h"
#include "volspline/render/mesh_renderer.h"

namespace volspline::cli {

void add_faces_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("faces", "Tessellate the six boundary faces of every volume (parts 0..5) into one welded mesh");
  auto out = std::make_shared<std::string>();
  auto png = std::make_shared<std::string>();
  auto resolution = std::make_shared<int>(24);
  auto ascii = std::make_shared<bool>(false);
  auto edges = std::make_shared<bool>(false);
  auto transparent = std::make_shared<bool>(false);
  auto size = std::make_shared<std::string>("800,600");
  const auto input = add_model_input(cmd);
  const auto in = std::shared_ptr<std::string>(input, &input->path);
  cmd->add_option("-o,--output", *out, "mesh file: .ply (binary; x y z u v w, face part), .obj or .stl")->required();
  cmd->add_option("--png", *png, "also render a shaded picture of the faces");
  cmd->add_option("--resolution", *resolution, "segments per parameter direction, plus every knot (default 24)")->check(CLI::Range(1, 1024));
  cmd->add_flag("--ascii", *ascii, "write PLY or STL as text");
  cmd->add_flag("--edges", *edges, "draw the triangle edges in the picture");
  cmd->add_flag("--transparent", *transparent, "transparent picture background");
  cmd->add_option("--size", *size, "picture size W,H in pixels (default 800,600)");
  const auto html = add_html_option(cmd);
  cmd->callback([=] {
    const MeshFormat format = mesh_format_from_path(*out);  // reject a bad extension before any work
    if (!png->empty() && std::filesystem::path(*png).extension() != ".png")
      throw InvalidInput("expected a file name ending in .png, got '" + *png + "'", "--png");
    const auto wh = parse_integers(*size, 2, 16, "--size");
    if (wh[0] > 8192 || wh[1] > 8192) throw InvalidInput("expected at most 8192 x 8192 pixels, got '" + *size + "'", "--size");
    check_html_option(*html);
    const Model model = input->read();
    TriangleMesh mesh;
    const std::size_t volumes = for_each_volume(model, *in, [&](std::size_t, const ModelObject&, const BSplineVolume& v) {
      mesh.append(tessellate_faces(v, {.resolution = *resolution}));
    });
    RenderOptions options;
    options.width = wh[0];
    options.height = wh[1];
    options.edges = *edges;
    options.transparent_background = *transparent;
    write_mesh_and_picture(mesh, *out, format, *ascii, *png, options);
    const auto stats = edge_statistics(mesh);
    if (!html->empty()) {
      InteractivePage page;
      page.title = "faces of " + *in;
      page.mesh = mesh;
      page.info = model_page_info(model, *in);
      page.info["faces"] = {{"vertices", mesh.num_vertices()},      {"triangles", mesh.num_triangles()},
                            {"closed", stats.closed()},             {"boundary_edges", stats.boundary_edges},
                            {"nonmanifold_edges", stats.nonmanifold_edges}};
      add_model_probes(page, model, {}, *in);
      write_html_page(*html, std::move(page));
    }
    std::cout << "wrote " << *out << ": " << mesh.num_vertices() << " vertices, " << mesh.num_triangles() << " triangles from "
              << volumes << " volume(s); " << (stats.closed() ? "closed" : "not closed") << " (" << stats.boundary_edges
              << " boundary, " << stats.nonmanifold_edges << " non-manifold edges)\n";
    if (!png->empty()) std::cout << "wrote " << *png << "\n";
  });
}

}  // namespace volspline::cli
