// volspline convert MODEL -o OUT [--format F] [--input-format F] [--insert-knots DIR:V,...]
// [--elevate DIR:TIMES] [--bezier]; formats by extension from io/model_formats.h.
#include <algorithm>
#include <iostream>
#include <optional>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/core/error.h"
#include "volspline/io/model_formats.h"
#include "volspline/io/model_refinement.h"
#include "volspline/io/model_volumes.h"

namespace volspline::cli {

namespace {

std::pair<int, std::string> split_direction(const std::string& text, const std::string& option) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InvalidInput("expected DIR:VALUES such as w:0.25,0.5, got '" + text + "'", option);
  return {parse_direction(text.substr(0, colon), option), text.substr(colon + 1)};
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("convert", "Rewrite a model, in another format or refined: insert knots, elevate degrees, split into Bézier pieces (geometry unchanged)");
  std::string formats;
  for (const ModelFormat& f : model_formats()) {
    formats += std::string(formats.empty() ? "" : ", ") + f.name + " (" + f.extension + ")";
  }
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto inserts = std::make_shared<std::vector<std::string>>();
  auto elevations = std::make_shared<std::vector<std::string>>();
  auto bezier = std::make_shared<bool>(false);
  auto format = std::make_shared<std::string>();
  auto input_format = std::make_shared<std::string>();
  cmd->add_option("MODEL", *in, "input model file; its format from the extension: " + formats)->required();
  cmd->add_option("-o,--output", *out, "output file; its format from the extension")->required();
  cmd->add_option("--format", *format, "output format, overriding the extension: json, gismo, irit or vtu");
  cmd->add_option("--input-format", *input_format, "input format, overriding the extension");
  cmd->add_option("--insert-knots", *inserts, "DIR:VALUE[,VALUE...] knots to insert in direction u, v or w; repeatable");
  cmd->add_option("--elevate", *elevations, "DIR:TIMES raise the degree in a direction; repeatable");
  cmd->add_flag("--bezier", *bezier, "write every nonempty knot cell as its own bezier_* object (after the other steps)");
  cmd->callback([=] {
    std::vector<RefinementStep> steps;
    for (const auto& s : *inserts) {
      auto [d, rest] = split_direction(s, "--insert-knots");
      steps.push_back(RefinementStep::insertion(
          d, parse_numbers(rest, static_cast<std::size_t>(std::count(rest.begin(), rest.end(), ',') + 1), "--insert-knots")));
    }
    for (const auto& s : *elevations) {
      auto [d, rest] = split_direction(s, "--elevate");
      steps.push_back(RefinementStep::degree_elevation(d, parse_integers(rest, 1, 1, "--elevate")[0]));
    }
    // Unknown formats are reported before any work.
    if (!format->empty()) {
      model_format_named(*format);
    } else {
      model_format_from_path(*out);
    }
    Progress* progress = command_progress();
    Model model = [&] {
      const ProgressPhase phase(progress, "reading");
      return read_model_file(*in, *input_format);
    }();
    std::optional<ProgressPhase> phase(std::in_place, progress, "converting", static_cast<double>(model.objects.size()));
    Model result;
    result.metadata = model.metadata;
    for (std::size_t i = 0; i < model.objects.size(); ++i) {
      try {
        if (*bezier) {
          for (ModelObject& piece : bezier_objects(model.objects[i], steps)) result.objects.push_back(std::move(piece));
        } else {
          result.objects.push_back(refine_object(model.objects[i], steps));
        }
      } catch (const InvalidInput& e) {
        throw e.located(object_location(*in, i));
      }
      phase->advance();
    }
    phase.emplace(progress, "writing");
    write_model_file(result, *out, *format);
    phase.reset();
    std::cout << "wrote " << *out << " (" << result.objects.size() << " object(s))\n";
  });
}

}  // namespace volspline::cli
