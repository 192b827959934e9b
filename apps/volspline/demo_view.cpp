// The looking-inside examples of `volspline demo` (Lasser 1994 §IV, Figs. 8-13): each is a
// `volspline view` command, run here exactly as the gallery prints it (inside the demo folder).
#include "demo_view.h"

#include <iostream>
#include <sstream>

#include "demo_gallery.h"
#include "view_command.h"
#include "volspline/construct/example_solids.h"
#include "volspline/construct/paper_examples.h"
#include "volspline/construct/primitives.h"
#include "volspline/core/progress.h"
#include "volspline/io/model_file.h"

namespace volspline::cli {
namespace {

// A solid torus segment carrying a "temperature" attribute that rises along the tube (w) and
// outwards from the tube's centre line (u): a material field for --color.
Model torus_with_temperature() {
  const BSplineVolume volume = torus(3.0, 1.0, 270.0);
  const auto n = volume.num_control_points();
  std::vector<double> temperature;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) temperature.push_back(20 + 40.0 * k / (n[2] - 1) + 8.0 * i / (n[0] - 1));
  Model model;
  ModelObject object{"torus", false, volume, nullptr};
  object.attributes["temperature"] = temperature;
  model.objects.push_back(object);
  return model;
}

void write_if_absent(const std::filesystem::path& path, const std::string& name, const BSplineVolume& volume) {
  if (std::filesystem::exists(path)) return;
  Model model;
  model.objects.push_back({name, true, volume, nullptr});  // bezier_volume when it is one span on [0,1]^3
  write_model(model, path);
}

}  // namespace

void write_view_demo(DemoRun& demo) {
  if (!demo.wants_group("view-", "view-family-w..view-fold-jacobian")) return;
  const std::filesystem::path& dir = demo.dir();
  write_model(torus_with_temperature(), dir / "torus-temperature.json");
  write_if_absent(dir / "bent-tricubic.json", "bent-tricubic", bent_tricubic_volume());
  write_if_absent(dir / "half-torus.json", "half-torus", half_torus());
  write_if_absent(dir / "twisted-loft.json", "twisted-loft", twisted_loft());
  struct Example {
    std::string title, description;
    ViewArguments arguments;
  };
  const auto view = [](std::string model, std::string image) {
    ViewArguments a;
    a.model = std::move(model);
    a.image = std::move(image);
    a.size = "640,480";
    a.resolution = 24;
    return a;
  };
  std::vector<Example> examples;
  {
    auto a = view("bent-tricubic.json", "view-family-w.png");
    a.iso = {"w:5"};
    examples.push_back({"A family of isoparametric surfaces", "Lasser Fig. 8: surfaces w = const of a tricubic volume", a});
  }
  for (const char* d : {"u", "v"}) {
    auto a = view("bent-tricubic.json", std::string("view-family-") + d + ".png");
    a.iso = {std::string(d) + ":5"};
    examples.push_back({std::string("Isoparametric surfaces ") + d + " = const", "Lasser Fig. 9: the other two families", a});
  }
  {
    auto a = view("bent-tricubic.json", "view-through-point.png");
    a.through = "0.35,0.6,0.5";
    a.color = "jacobian";
    examples.push_back({"Three surfaces through a point", "Lasser Fig. 10: V(u_i, v, w), V(u, v_j, w), V(u, v, w_k) through V(0.35, 0.6, 0.5), coloured by the Jacobian", a});
  }
  {
    auto a = view("half-torus.json", "view-cross-section.png");
    a.planes = {"1,0,0.4,0.3"};
    a.cutaway = true;
    examples.push_back({"Cross section", "Lasser Fig. 11: the half torus cut by an oblique plane, the part in front cut away", a});
  }
  {
    auto a = view("torus-temperature.json", "view-slices.png");
    a.slices = {"x:5"};
    a.color = "temperature";
    examples.push_back({"A series of parallel slices", "Lasser Fig. 12: five slices x = const, coloured by a material attribute", a});
  }
  {
    auto a = view("torus-temperature.json", "view-core.png");
    a.core = "0.5,2.8,0.2";
    a.cutaway = true;
    a.color = "temperature";
    examples.push_back({"Core section", "Lasser Fig. 13: three orthogonal slices through a point", a});
  }
  {
    auto a = view("torus-temperature.json", "view-paddlewheel.png");
    a.paddlewheels = {"z:6"};
    a.color = "temperature";
    examples.push_back({"Paddlewheel probe", "six planes through the torus axis", a});
  }
  {
    auto a = view("twisted-loft.json", "view-fold-jacobian.png");
    a.iso = {"w:4"};
    a.color = "jacobian";
    examples.push_back({"Where the map folds", "Joy-Duchaineau Fig. 11's twisted loft: surfaces w = const coloured by the Jacobian, red and blue on the two sides of the fold", a});
  }
  for (const auto& e : examples) {
    const std::string name = e.arguments.image.substr(0, e.arguments.image.size() - 4);
    if (!demo.wants(name)) continue;
    ViewArguments arguments = e.arguments;
    if (interactive_pages_available()) arguments.html = name + ".html";
    ViewArguments run = arguments;
    run.model = (dir / run.model).string();
    run.image = (dir / run.image).string();
    if (!run.html.empty()) run.html = (dir / run.html).string();
    {
      const ProgressPhase phase(demo.progress(), name);
      std::ostringstream log;
      run_view(run, log);
    }
    demo.gallery().add({e.title, e.description, {e.arguments.image}, view_command_line(arguments), arguments.html});
    std::cout << name << ": " << e.description << "\n  " << run.image << "\n";
  }
}

}  // namespace volspline::cli
