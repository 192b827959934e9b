// volspline make swept-solid --generator G.json --path C.json [--frame F] -o S.json: the swept
// trivariate solid s = c(t) + R(t) g(u, v, w) of Conkey-Joy 2000 (construct/swept_solid.h),
// written as a swept_solid model object (docs/sweeps.md, "Swept solids").
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_support.h"
#include "commands.h"
#include "volspline/construct/swept_solid.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/model_file.h"
#include "volspline/io/model_volumes.h"

namespace volspline::cli {

namespace {

struct SweptSolidRequest {
  std::string generator, path, frame = "fixed", out;
};

// The volume objects of the generator file, and where each came from ("G.json: objects[i]").
std::pair<std::vector<BSplineVolume>, std::vector<std::string>> generator_patches(const std::string& file) {
  const Model model = read_model(file);
  std::vector<BSplineVolume> patches;
  std::vector<std::string> locations;
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    if (const auto* v = std::get_if<BSplineVolume>(&model.objects[i].spline)) {
      patches.push_back(*v);
      locations.push_back(object_location(file, i));
    }
  }
  if (patches.empty()) throw InvalidInput(file + " has no volume object (bspline_volume or bezier_volume)", "--generator");
  return {std::move(patches), std::move(locations)};
}

// The curve objects of a path or frame file, which must hold curves only (an object of another
// kind is refused by its place, not passed over).
std::vector<BSplineCurve> curves_of(const std::string& file, const std::string& option) {
  std::vector<BSplineCurve> curves;
  const Model model = read_model(file);
  for (std::size_t i = 0; i < model.objects.size(); ++i) {
    if (const auto* c = std::get_if<BSplineCurve>(&model.objects[i].spline)) curves.push_back(*c);
    else throw InvalidInput(object_location(file, i) + " is not a curve (bspline_curve or bezier_curve): a " +
                                (option == "--path" ? "path file holds one curve" : "frame file holds three curves, b, n, t"),
                            option);
  }
  return curves;
}

// fixed | frenet | rmf | rotate:AX,AY,AZ:DEGREES | FRAME.json (three curves b, n, t).
SweptSolidFrame parse_frame(const std::string& text) {
  SweptSolidFrame frame;
  if (text == "fixed") return frame;
  if (text == "frenet" || text == "rmf") {
    frame.kind = text == "frenet" ? SweptSolidFrame::Kind::Frenet : SweptSolidFrame::Kind::RotationMinimizing;
    return frame;
  }
  if (text.rfind("rotate:", 0) == 0) {
    const std::string rest = text.substr(7);
    const auto colon = rest.find(':');
    if (colon == std::string::npos)
      throw InvalidInput("expected rotate:AX,AY,AZ:DEGREES, got '" + text + "'", "--frame");
    const auto axis = parse_numbers(rest.substr(0, colon), 3, "--frame axis");
    frame.kind = SweptSolidFrame::Kind::Rotation;
    frame.axis = Eigen::Vector3d(axis[0], axis[1], axis[2]);
    frame.degrees = parse_numbers(rest.substr(colon + 1), 1, "--frame degrees")[0];
    return frame;
  }
  frame.kind = SweptSolidFrame::Kind::Curves;
  frame.curves = curves_of(text, "--frame");
  if (frame.curves.size() != 3)
    throw InvalidInput(text + " has " + std::to_string(frame.curves.size()) +
                           " curve object(s); a frame file has exactly 3 (b, n, t: the columns of R(t))",
                       "--frame");
  return frame;
}

void make_swept_solid_file(const SweptSolidRequest& r) {
  // Named, not a structured binding: clang 14 (the sanitizer build's compiler) does not let the
  // lambda below capture bindings.
  auto generator = generator_patches(r.generator);
  auto& patches = generator.first;
  const auto& locations = generator.second;
  const std::vector<BSplineCurve> path_curves = curves_of(r.path, "--path");
  if (path_curves.size() != 1)
    throw InvalidInput(r.path + " has " + std::to_string(path_curves.size()) + " curve objects; a path file holds exactly one (the trajectory c(t))",
                       "--path");
  const SweptSolidFrame frame = parse_frame(r.frame);
  const std::size_t count = patches.size();
  SweptSolid solid = [&] {
    try {
      return make_swept_solid(std::move(patches), path_curves.front(), frame);
    } catch (const InvalidInput& e) {
      // Name the file the library's "generator[i]", "path" or "frame..." came from.
      const std::string& where = e.where();
      if (where.rfind("generator[", 0) == 0) {
        const std::size_t i = std::stoul(where.substr(10));
        throw InvalidInput(e.message(), "--generator " + (i < locations.size() ? locations[i] : r.generator));
      }
      if (where.rfind("path", 0) == 0) throw InvalidInput(e.message(), "--path " + r.path);
      if (where.rfind("frame", 0) == 0) throw InvalidInput(e.message(), "--frame " + r.frame);
      // The frames computed from the path (Frenet, rotation-minimising) fail on the path.
      if (where.empty() && (frame.kind == SweptSolidFrame::Kind::Frenet || frame.kind == SweptSolidFrame::Kind::RotationMinimizing))
        throw InvalidInput(e.message(), "--frame " + r.frame + " on --path " + r.path);
      throw;
    }
  }();
  Model model;
  model.objects.push_back({"swept solid", false, solid, nullptr});
  write_model(model, r.out);
  std::cout << "wrote " << r.out << ": swept solid of " << count << " generator patch(es), frame " << solid.frame_name;
  if (frame.kind == SweptSolidFrame::Kind::Frenet || frame.kind == SweptSolidFrame::Kind::RotationMinimizing)
    std::cout << ", frame fit error " << format_double(solid.frame_fit_error) << " (max |R^T R - I|, tolerance " << frame.tolerance
              << ")";
  std::cout << "\n";
}

}  // namespace

void add_make_swept_solid_kind(CLI::App* make) {
  auto r = std::make_shared<SweptSolidRequest>();
  auto* cmd = make->add_subcommand("swept-solid", "Sweep a generator solid along a path with a moving frame, s = c(t) + R(t) g(u,v,w) "
                                                  "(Conkey-Joy 2000): a swept_solid object of 4-variate patches");
  cmd->add_option("--generator", r->generator, "model file; every volume object is a generator patch")->required();
  cmd->add_option("--path", r->path, "model file holding one curve: the trajectory c(t)")->required();
  cmd->add_option("--frame", r->frame,
                  "fixed (default), frenet, rmf (fitted; prints the fit error), rotate:AX,AY,AZ:DEGREES (exact turn by DEGREES * t "
                  "at arc ends), or a model file whose three curves are b, n, t (the columns of R(t))");
  cmd->add_option("-o,--output", r->out, "output model file (.json)")->required();
  cmd->callback([r] { make_swept_solid_file(*r); });
}

}  // namespace volspline::cli
