// volspline info MODEL [--json]: what a model file holds.
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "volspline/analysis/mass_properties.h"
#include "volspline/core/format.h"
#include "volspline/pipeline/model_summary.h"

namespace volspline::cli {

namespace {

std::string list(const nlohmann::json& a, const char* sep = " x ") {
  std::string s;
  for (std::size_t i = 0; i < a.size(); ++i) s += (i ? sep : "") + json_text(a[i], -1);
  return s;
}

std::string numbers(const nlohmann::json& a) {
  std::string s;
  for (std::size_t i = 0; i < a.size(); ++i) s += (i ? ", " : "") + format_double(a[i].get<double>());
  return "(" + s + ")";
}

// --mass: volume, centroid and inertia (about the centroid) of a volume in R^3, plus how the
// quadrature went; docs/mass-properties.md. A zero volume has no centroid or inertia (null).
void add_mass(nlohmann::json& j, const MassProperties& m) {
  auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); };
  j["volume"] = m.volume;
  j["centroid"] = {finite(m.centroid.x()), finite(m.centroid.y()), finite(m.centroid.z())};
  j["inertia"] = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) j["inertia"].push_back({finite(m.inertia(r, 0)), finite(m.inertia(r, 1)), finite(m.inertia(r, 2))});
  j["mass_quadrature"] = {{"signed_volume", m.signed_volume},       {"estimated_relative_error", m.estimated_relative_error},
                          {"converged", m.converged},               {"quadrature_points", m.quadrature_points},
                          {"knot_cells", m.knot_cells},             {"folded_cells", m.folded_cells}};
}

void print_mass(const nlohmann::json& j) {
  if (!j.contains("volume")) {
    std::cout << "  mass            none (only volumes in R^3 have mass properties)\n";
    return;
  }
  std::cout << "  volume          " << format_double(j["volume"].get<double>()) << "\n";
  if (j["centroid"][0].is_null()) {
    std::cout << "  centroid        undefined (zero volume)\n";
  } else {
    std::cout << "  centroid        " << numbers(j["centroid"]) << "\n  inertia (about the centroid)\n";
    for (const auto& row : j["inertia"]) std::cout << "                  " << numbers(row) << "\n";
  }
  const auto& q = j["mass_quadrature"];
  if (q["folded_cells"].get<int>() > 0)
    std::cout << "  note            the Jacobian changes sign in " << q["folded_cells"].get<int>() << " of " << q["knot_cells"].get<int>()
              << " knot cells: the volume folds over itself and overlaps count twice (signed volume "
              << format_double(q["signed_volume"].get<double>()) << ")\n";
  if (!q["converged"].get<bool>())
    std::cout << "  note            quadrature budget exhausted: estimated relative error "
              << format_double(q["estimated_relative_error"].get<double>()) << "\n";
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe every object of a model: type, degrees, control points, knot spans, domain, rational, bounding box");
  auto json = std::make_shared<bool>(false);
  const auto input = add_model_input(cmd);
  const auto model_path = std::shared_ptr<std::string>(input, &input->path);
  cmd->add_flag("--json", *json, "print JSON instead of text");
  auto mass = std::make_shared<bool>(false);
  cmd->add_flag("--mass", *mass, "also volume, centroid and inertia tensor (about the centroid, unit density) of every volume");
  cmd->callback([=] {
    const Model model = input->read();
    nlohmann::json out;
    out["file"] = *model_path;
    out["objects"] = model_object_summaries(model);
    if (*mass)
      for (std::size_t i = 0; i < model.objects.size(); ++i)
        if (const auto* v = std::get_if<BSplineVolume>(&model.objects[i].spline); v != nullptr && v->dimension() == 3)
          add_mass(out["objects"][i], mass_properties(*v));
    if (*json) {
      std::cout << json_text(out) << "\n";
      return;
    }
    std::cout << *model_path << ": " << model.objects.size() << " object(s)\n";
    for (const auto& j : out["objects"]) {
      std::cout << "object " << j["index"].get<std::size_t>() << ": " << j["type"].get<std::string>();
      if (j.contains("name")) std::cout << " \"" << j["name"].get<std::string>() << "\"";
      if (j.contains("tetrahedra")) {
        std::cout << "\n  degree          " << j["degree"].get<int>() << "\n  domain          " << j["tetrahedra"].get<std::size_t>()
                  << " tetrahedra on " << j["domain_points"].get<std::size_t>() << " points, volume "
                  << format_double(j["domain_volume"].get<double>()) << "\n  knots           " << j["knots"].get<std::size_t>() << " ("
                  << j["degree"].get<int>() + 1 << " per point)\n  control points  " << j["control_points"].get<int>() << " ("
                  << j["control"].get<std::string>() << "), in " << numbers(j["control_box"]["min"]) << " .. "
                  << numbers(j["control_box"]["max"]) << "\n";
        for (const auto& name : j["attributes"])
          std::cout << "  attribute       " << name.get<std::string>() << " in ["
                    << format_double(j["attribute_ranges"][name.get<std::string>()][0].get<double>()) << ", "
                    << format_double(j["attribute_ranges"][name.get<std::string>()][1].get<double>()) << "]\n";
        continue;
      }
      if (j.contains("generator_patches")) {
        std::cout << "\n  generator       " << j["generator_patches"].get<std::size_t>() << " volume patch(es)"
                  << "\n  path            degree " << j["path"]["degree"][0].get<int>() << ", " << j["path"]["knot_spans"][0].get<int>()
                  << " knot span(s), t in [0, 1]\n  frame           " << j["frame"].get<std::string>();
        if (j["frame_fit_error"].get<double>() > 0) std::cout << " (fit error " << format_double(j["frame_fit_error"].get<double>()) << ")";
        std::cout << "\n";
        continue;
      }
      std::cout << "\n  degree          " << list(j["degree"], ", ")
                << "\n  control points  " << list(j["control_points"]) << " in R^" << j["dimension"].get<int>()
                << "\n  knot spans      " << list(j["knot_spans"]) << "\n  domain          ";
      for (std::size_t d = 0; d < j["domain"].size(); ++d)
        std::cout << (d ? " x " : "") << "[" << format_double(j["domain"][d][0].get<double>()) << ", "
                  << format_double(j["domain"][d][1].get<double>()) << "]";
      std::cout << "\n  rational        " << (j["rational"].get<bool>() ? "yes" : "no");
      if (j["points_at_infinity"].get<long>() > 0) std::cout << " (" << j["points_at_infinity"].get<long>() << " control point(s) at infinity)";
      std::cout << "\n  bounding box    " << numbers(j["bounding_box"]["min"]) << " .. " << numbers(j["bounding_box"]["max"]) << "\n";
      if (*mass) print_mass(j);
    }
  });
}

}  // namespace volspline::cli
