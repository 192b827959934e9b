// volspline eval MODEL --at U,V,W ... | --grid NU,NV,NW [--derivatives] [--json]
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/io/model_volumes.h"
#include "volspline/pipeline/object_evaluation.h"

namespace volspline::cli {

namespace {

struct EvalRequest {
  std::vector<std::string> at;
  std::string grid;
  long long object = 0;
  bool derivatives = false;
  bool json = false;
  std::string location;  // "FILE: objects[i]" for error messages
};

// The rows of the requested points of `object`: the grid's, then each --at point's.
std::vector<std::vector<double>> evaluate_rows(const ModelObject& object, const EvalRequest& r) {
  const auto parameters = static_cast<std::size_t>(parameter_count(object));
  std::vector<std::vector<double>> rows;
  if (!r.grid.empty()) {
    const auto n = parse_integers(r.grid, parameters, 2, "--grid");
    double requested = 1.0;
    for (int x : n) requested *= x;
    if (requested > 5e7) throw InvalidInput("expected at most 50 million grid points, got '" + r.grid + "'", "--grid");
    rows = evaluate_object_on_grid(object, n, r.derivatives);
  }
  std::vector<std::vector<double>> points;
  for (std::size_t i = 0; i < r.at.size(); ++i)
    points.push_back(parse_numbers(r.at[i], parameters, r.location + " at --at[" + std::to_string(i) + "]"));
  std::vector<std::vector<double>> at_rows;
  try {
    at_rows = evaluate_object_at_each(object, points, r.derivatives);
  } catch (const InvalidInput& e) {
    // "points[i]: ..." becomes "FILE: objects[k] at --at[i]: ...".
    const std::string& where = e.where();
    const std::string index = where.rfind("points[", 0) == 0 ? where.substr(6, where.find(']') - 5) : "";
    throw InvalidInput(e.message(), r.location + " at --at" + index);
  }
  rows.insert(rows.end(), std::make_move_iterator(at_rows.begin()), std::make_move_iterator(at_rows.end()));
  return rows;
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("eval", "Evaluate an object at parameter points or on a regular grid; prints one line per point, x y z [then xu yu zu xv yv zv xw yw zw]; "
      "a simplex_spline_volume at points X,Y,Z of its domain: x y z, then each attribute [then their derivatives along x, y, z], all 0 outside the domain");
  auto r = std::make_shared<EvalRequest>();
  const auto input = add_model_input(cmd);
  cmd->add_option("--at", r->at, "a parameter point U,V,W (as many numbers as the object has parameters); repeatable")->take_all();
  cmd->add_option("--grid", r->grid, "NU,NV,NW samples per direction, endpoints included, u fastest");
  cmd->add_option("--object", r->object, "index of the object to evaluate (default 0)");
  cmd->add_flag("--derivatives", r->derivatives, "also print the first partial derivatives");
  cmd->add_flag("--json", r->json, "print JSON: {\"points\": [[x,y,z],...], \"derivatives\": [[xu,...],...]}");
  cmd->callback([=] {
    if (r->at.empty() && r->grid.empty()) throw InvalidInput("give at least one --at U,V,W or a --grid NU,NV,NW", "eval");
    const Model model = input->read();
    const std::size_t index = object_index(r->object, model.objects.size(), "--object");
    const auto& object = model.objects[index];
    r->location = object_location(input->path, index);
    const auto* simplex = std::get_if<DmsSplineVolume>(&object.spline);
    const int k = simplex ? simplex->dimension() : visit_spline(object, "eval", r->location, [](const auto& s) { return s.dimension(); });
    const auto rows = evaluate_rows(object, *r);
    if (r->json) {
      nlohmann::json out;
      out["points"] = nlohmann::json::array();
      for (const auto& row : rows) {
        out["points"].push_back(std::vector<double>(row.begin(), row.begin() + k));
        if (r->derivatives) out["derivatives"].push_back(std::vector<double>(row.begin() + k, row.end()));
      }
      std::cout << json_text(out, -1) << "\n";
      return;
    }
    std::string text;
    for (const auto& row : rows) text += join_numbers(row.data(), row.size()) + "\n";
    std::cout << text;
  });
}

}  // namespace volspline::cli
