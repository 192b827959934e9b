// volspline xray MODEL -o IMAGE.png [--attribute A] [--size W,H] [--view DX,DY,DZ] [--up UX,UY,UZ]
//   [--fov DEG] [--absorption K] [--baseline B] [--raw OUT.pfm] [--object I]
// The X-ray (absorption) picture of an attribute of a simplex spline volume (Hua–He–Qin §6.1,
// render/xray_image.h), its line integrals computed analytically.
#include <iostream>
#include <memory>
#include <string>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/pfm_file.h"
#include "volspline/render/xray_image.h"

namespace volspline::cli {

namespace {

struct XrayRequest {
  std::string out, attribute, size = "512,512", view, up, raw;
  double fov = 0;
  double absorption = std::numeric_limits<double>::quiet_NaN();
  double baseline = 0;
  long long object = 0;
};

}  // namespace

void add_xray_command(CLI::App& app) {
  auto r = std::make_shared<XrayRequest>();
  auto* cmd = app.add_subcommand("xray", "X-ray picture of an attribute of a simplex spline volume: I = exp(-k * integral of the attribute "
                                         "along each ray), the integrals computed analytically");
  const auto input = add_model_input(cmd);
  cmd->add_option("-o,--output", r->out, "output picture (.png): white where the material absorbs, black where it does not")->required();
  cmd->add_option("--attribute", r->attribute, "the attribute integrated (default: the first; none: the length of the rays inside the domain)");
  cmd->add_option("--size", r->size, "W,H in pixels (default 512,512)");
  cmd->add_option("--view", r->view, "DX,DY,DZ: the direction the camera looks in (default -1,-1.3,-0.8)");
  cmd->add_option("--up", r->up, "UX,UY,UZ: the direction shown upwards (default 0,0,1)");
  cmd->add_option("--fov", r->fov, "angle of view in degrees; 0 (default) is a parallel projection");
  cmd->add_option("--absorption", r->absorption, "the absorption coefficient k (default: the largest integral absorbs 86%)");
  cmd->add_option("--baseline", r->baseline,
                  "subtract this from the attribute before integrating (e.g. the ambient temperature; default 0)");
  cmd->add_option("--raw", r->raw, "also write the line integrals as a float image (.pfm)");
  cmd->add_option("--object", r->object, "index of the simplex_spline_volume object (default: the first)");
  cmd->callback([=] {
    const Model model = input->read();
    const DmsSplineVolume* volume = nullptr;
    const std::size_t chosen = cmd->count("--object") ? object_index(r->object, model.objects.size(), "--object") : 0;
    for (std::size_t i = 0; i < model.objects.size() && volume == nullptr; ++i)
      if (cmd->count("--object") == 0 || i == chosen) volume = std::get_if<DmsSplineVolume>(&model.objects[i].spline);
    if (volume == nullptr)
      throw InvalidInput(input->path + (cmd->count("--object") ? ": objects[" + std::to_string(r->object) + "] is not" : " has no") +
                             " simplex_spline_volume object (make one with `volspline make simplex-spline`)",
                         "--object");
    XrayOptions options;
    const auto size = parse_integers(r->size, 2, 1, "--size");
    options.width = size[0];
    options.height = size[1];
    options.attribute = r->attribute;
    if (!r->view.empty()) options.view_direction = parse_view_direction(r->view, "--view");
    if (!r->up.empty()) {
      const auto u = parse_numbers(r->up, 3, "--up");
      options.up = Eigen::Vector3d(u[0], u[1], u[2]);
    }
    options.field_of_view_deg = r->fov;
    options.absorption = r->absorption;
    options.baseline = r->baseline;
    const XrayRenderer renderer(*volume, options);
    write_png(renderer.image(), r->out);
    if (!r->raw.empty()) write_pfm(renderer.picture().line_integrals, options.width, options.height, r->raw);
    const auto& p = renderer.picture();
    double largest = 0;
    for (double v : p.line_integrals) largest = std::max(largest, v);
    std::cout << "wrote " << r->out << (r->raw.empty() ? "" : " and " + r->raw) << ": " << options.width << " x " << options.height
              << ", largest line integral " << format_double(largest) << ", absorption " << format_double(p.absorption) << ", "
              << p.tetrahedron_integrals << " tetrahedron integrals in " << format_double(p.seconds) << " s\n";
  });
}

}  // namespace volspline::cli
