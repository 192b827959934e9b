// volspline info MODEL [--json]: what a model file holds.
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/format.h"
#include "volspline/spline/affine_map.h"

namespace volspline::cli {

namespace {

template <int D>
nlohmann::json describe(const TensorSpline<D>& s) {
  nlohmann::json j;
  const auto [lo, hi] = bounding_box(s, 4);  // 16 pieces per span: tight to ~1e-3 of the size
  for (int d = 0; d < D; ++d) {
    const auto& kv = s.knot_vector(d);
    j["degree"].push_back(kv.degree());
    j["control_points"].push_back(s.num_control_points()[static_cast<std::size_t>(d)]);
    j["knot_spans"].push_back(kv.num_spans());
    j["domain"].push_back({kv.domain_min(), kv.domain_max()});
    j["clamped"].push_back(kv.is_clamped());
  }
  j["dimension"] = s.dimension();
  j["rational"] = s.is_rational();
  j["points_at_infinity"] = std::count(s.weights().begin(), s.weights().end(), 0.0);
  j["bounding_box"] = {{"min", std::vector<double>(lo.data(), lo.data() + lo.size())},
                       {"max", std::vector<double>(hi.data(), hi.data() + hi.size())}};
  return j;
}

std::string list(const nlohmann::json& a, const char* sep = " x ") {
  std::string s;
  for (std::size_t i = 0; i < a.size(); ++i) s += (i ? sep : "") + a[i].dump();
  return s;
}

std::string numbers(const nlohmann::json& a) {
  std::string s;
  for (std::size_t i = 0; i < a.size(); ++i) s += (i ? ", " : "") + format_double(a[i].get<double>());
  return "(" + s + ")";
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("info", "Describe every object of a model: type, degrees, control points, knot spans, domain, rational, bounding box");
  auto model_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("MODEL", *model_path, "model file (JSON, docs/model-format.md)")->required();
  cmd->add_flag("--json", *json, "print JSON instead of text");
  cmd->callback([=] {
    const Model model = read_model(*model_path);
    nlohmann::json out;
    out["file"] = *model_path;
    out["objects"] = nlohmann::json::array();
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      const auto& object = model.objects[i];
      nlohmann::json j = std::visit([](const auto& s) { return describe(s); }, object.spline);
      j["index"] = i;
      j["type"] = object_type_name(object);
      if (!object.name.empty()) j["name"] = object.name;
      out["objects"].push_back(j);
    }
    if (*json) {
      std::cout << out.dump(2) << "\n";
      return;
    }
    std::cout << *model_path << ": " << model.objects.size() << " object(s)\n";
    for (const auto& j : out["objects"]) {
      std::cout << "object " << j["index"].get<std::size_t>() << ": " << j["type"].get<std::string>();
      if (j.contains("name")) std::cout << " \"" << j["name"].get<std::string>() << "\"";
      std::cout << "\n  degree          " << list(j["degree"], ", ")
                << "\n  control points  " << list(j["control_points"]) << " in R^" << j["dimension"].get<int>()
                << "\n  knot spans      " << list(j["knot_spans"]) << "\n  domain          ";
      for (std::size_t d = 0; d < j["domain"].size(); ++d)
        std::cout << (d ? " x " : "") << "[" << format_double(j["domain"][d][0].get<double>()) << ", "
                  << format_double(j["domain"][d][1].get<double>()) << "]";
      std::cout << "\n  rational        " << (j["rational"].get<bool>() ? "yes" : "no");
      if (j["points_at_infinity"].get<long>() > 0) std::cout << " (" << j["points_at_infinity"].get<long>() << " control point(s) at infinity)";
      std::cout << "\n  bounding box    " << numbers(j["bounding_box"]["min"]) << " .. " << numbers(j["bounding_box"]["max"]) << "\n";
    }
  });
}

}  // namespace volspline::cli
