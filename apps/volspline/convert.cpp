// volspline convert MODEL -o OUT [--format F] [--input-format F] [--insert-knots DIR:V,...]
// [--elevate DIR:TIMES] [--bezier]; formats by extension from io/model_formats.h.
#include <iostream>
#include <optional>

#include "cli_support.h"
#include "commands.h"
#include "progress_bar.h"
#include "volspline/core/error.h"
#include "volspline/io/model_formats.h"
#include "volspline/spline/attribute_spline.h"
#include "volspline/spline/bezier_extraction.h"
#include "volspline/spline/degree_elevation.h"
#include "volspline/spline/knot_insertion.h"
#include "volspline/spline/reparameterization.h"

namespace volspline::cli {

namespace {

struct Refinement {
  int direction;
  std::vector<double> knots;  // insertion
  int times = 0;              // elevation
};

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
    std::vector<Refinement> steps;
    for (const auto& s : *inserts) {
      auto [d, rest] = split_direction(s, "--insert-knots");
      steps.push_back({d, parse_numbers(rest, static_cast<std::size_t>(std::count(rest.begin(), rest.end(), ',') + 1), "--insert-knots"), 0});
    }
    for (const auto& s : *elevations) {
      auto [d, rest] = split_direction(s, "--elevate");
      steps.push_back({d, {}, parse_integers(rest, 1, 1, "--elevate")[0]});
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
      ModelObject& object = model.objects[i];
      const std::string where = *in + ": objects[" + std::to_string(i) + "]";
      try {
      std::visit(
          [&](auto& geometry) {
            using Spline = std::decay_t<decltype(geometry)>;
            // Attributes ride along as extra coordinates, so every step transforms them exactly
            // as it transforms the geometry.
            std::vector<std::string> names;
            std::vector<std::vector<double>> fields;
            for (const auto& [name, values] : object.attributes) {
              names.push_back(name);
              fields.push_back(values);
            }
            validate_attributes(object);
            const int k = geometry.dimension();
            Spline s = fields.empty() ? geometry : append_coordinates(geometry, fields);
            const auto store = [&](ModelObject& target, const Spline& augmented) {
              if (names.empty()) {
                target.spline = augmented;
                return;
              }
              auto [spline, values] = split_coordinates(augmented, k);
              target.spline = std::move(spline);
              target.attributes.clear();
              for (std::size_t f = 0; f < names.size(); ++f) target.attributes[names[f]] = std::move(values[f]);
            };
            for (const auto& step : steps) {
              if (step.direction >= Spline::num_parameters)
                throw InvalidInput("direction " + std::to_string(step.direction) + " does not exist for a " +
                                       object_type_name(object),
                                   where);
              s = step.times ? elevate_degree(s, step.direction, step.times) : refine_knots(s, step.direction, step.knots);
            }
            if (!*bezier) {
              object.bezier = object.bezier && std::all_of(s.knot_vectors().begin(), s.knot_vectors().end(),
                                                           [](const KnotVector& kv) { return kv.is_bezier(); });
              ModelObject converted = object;
              store(converted, s);
              result.objects.push_back(std::move(converted));
              return;
            }
            const auto pieces = bezier_pieces(s);
            for (std::size_t c = 0; c < pieces.size(); ++c) {
              ModelObject piece{object.name.empty() ? "" : object.name + " cell " + std::to_string(c), true,
                                geometry, object.metadata};
              store(piece, reparameterize_to_unit_box(pieces[c]));
              result.objects.push_back(std::move(piece));
            }
          },
          object.spline);
      } catch (const InvalidInput& e) {
        throw e.located(where);
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
