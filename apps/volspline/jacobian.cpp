// volspline jacobian MODEL [--tol T] [--max-cells N] [--bounds bezier|cone] [--json] [--fail-invalid]
#include <iomanip>
#include <iostream>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/analysis/jacobian_validity.h"
#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"
#include "volspline/core/format.h"
#include "volspline/io/model_formats.h"
#include "volspline/io/model_volumes.h"

namespace volspline::cli {

namespace {

JacobianBoundMethod parse_bounds(const std::string& text) {
  if (text == "bezier") return JacobianBoundMethod::Bezier;
  if (text == "cone") return JacobianBoundMethod::Cone;
  throw InvalidInput("expected 'bezier' or 'cone', got '" + text + "'", "--bounds");
}

// JSON has no infinity: an infinite bound is written null, and "bounds_finite" says whether both
// bounds are numbers (docs/jacobian.md).
nlohmann::json jacobian_json_number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void print_validity(std::size_t i, const ModelObject& object, const BSplineVolume& v, const JacobianValidity& r) {
  std::cout << "object " << i << (object.name.empty() ? "" : " (" + object.name + ")") << ": " << verdict_name(r.verdict);
  if (r.verdict == JacobianVerdict::Valid) std::cout << ", orientation " << (r.orientation > 0 ? "+" : "-");
  std::cout << "\n  J in [" << format_double(r.lower) << ", " << format_double(r.upper) << "]"
            << (v.is_rational() ? " (rational: from the bounds of w^4 J and of w)" : "") << "\n";
  if (r.witness) {
    std::cout << "  witness (u, v, w) = (" << join_numbers(r.witness->data(), 3) << ") where "
              << (r.witness_value == 0 ? "J = 0 (collapsed control points)"
                                       : std::string(r.witness_value < 0 ? "J < 0" : "J > 0") + " (" + format_double(r.witness_value) + ")")
              << "\n";
  }
  std::cout << "  " << r.cells << " cells, " << std::setprecision(3) << r.seconds * 1e3 << " ms\n";
}

}  // namespace

void add_jacobian_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("jacobian",
                                 "Certify the sign of the Jacobian determinant of every volume: valid (orientation + or -), "
                                 "invalid (with a witness point) or undecided within the budget");
  auto tol = std::make_shared<double>(1e-12);
  auto max_cells = std::make_shared<std::int64_t>(200000);
  auto bounds = std::make_shared<std::string>("bezier");
  auto json = std::make_shared<bool>(false);
  auto fail = std::make_shared<bool>(false);
  const auto input = add_model_input(cmd);
  const auto in = std::shared_ptr<std::string>(input, &input->path);
  cmd->add_option("--tol", *tol, "cells whose bound is narrower than TOL x max|J| are not split further (default 1e-12)");
  cmd->add_option("--max-cells", *max_cells, "budget of cells examined per volume (default 200000, or fewer where the memory and work limits hold fewer; a larger explicit budget than they hold is refused)")->check(CLI::Range(std::int64_t{1}, std::int64_t{1} << 40));
  cmd->add_option("--bounds", *bounds, "bezier (certified Bernstein coefficients, default) or cone (Joy–Duchaineau §5)");
  cmd->add_flag("--json", *json, "print JSON: {\"objects\": [{\"verdict\", \"orientation\", \"lower\", \"upper\", \"witness\", \"cells\", \"seconds\"}]}");
  cmd->add_flag("--fail-invalid", *fail, "exit with code 3 if any volume is invalid");
  cmd->callback([=] {
    JacobianValidityOptions options;
    options.bounds = parse_bounds(*bounds);
    options.tolerance = *tol;
    options.max_cells = *max_cells;
    if (!(*tol >= 0) || !std::isfinite(*tol)) throw InvalidInput("expected a finite number >= 0", "--tol");
    options.progress = command_progress();
    const Model model = [&] {
      const ProgressPhase phase(options.progress, "reading");
      return input->read();
    }();
    const bool several = count_volumes(model) > 1;
    nlohmann::json out = {{"objects", nlohmann::json::array()}};
    bool any_invalid = false;
    for_each_volume(model, *in, [&](std::size_t i, const ModelObject& object, const BSplineVolume& v) {
      if (several) reporter().set_label("object " + std::to_string(i));
      if (cmd->count("--max-cells") != 0 && v.dimension() == 3) {
        // An explicit budget is refused, not shrunk, when the limits cannot hold it.
        const std::int64_t allowed = jacobian_cells_within_limits(v, options.bounds);
        if (options.max_cells > allowed)
          throw InvalidInput("--max-cells " + std::to_string(options.max_cells) + " needs more memory or work than the limits allow (at most " +
                             std::to_string(allowed) + " cells of this volume's degree; " + memory_limit_hint() + ", or --work-limit)");
      }
      const JacobianValidity r = check_jacobian(v, options);
      any_invalid = any_invalid || r.verdict == JacobianVerdict::Invalid;
      nlohmann::json o = {{"object", i},
                          {"name", object.name},
                          {"verdict", verdict_name(r.verdict)},
                          {"orientation", r.orientation},
                          {"lower", jacobian_json_number(r.lower)},
                          {"upper", jacobian_json_number(r.upper)},
                          {"bounds_finite", std::isfinite(r.lower) && std::isfinite(r.upper)},
                          {"witness", r.witness ? nlohmann::json(*r.witness) : nlohmann::json(nullptr)},
                          {"witness_value", r.witness ? jacobian_json_number(r.witness_value) : nlohmann::json(nullptr)},
                          {"rational", v.is_rational()},
                          {"cells", r.cells},
                          {"seconds", r.seconds}};
      out["objects"].push_back(o);
      if (!*json) print_validity(i, object, v, r);
    });
    reporter().set_label("");
    if (*json) std::cout << json_text(out) << "\n";
    if (*fail && any_invalid) throw ExitCode{3};
  });
}

}  // namespace volspline::cli
