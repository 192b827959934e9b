// volspline eval MODEL --at U,V,W ... | --grid NU,NV,NW [--derivatives] [--json]
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "volspline/core/error.h"
#include "volspline/io/model_volumes.h"

namespace volspline::cli {

namespace {

struct EvalRequest {
  std::vector<std::string> at;
  std::string grid;
  std::size_t object = 0;
  bool derivatives = false;
  bool json = false;
  std::string location;  // "FILE: objects[i]" for error messages
};

// Values (and first partials) of one object at the requested points, one row per point:
// k numbers, then with derivatives D * k partials (x_u y_u z_u x_v ...).
template <int D>
std::vector<std::vector<double>> evaluate_rows(const TensorSpline<D>& s, const EvalRequest& r) {
  const int order = r.derivatives ? 1 : 0;
  const std::size_t k = static_cast<std::size_t>(s.dimension());
  const std::size_t row = k * (order ? D + 1 : 1);
  std::vector<std::vector<double>> rows;
  if (!r.grid.empty()) {
    const auto n = parse_integers(r.grid, D, 2, "--grid");
    double requested = 1.0;
    for (int x : n) requested *= x;
    if (requested > 5e7) throw InvalidInput("expected at most 50 million grid points, got '" + r.grid + "'", "--grid");
    std::array<std::vector<double>, D> samples;
    std::size_t total = 1;
    for (int d = 0; d < D; ++d) {
      const auto dd = static_cast<std::size_t>(d);
      for (int i = 0; i < n[dd]; ++i) {
        // exact endpoints: the last sample is the domain maximum itself
        const double a = s.domain_min(d), b = s.domain_max(d);
        samples[dd].push_back(i == n[dd] - 1 ? b : a + (b - a) * i / (n[dd] - 1));
      }
      total *= static_cast<std::size_t>(n[dd]);
    }
    const auto values = s.evaluate_grid(samples, order);
    for (std::size_t p = 0; p < total; ++p) {
      std::vector<double> line(row);
      for (std::size_t a = 0; a < row / k; ++a)
        for (std::size_t c = 0; c < k; ++c) line[a * k + c] = values[(a * total + p) * k + c];
      rows.push_back(std::move(line));
    }
  }
  for (std::size_t i = 0; i < r.at.size(); ++i) {
    const std::string where = r.location + " at --at[" + std::to_string(i) + "]";
    const auto t = parse_numbers(r.at[i], D, where);
    std::array<double, D> param{};
    std::copy(t.begin(), t.end(), param.begin());
    std::vector<double> line(row);
    try {
      s.evaluate_derivatives(param, order, line.data());
    } catch (const InvalidInput& e) {
      throw e.located(where);
    }
    rows.push_back(std::move(line));
  }
  return rows;
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("eval", "Evaluate an object at parameter points or on a regular grid; prints one line per point, x y z [then xu yu zu xv yv zv xw yw zw]");
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
    if (r->object >= model.objects.size())
      throw InvalidInput("object " + std::to_string(r->object) + " does not exist; the model has " +
                             std::to_string(model.objects.size()) + " object(s)",
                         "--object");
    const auto& object = model.objects[r->object];
    r->location = object_location(input->path, r->object);
    const int k = std::visit([](const auto& s) { return s.dimension(); }, object.spline);
    const auto rows = std::visit([&](const auto& s) { return evaluate_rows(s, *r); }, object.spline);
    if (r->json) {
      nlohmann::json out;
      out["points"] = nlohmann::json::array();
      for (const auto& row : rows) {
        out["points"].push_back(std::vector<double>(row.begin(), row.begin() + k));
        if (r->derivatives) out["derivatives"].push_back(std::vector<double>(row.begin() + k, row.end()));
      }
      std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::strict) << "\n";
      return;
    }
    std::string text;
    for (const auto& row : rows) text += join_numbers(row.data(), row.size()) + "\n";
    std::cout << text;
  });
}

}  // namespace volspline::cli
