// volspline make KIND [options] -o OUT.json: exact primitives, revolutions, extrusions, ruled
// volumes, lofts, sweeps and the paper examples, built by construct/ and written as a model file.
#include <array>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli_support.h"
#include "commands.h"
#include "volspline/construct/loft.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/construct/revolution.h"
#include "volspline/construct/sweep.h"
#include "volspline/construct/translation.h"
#include "volspline/core/error.h"
#include "volspline/io/model_file.h"

namespace volspline::cli {

namespace {

Eigen::Vector3d vector3(const std::string& text, const std::string& option) {
  const auto v = parse_numbers(text, 3, option);
  return {v[0], v[1], v[2]};
}

// The library names its parameters in InvalidInput::where() ("radius", "sections[1]"); the user
// knows them as options. `options` maps a parameter name (or the prefix before "[") to one.
BSplineVolume build(const std::function<BSplineVolume()>& construct, const std::map<std::string, std::string>& options) {
  try {
    return construct();
  } catch (const InvalidInput& e) {
    const std::string& where = e.where();
    if (auto it = options.find(where); it != options.end()) throw InvalidInput(e.message(), it->second);
    const auto bracket = where.find('[');
    if (bracket != std::string::npos)
      if (auto it = options.find(where.substr(0, bracket)); it != options.end())
        throw InvalidInput(e.message(), it->second + where.substr(bracket));
    throw;
  }
}

template <int D>
TensorSpline<D> first_object(const std::string& path, const std::string& option) {
  static_assert(D == 1 || D == 2);
  const Model model = read_model(path);
  for (const auto& object : model.objects)
    if (const auto* s = std::get_if<TensorSpline<D>>(&object.spline)) return *s;
  const std::string kind = D == 1 ? "curve" : "surface";
  throw InvalidInput(path + " has no " + kind + " object (bspline_" + kind + " or bezier_" + kind + ")", option);
}

void write_volume(const BSplineVolume& v, const std::string& kind, const std::string& out) {
  Model model;
  model.objects.push_back({kind, true, v, nullptr});  // written as bezier_volume when it is one Bézier span on [0,1]^3
  write_model(model, out);
  const auto p = v.degrees();
  const auto n = v.num_control_points();
  std::cout << "wrote " << out << ": " << kind << ", " << object_type_name(model.objects[0]) << " of degree (" << p[0] << ", " << p[1]
            << ", " << p[2] << "), " << n[0] << " x " << n[1] << " x " << n[2] << " control points"
            << (v.is_rational() ? ", rational" : "") << "\n";
}

// One `make` kind: its subcommand with -o and, if `center`, --center; `run` builds the volume.
struct Kind {
  CLI::App* app;
  std::shared_ptr<std::string> out = std::make_shared<std::string>();
  std::shared_ptr<std::string> center = std::make_shared<std::string>("0,0,0");
  Eigen::Vector3d center_point() const { return vector3(*center, "--center"); }
};

Kind add_kind(CLI::App* make, const std::string& name, const std::string& description, bool center,
              std::function<BSplineVolume(const Kind&)> run) {
  Kind kind{make->add_subcommand(name, description)};
  kind.app->add_option("-o,--output", *kind.out, "output model file (.json)")->required();
  if (center) kind.app->add_option("--center", *kind.center, "X,Y,Z center of the solid (default 0,0,0)");
  kind.app->callback([kind, name, run] { write_volume(run(kind), name, *kind.out); });
  return kind;
}

// The exact primitives (docs/constructions.md).
void add_primitive_kinds(CLI::App* make) {
  {
    auto size = std::make_shared<std::string>();
    auto k = add_kind(make, "box", "Axis-parallel box, degree (1,1,1)", true, [=](const Kind& k) {
      const auto s = vector3(*size, "--size");
      return build([&] { return box(s, k.center_point()); }, {{"size", "--size"}, {"center", "--center"}});
    });
    k.app->add_option("--size", *size, "X,Y,Z edge lengths")->required();
  }
  {
    auto radius = std::make_shared<double>();
    auto k = add_kind(make, "ball", "Solid ball: a half disk revolved, degree (1,2,2)", true, [=](const Kind& k) {
      return build([&] { return ball(*radius, k.center_point()); }, {{"radius", "--radius"}, {"center", "--center"}});
    });
    k.app->add_option("--radius", *radius, "radius R > 0")->required();
  }
  {
    auto radius = std::make_shared<double>(), height = std::make_shared<double>(), inner = std::make_shared<double>(0.0);
    auto k = add_kind(make, "cylinder", "Solid or hollow cylinder about the z axis, degree (1,1,2)", true, [=](const Kind& k) {
      return build([&] { return cylinder(*radius, *height, *inner, k.center_point()); },
                   {{"radius", "--radius"}, {"height", "--height"}, {"inner", "--inner"}, {"center", "--center"}});
    });
    k.app->add_option("--radius", *radius, "outer radius R > 0")->required();
    k.app->add_option("--height", *height, "height H > 0")->required();
    k.app->add_option("--inner", *inner, "inner radius 0 <= R0 < R (default 0: solid)");
  }
  {
    auto r1 = std::make_shared<double>(), r2 = std::make_shared<double>(), height = std::make_shared<double>();
    auto k = add_kind(make, "cone", "Cone or frustum about the z axis, degree (1,1,2)", true, [=](const Kind& k) {
      return build([&] { return cone(*r1, *r2, *height, k.center_point()); },
                   {{"radius1", "--radius1"}, {"radius2", "--radius2"}, {"height", "--height"}, {"center", "--center"}});
    });
    k.app->add_option("--radius1", *r1, "bottom radius >= 0")->required();
    k.app->add_option("--radius2", *r2, "top radius >= 0 (0: a cone)")->required();
    k.app->add_option("--height", *height, "height H > 0")->required();
  }
  {
    auto major = std::make_shared<double>(), minor = std::make_shared<double>(), angle = std::make_shared<double>(360.0);
    auto k = add_kind(make, "torus", "Solid torus or torus segment about the z axis, degree (1,2,2)", true, [=](const Kind& k) {
      return build([&] { return torus(*major, *minor, *angle, k.center_point()); },
                   {{"major", "--major"}, {"minor", "--minor"}, {"angle", "--angle"}, {"center", "--center"}});
    });
    k.app->add_option("--major", *major, "distance R from the axis to the tube's center")->required();
    k.app->add_option("--minor", *minor, "tube radius 0 < r < R")->required();
    k.app->add_option("--angle", *angle, "angle of the segment in degrees, in (0, 360] (default 360)");
  }
}

// Lasser's Figs. 2 and 3 and Joy-Duchaineau's Fig. 1: exact rational solids of the papers.
void add_paper_solid_kinds(CLI::App* make) {
  {
    auto major = std::make_shared<double>(2.0), minor = std::make_shared<double>(1.0);
    auto k = add_kind(make, "half-torus", "Lasser Fig. 2: solid half torus, one Bézier volume of degree (1,2,2) with points at infinity", true,
                      [=](const Kind& k) {
                        return build([&] { return half_torus(*major, *minor, k.center_point()); },
                                     {{"major", "--major"}, {"minor", "--minor"}, {"center", "--center"}});
                      });
    k.app->add_option("--major", *major, "distance R from the axis to the tube's center (default 2)");
    k.app->add_option("--minor", *minor, "tube radius 0 < r < R (default 1)");
  }
  {
    auto throat = std::make_shared<double>(1.0), half_height = std::make_shared<double>(1.0);
    auto k = add_kind(make, "hyperboloid",
                      "Lasser Fig. 3: half of a solid hyperboloid of one sheet x^2+y^2-z^2 = a^2, degree (1,1,2) with points at infinity", true,
                      [=](const Kind& k) {
                        return build([&] { return hyperboloid_segment(*throat, *half_height, k.center_point()); },
                                     {{"throat_radius", "--throat-radius"}, {"half_height", "--half-height"}, {"center", "--center"}});
                      });
    k.app->add_option("--throat-radius", *throat, "radius a of the waist (default 1)");
    k.app->add_option("--half-height", *half_height, "the solid spans |z| <= this (default 1)");
  }
  add_kind(make, "half-cylinder-sweep", "Joy-Duchaineau Fig. 1: (cos pi u + 3w, sin pi u, v), rational degree (2,1,1)", false,
           [](const Kind&) { return half_cylinder_sweep(); });
}

// Volumes made from profile surfaces read from model files: revolved, moved, ruled, lofted.
void add_profile_kinds(CLI::App* make) {
  {
    auto profile = std::make_shared<std::string>(), point = std::make_shared<std::string>(), direction = std::make_shared<std::string>();
    auto angle = std::make_shared<double>();
    auto single = std::make_shared<bool>(false);
    auto k = add_kind(make, "revolve", "Revolve a profile surface about an axis (Lasser Theorem 2), exact", false, [=](const Kind&) {
      const auto a = vector3(*point, "--axis-point"), d = vector3(*direction, "--axis-direction");
      const auto f = first_object<2>(*profile, "--profile");
      return build([&] { return *single ? revolve_single_segment(f, a, d, *angle) : revolve(f, a, d, *angle); },
                   {{"profile", "--profile"}, {"axis_point", "--axis-point"}, {"axis_direction", "--axis-direction"}, {"angle", "--angle"}});
    });
    k.app->add_option("--profile", *profile, "model file; its first surface is revolved")->required();
    k.app->add_option("--axis-point", *point, "X,Y,Z a point on the axis")->required();
    k.app->add_option("--axis-direction", *direction, "X,Y,Z the axis direction (rotation counter-clockwise about it)")->required();
    k.app->add_option("--angle", *angle, "degrees, in (0, 360]; arcs of at most 90 degrees")->required();
    k.app->add_flag("--single-segment", *single, "one rational Bézier segment in w (angle in (0, 180]; 180 gives points at infinity)");
  }
  {
    auto profile = std::make_shared<std::string>(), vector = std::make_shared<std::string>(), along = std::make_shared<std::string>();
    auto k = add_kind(make, "extrude", "Move a profile surface along a vector or a curve (Lasser Theorem 1)", false, [=](const Kind&) {
      if (vector->empty() == along->empty()) throw InvalidInput("give exactly one of --vector and --along", "--vector");
      const auto f = first_object<2>(*profile, "--profile");
      if (!vector->empty()) {
        const auto t = vector3(*vector, "--vector");
        return build([&] { return extrude(f, t); }, {{"vector", "--vector"}, {"profile", "--profile"}});
      }
      const auto path = first_object<1>(*along, "--along");
      return build([&] { return translation_volume(f, path); }, {{"path", "--along"}});
    });
    k.app->add_option("--profile", *profile, "model file; its first surface is moved")->required();
    auto* v = k.app->add_option("--vector", *vector, "X,Y,Z straight extrusion (degree 1 in w)");
    k.app->add_option("--along", *along, "model file; the surface moves along its first curve, translated to start at F(u_min, v_min)")->excludes(v);
  }
  {
    auto from = std::make_shared<std::string>(), to = std::make_shared<std::string>();
    auto k = add_kind(make, "ruled", "Ruled (linear blending) volume between two surfaces", false, [=](const Kind&) {
      const auto a = first_object<2>(*from, "--from"), b = first_object<2>(*to, "--to");
      return build([&] { return ruled_volume(a, b); }, {{"sections[0]", "--from"}, {"sections[1]", "--to"}});
    });
    k.app->add_option("--from", *from, "model file; its first surface is w = 0")->required();
    k.app->add_option("--to", *to, "model file; its first surface is w = 1")->required();
  }
  {
    auto through = std::make_shared<std::vector<std::string>>();
    auto degree = std::make_shared<int>(3);
    auto centripetal = std::make_shared<bool>(false);
    auto k = add_kind(make, "loft", "Loft (skin) through surfaces, interpolating each", false, [=](const Kind&) {
      std::vector<BSplineSurface> sections;
      for (std::size_t i = 0; i < through->size(); ++i)
        sections.push_back(first_object<2>((*through)[i], "--through[" + std::to_string(i) + "]"));
      return build([&] { return loft(sections, *degree, *centripetal ? LoftParameterization::Centripetal : LoftParameterization::ChordLength); },
                   {{"sections", "--through"}, {"degree", "--degree"}});
    });
    k.app->add_option("--through", *through, "model files, in order; the first surface of each is a section (at least 2)")->required();
    k.app->add_option("--degree", *degree, "degree in w (default 3; at most the number of sections - 1)");
    k.app->add_flag("--centripetal", *centripetal, "centripetal instead of chord-length section parameters");
  }
}

// A profile swept along a path with a moving frame (docs/sweeps.md).
void add_sweep_kind(CLI::App* make) {
  {
    auto profile = std::make_shared<std::string>(), path = std::make_shared<std::string>(), frame = std::make_shared<std::string>("rmf");
    auto k = add_kind(make, "sweep", "Sweep a profile surface along a curve with a moving frame, V = c(w) + R(w) F(u,v)", false, [=](const Kind&) {
      const auto f = first_object<2>(*profile, "--profile");
      const auto c = first_object<1>(*path, "--path");
      const std::map<std::string, std::string> names{{"profile", "--profile"}, {"path", "--path"}, {"frame", "--frame"}};
      if (*frame == "rmf") return build([&] { return sweep(f, c, SweepFrame::RotationMinimizing); }, names);
      if (*frame == "frenet") return build([&] { return sweep(f, c, SweepFrame::Frenet); }, names);
      if (*frame == "fixed") return build([&] { return sweep(f, c, SweepFrame::Fixed); }, names);
      const Model m = read_model(*frame);
      std::vector<BSplineCurve> curves;
      for (const auto& object : m.objects)
        if (const auto* s = std::get_if<BSplineCurve>(&object.spline)) curves.push_back(*s);
      if (curves.size() < 3)
        throw InvalidInput(*frame + " has " + std::to_string(curves.size()) + " curve object(s); a frame needs 3 (the columns of R(w))", "--frame");
      return build([&] { return sweep_with_frame_curves(f, c, {curves[0], curves[1], curves[2]}); }, names);
    });
    k.app->add_option("--profile", *profile, "model file; its first surface is swept")->required();
    k.app->add_option("--path", *path, "model file; its first curve is the path c(w)")->required();
    k.app->add_option("--frame", *frame, "rmf (rotation minimising, default), frenet, fixed, or a model file whose first 3 curves are the columns of R(w)");
  }
}

// Joy-Duchaineau's Figs. 10, 11 and 13, built in code.
void add_joy_duchaineau_kinds(CLI::App* make) {
  add_kind(make, "swept-patch", "Joy-Duchaineau Fig. 10: a bicubic patch swept along a line", false, [](const Kind&) { return swept_patch(); });
  add_kind(make, "twisted-loft", "Joy-Duchaineau Fig. 11: the patch twisted 35 degrees while swept, sampled 4 times and lofted", false,
           [](const Kind&) { return twisted_loft(); });
  add_kind(make, "curved-loft", "Joy-Duchaineau Fig. 13: the patch swept along a curved path, sampled and lofted", false,
           [](const Kind&) { return curved_loft(); });
}

}  // namespace

void add_make_command(CLI::App& app) {
  auto* make = app.add_subcommand("make", "Build an exact solid (primitive, revolution, extrusion, loft, sweep, paper example) as a model file");
  make->require_subcommand(1);
  add_primitive_kinds(make);
  add_paper_solid_kinds(make);
  add_profile_kinds(make);
  add_sweep_kind(make);
  add_joy_duchaineau_kinds(make);
  add_make_swept_solid_kind(make);
  add_make_simplex_spline_kind(make);
}

}  // namespace volspline::cli
