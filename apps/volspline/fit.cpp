// volspline fit DATA -o MODEL.json --degree N [--attributes a,b] [--primary-knots K] [--error E]
//   [--max-tetrahedra M] [--seconds T] [--stats S.json] [--png P.png]
// Fits scattered volume data with a trivariate DMS simplex spline (Hua–He–Qin §5, eq. 10;
// simplex/volume_fitting.h): domain from the data, generated knot clouds, geometry and
// attributes by least squares, then adaptive refinement (§5.4) down to the error bound E. DATA is a file (io/volume_data.h) or a generated data set:
// marschner-lobb:N (N³ samples on [−1, 1]³) or two-material:N.
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "fit_command.h"
#include "progress_bar.h"
#include "commands.h"
#include "volspline/construct/volume_data_examples.h"
#include "volspline/core/error.h"
#include "volspline/core/format.h"
#include "volspline/io/atomic_file.h"
#include "volspline/io/model_file.h"
#include "volspline/io/volume_data.h"
#include "volspline/pipeline/fit_baselines.h"
#include "volspline/render/image.h"
#include "volspline/render/xray_image.h"
#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline::cli {
namespace {


nlohmann::json baselines_json(const std::vector<MethodError>& errors) {
  nlohmann::json out = nlohmann::json::array();
  auto number = [](double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  for (const MethodError& e : errors)
    out.push_back({{"method", e.method},
                   {"attribute", e.attribute},
                   {"coefficients", e.coefficients},
                   {"data_points", e.data_points},
                   {"data_mean_square", e.data_mean_square},
                   {"data_max_abs", e.data_max_abs},
                   {"normalised_data_mean_square", e.normalised_data_mean_square},
                   {"normalised_data_max_abs", e.normalised_data_max_abs},
                   {"truth_mean_square", number(e.truth_mean_square)},
                   {"truth_max_abs", number(e.truth_max_abs)},
                   {"normalised_truth_mean_square", number(e.normalised_truth_mean_square)},
                   {"normalised_truth_max_abs", number(e.normalised_truth_max_abs)},
                   {"seconds", e.seconds}});
  return out;
}

VolumeData data_of(const std::string& name) {
  if (std::optional<VolumeData> generated = generated_volume_data(name)) return std::move(*generated);
  return read_volume_data(name);
}

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= list.size() && !list.empty()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    // "t, u" as "t,u": names are taken without the spaces around them.
    std::string name = list.substr(start, comma - start);
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    names.push_back(name);
    start = comma + 1;
  }
  return names;
}

nlohmann::json statistics_json(const VolumeFitStatistics& s, const std::string& data, int degree, double error_bound) {
  nlohmann::json j;
  const VolumeFitErrors& e = s.errors;
  j["data"] = data;
  j["degree"] = degree;
  j["data_points"] = s.data_points;
  j["fitted_points"] = e.fitted_points;
  j["outside_points"] = e.outside_points;
  j["delaunay_tetrahedra"] = s.delaunay_tetrahedra;
  j["domain_tetrahedra"] = s.domain_tetrahedra;
  j["control_points"] = s.control_points;
  j["primary_knots"] = s.primary_knots;
  j["primary_knots_layout"] = s.layout;
  j["fairing"] = s.fairing;
  j["knots"] = s.knots;
  j["coefficients_per_data_point"] = static_cast<double>(s.control_points) / static_cast<double>(std::max<std::size_t>(1, s.data_points));
  j["boundary_vertices"] = {{"corner", s.corner_vertices}, {"curve", s.curve_vertices}, {"general", s.general_vertices}};
  j["geometric_error"] = {{"mean_square", e.geometric_mean_square},
                          {"max_square", e.geometric_max},
                          {"scale", e.geometric_scale},
                          {"normalised_mean_square", e.normalised_geometric_mean_square},
                          {"normalised_max_square", e.normalised_geometric_max}};
  nlohmann::json fields = nlohmann::json::array();
  for (const auto& f : e.attributes)
    fields.push_back({{"attribute", f.name},
                      {"data_min", f.data_min},
                      {"data_max", f.data_max},
                      {"mean_square", f.mean_square},
                      {"max_abs", f.max_abs},
                      {"normalised_mean_square", f.normalised_mean_square},
                      {"normalised_max_abs", f.normalised_max_abs}});
  j["field_errors"] = fields;
  // Table 1's "field fitting error" is one number per data set; with several attributes fitted
  // together it is their mean normalised mean square (what refinement and placement minimise).
  j["field_normalised_mean_square"] = mean_normalised_field_error(e);
  nlohmann::json phases = nlohmann::json::object();
  double total = 0;
  for (const auto& p : s.phases) phases[p.name] = p.seconds, total += p.seconds;
  j["seconds"] = phases;
  j["seconds_total"] = total;
  j["solver"] = {{"method", e.solver.direct ? "SimplicialLDLT" : "conjugate gradients (incomplete Cholesky)"},
                 {"tikhonov_steps", e.solver.tikhonov_steps},
                 {"iterations", e.solver.iterations}};
  const KnotOptimisationReport& k = s.knot_optimisation;
  j["knot_optimisation"] = {{"sweeps", k.sweeps},
                            {"vertices_above_threshold", k.vertices_tried},
                            {"vertices_moved", k.vertices_moved},
                            {"primary_knots_moved", k.primary_knots_moved},
                            {"sweeps_kept", k.kept_sweeps},
                            {"sweeps_undone", k.undone_sweeps},
                            {"field_normalised_mean_square_before", k.before},
                            {"field_normalised_mean_square_after", k.after},
                            {"judged_on_held_out", k.judged_on_held_out},
                            {"held_out_field_normalised_mean_square_before", k.held_out_before},
                            {"held_out_field_normalised_mean_square_after", k.held_out_after}};
  const KnotPlacementReport& placement = s.knot_placement;
  j["knot_placement"] = {{"rounds", placement.rounds},
                         {"round_kept", placement.kept},
                         {"rounds_failed", placement.failed},
                         {"fairing", placement.fairing},
                         {"field_normalised_mean_square_before", placement.before},
                         {"field_normalised_mean_square_after", placement.after},
                         {"held_out_field_normalised_mean_square_before", placement.held_out_before},
                         {"held_out_field_normalised_mean_square_after", placement.held_out_after}};
  const SharpFeatureReport& sharp = s.sharp_features;
  if (sharp.enabled)
    j["sharp_features"] = {{"region_points", sharp.region_points},
                           {"jump_pairs", sharp.jump_edges},
                           {"interface_samples", sharp.interface_samples},
                           {"cut_tetrahedra", sharp.cut_tetrahedra},
                           {"snapped_points", sharp.snapped_points},
                           {"interface_points", sharp.interface_points},
                           {"points_across_interface", sharp.points_across}};
  const AdaptiveRefinementReport& r = s.refinement;
  nlohmann::json rounds = nlohmann::json::array();
  for (const auto& round : r.rounds)
    rounds.push_back({{"tetrahedra", round.tetrahedra},
                      {"control_points", round.control_points},
                      {"above_bound", round.above},
                      {"split", round.split},
                      {"field_normalised_mean_square", round.field_mean_square},
                      {"largest_tetrahedron_rms", round.largest_tetrahedron_error},
                      {"seconds", round.seconds},
                      {"undone", round.undone}});
  j["adaptive_refinement"] = {{"error_bound", error_bound},
                              {"error_measure", "per tetrahedron: RMS over its data points and the attributes of the normalised field error"},
                              {"state", refinement_stop_text(r.stop)},
                              {"tetrahedra_above_bound", r.above},
                              {"rounds", rounds}};
  return j;
}

}  // namespace

void run_fit(const FitArguments& r, std::ostream& out) {
  VolumeData data = data_of(r.data);
  try {
    data = select_attributes(data, split_names(r.attributes));
  } catch (const InvalidInput& e) {
    throw InvalidInput(e.message(), "--attributes");
  }
  if (data.attribute_names.empty()) throw InvalidInput(r.data + " has no attributes to fit (only x, y, z)", "DATA");
  VolumeFitOptions options;
  options.degree = r.degree;
  options.domain.primary_knots = r.primary_knots;
  if (r.layout != "auto" && r.layout != "farthest" && r.layout != "lattice")
    throw InvalidInput("expected --primary-knots-layout auto, farthest or lattice, got '" + r.layout + "'", "--primary-knots-layout");
  options.domain.lattice = r.layout == "lattice";
  options.grid_layout = r.layout == "auto";
  if (r.primary_knots < 0) throw InvalidInput("expected a positive number of primary knots, got " + std::to_string(r.primary_knots), "--primary-knots");
  if (!(r.error >= 0)) throw InvalidInput("expected an error bound >= 0, got " + format_double(r.error), "--error");
  if (r.max_tetrahedra < 0) throw InvalidInput("expected a tetrahedron budget >= 0, got " + std::to_string(r.max_tetrahedra), "--max-tetrahedra");
  if (!(r.seconds >= 0)) throw InvalidInput("expected a time budget >= 0 seconds, got " + format_double(r.seconds), "--seconds");
  if (r.knots != "fixed" && r.knots != "place" && r.knots != "optimise")
    throw InvalidInput("expected --knots fixed, place or optimise, got '" + r.knots + "'", "--knots");
  options.knots.enabled = r.knots != "fixed";
  options.knots.local = r.knots == "optimise";
  if (r.placement_rounds < 0 || r.placement_rounds > 10)
    throw InvalidInput("expected 0 to 10 placement rounds, got " + std::to_string(r.placement_rounds), "--placement-rounds");
  options.knots.placement_rounds = r.placement_rounds;
  if (!(r.spacing_ratio >= 1 && r.spacing_ratio <= 100))
    throw InvalidInput("expected a spacing ratio from 1 to 100, got " + format_double(r.spacing_ratio), "--spacing-ratio");
  options.knots.spacing_ratio = r.spacing_ratio;
  options.knots.move_primary_knots = !r.fixed_primary_knots;
  options.knots.held_out = !r.judge_local_step_at_data;
  if (r.knot_sweeps < 1 || r.knot_sweeps > 50)
    throw InvalidInput("expected 1 to 50 knot optimisation sweeps, got " + std::to_string(r.knot_sweeps), "--knot-sweeps");
  options.knots.sweeps = r.knot_sweeps;
  if (!(r.fairing >= 0) || !std::isfinite(r.fairing)) throw InvalidInput("expected a fairing weight >= 0, got " + format_double(r.fairing), "--fairing");
  options.fit.fairing = r.fairing;
  // An explicit --fairing, 0 too, is kept.
  if (r.fairing_given || (r.fairing_option && r.fairing_option->count() > 0)) options.default_fairing = r.fairing;
  if (!(r.jump >= 0) || !std::isfinite(r.jump)) throw InvalidInput("expected a jump >= 0, got " + format_double(r.jump), "--jump");
  options.jump = r.jump;
  options.refinement.error = r.error;
  options.refinement.max_tetrahedra = static_cast<std::size_t>(r.max_tetrahedra);
  options.refinement.seconds = r.seconds;
  Progress* progress = command_progress();
  VolumeFit fit = [&] {
    try {
      return fit_volume_data(data, options, [&](const std::string& phase) {
        if (progress) progress->begin_phase(phase);
      });
    } catch (const InvalidInput& e) {
      if (e.where() == "degree") throw InvalidInput(e.message(), "--degree");
      if (e.where() == "jump") throw InvalidInput(e.message(), "--jump");
      throw InvalidInput(e.message(), r.data + (e.where().empty() ? "" : ": " + e.where()));
    }
  }();
  if (progress) progress->end_phase();
  const VolumeFitStatistics statistics = fit.statistics;
  Model model;
  model.objects.push_back({"fitted " + r.data, false, std::move(fit.volume), nullptr});
  write_model(model, r.out);
  if (!r.png.empty()) {
    // The X-ray picture of the first fitted attribute (render/xray_image.h).
    const auto& volume = std::get<DmsSplineVolume>(model.objects.front().spline);
    XrayOptions xray;
    xray.attribute = data.attribute_names.front();
    if (progress) progress->begin_phase("picture");
    write_png(XrayRenderer(volume, xray).image(), r.png);
    if (progress) progress->end_phase();
  }
  std::vector<MethodError> baselines;
  if (r.baselines) {
    if (progress) progress->begin_phase("baselines");
    FitComparisonOptions comparison;
    comparison.truth = generated_volume_truth(r.data);
    baselines = compare_volume_fits(data, std::get<DmsSplineVolume>(model.objects.front().spline), comparison);
    if (progress) progress->end_phase();
  }
  if (!r.stats.empty()) {
    nlohmann::json j = statistics_json(statistics, r.data, r.degree, r.error);
    if (r.baselines) j["baselines"] = baselines_json(baselines);
    write_file_atomically(r.stats, j.dump(2) + "\n");
  }
  const VolumeFitErrors& e = statistics.errors;
  if (e.outside_points > 0)
    std::cerr << "volspline: warning: " << e.outside_points << " of " << e.data_points << " data points ("
              << (std::ostringstream() << std::fixed << std::setprecision(1)
                                       << 100.0 * static_cast<double>(e.outside_points) / static_cast<double>(std::max<std::size_t>(1, e.data_points)))
                     .str()
              << " %) lie outside the domain (the primary knots' Delaunay tetrahedra kept by the occupancy map): they are not "
                 "fitted and not in the errors; more --primary-knots cover more (docs/fitting.md, \"The domain\")\n";
  out << "wrote " << r.out << ": degree " << r.degree << " simplex spline fitted to " << e.fitted_points << " of " << e.data_points
            << " points (" << e.outside_points << " outside the domain), " << statistics.domain_tetrahedra << " tetrahedra, "
            << statistics.control_points << " control points, " << statistics.knots << " knots\n";
  out << "  primary knots: " << (statistics.layout == "lattice" ? "body-centred cubic lattice" : "farthest-point samples")
            << (r.layout == "auto" && statistics.layout == "lattice" ? " (the data form a complete grid)" : "") << ", fairing "
            << (std::ostringstream() << statistics.fairing).str() << "\n";
  out << "  geometry: mean square error " << format_double(e.geometric_mean_square) << "\n";
  if (e.attributes.size() > 1)
    out << "  fields: normalised mean square error " << format_double(mean_normalised_field_error(e)) << " (mean over "
              << e.attributes.size() << " attributes), "
              << format_double(static_cast<double>(statistics.control_points) / static_cast<double>(std::max<std::size_t>(1, e.data_points)))
              << " control points per data point\n";
  for (const auto& f : e.attributes)
    out << "  " << f.name << " (data " << format_double(f.data_min) << " .. " << format_double(f.data_max) << "): mean square error "
              << format_double(f.mean_square) << " (normalised " << format_double(f.normalised_mean_square) << "), max "
              << format_double(f.max_abs) << " (normalised " << format_double(f.normalised_max_abs) << ")\n";
  if (statistics.sharp_features.enabled) {
    const SharpFeatureReport& sh = statistics.sharp_features;
    out << "  sharp features: regions of " << sh.region_points[0] << " and " << sh.region_points[1] << " points, "
              << sh.interface_samples << " interface samples, " << sh.cut_tetrahedra << " tetrahedra cut, " << sh.snapped_points
              << " points moved onto the interface, " << sh.points_across << " data points across it (not fitted)\n";
  }
  if (r.knots != "fixed") {
    const KnotPlacementReport& p = statistics.knot_placement;
    out << "  knot placement: " << (p.kept ? "round " + std::to_string(p.kept) : std::string("no round")) << " of " << p.rounds
              << " kept, normalised field mean square "
              << format_double(p.before) << " -> " << format_double(p.after) << " (at the held-out eighth of the points: "
              << format_double(p.held_out_before) << " -> " << format_double(p.held_out_after) << ")\n";
    const KnotOptimisationReport& k = statistics.knot_optimisation;
    if (r.knots == "optimise")
      out << "  knot optimisation: " << k.vertices_moved << " of " << k.vertices_tried << " vertex clouds moved ("
              << k.primary_knots_moved << " with their primary knot) in " << k.sweeps << " sweeps (" << k.kept_sweeps << " kept), normalised field mean square " << format_double(k.before) << " -> " << format_double(k.after)
                << (k.judged_on_held_out ? " (at the held-out eighth of the points: " + format_double(k.held_out_before) + " -> " + format_double(k.held_out_after) + ")"
                                         : std::string(" (judged at the data)"))
                << "\n";
  }
  const AdaptiveRefinementReport& refinement = statistics.refinement;
  if (r.error > 0) {
    const std::string line = "adaptive refinement to " + format_double(r.error) + ": " + std::to_string(refinement.rounds.size() - 1) +
                             " rounds, " + refinement_stop_text(refinement.stop) + "; " + std::to_string(refinement.above) +
                             " tetrahedra above the bound";
    out << "  " << line << "\n";
    // Never silent: a budget that stopped the refinement is also said on stderr.
    if (refinement.stop != RefinementStop::Converged) reporter().warn(line);
  }
  if (r.baselines) {
    out << "  baselines (normalised mean square / max error at the data points"
              << (generated_volume_truth(r.data) ? "; against the true field at random points" : "") << "):\n";
    for (const MethodError& e : baselines) {
      out << "    " << e.method << ", " << e.attribute << ", " << e.coefficients << " coefficients: "
                << format_double(e.normalised_data_mean_square) << " / " << format_double(e.normalised_data_max_abs);
      if (!std::isnan(e.truth_mean_square))
        out << "; truth " << format_double(e.normalised_truth_mean_square) << " / " << format_double(e.normalised_truth_max_abs);
      out << "\n";
    }
  }
  out << "  time:";
  for (const auto& p : statistics.phases) out << " " << p.name << " " << format_double(p.seconds) << " s;";
  out << "\n";
}

void add_fit_command(CLI::App& app) {
  auto r = std::make_shared<FitArguments>();
  auto* cmd = app.add_subcommand("fit", "Fit scattered volume data (points with attributes) with a trivariate simplex spline "
                                        "(Hua-He-Qin 5: domain from the data, least squares, adaptive refinement)");
  cmd->add_option("DATA", r->data, kVolumeDataHelp)->required();
  cmd->add_option("-o,--output", r->out, "output model file (.json)")->required();
  cmd->add_option("--degree", r->degree, "the degree n, 1 to 5 (default 2)");
  cmd->add_option("--attributes", r->attributes, "the attributes to fit, comma-separated (default: all)");
  cmd->add_option("--primary-knots", r->primary_knots, "the number of primary knots (domain vertices; default: points / (2 (n+1)(n+2)), points / 24 for degree 2)");
  cmd->add_option("--primary-knots-layout", r->layout,
                  "auto (default: lattice for data on a complete regular grid, and farthest "
                  "otherwise or with --jump or --knots place/optimise), farthest (data points by farthest-point sampling) or "
                  "lattice (a body-centred cubic lattice over the bounding box: congruent tetrahedra; docs/fitting.md, \"Grid data\")");
  cmd->add_option("--error", r->error,
                  "adaptive refinement (Hua-He-Qin 5.4): split every tetrahedron whose RMS normalised field error is above E (default 0: none)");
  cmd->add_option("--max-tetrahedra", r->max_tetrahedra, "the refinement's tetrahedron budget (default: 8 times the initial domain)");
  cmd->add_option("--seconds", r->seconds, "the refinement's time budget in seconds (default: none)");
  cmd->add_option("--knots", r->knots,
                  "fixed (default), place (place the primary knots again where a first fit's error asks for them: error "
                  "equidistribution, judged on held-out data) or optimise (place, then move the sub-knots of vertices with a "
                  "large 1-ring error: Hua-He-Qin 5.3, Levenberg-Marquardt; slower)");
  cmd->add_option("--placement-rounds", r->placement_rounds,
                  "with --knots place or optimise: rounds of primary-knot placement from the error; the best by the held-out "
                  "error is kept if better than the first fit (default 3; 0: sub-knots only)");
  cmd->add_option("--spacing-ratio", r->spacing_ratio,
                  "with --knots place or optimise: the placed knots' spacing stays within this factor of its median (default 2.5)");
  cmd->add_option("--knot-sweeps", r->knot_sweeps,
                  "with --knots optimise: passes of the local step over the vertices above the error threshold, each followed "
                  "by a refit (default 2; more keep lowering the error, about 0.8 s each on fire_ug)");
  cmd->add_flag("--fixed-primary-knots", r->fixed_primary_knots,
               "with --knots optimise: the local step moves the sub-knots only (by default a primary knot moves with its "
               "sub-knots where that leaves the domain unchanged: inside, within a flat boundary, along a straight edge)");
  cmd->add_flag("--judge-local-step-at-data", r->judge_local_step_at_data,
               "with --knots optimise: keep a sweep of the local step if it lowers the error at the data (by default at the "
               "held-out eighth of the points, fitted to the others; the knots kept are then fitted to all the data)");
  cmd->add_option("--png", r->png, "also write an X-ray picture of the first fitted attribute (.png)");
  cmd->add_option("--stats", r->stats, "write the fit statistics (Hua-He-Qin Table 1 and more) to this JSON file");
  r->fairing_option = cmd->add_option("--fairing", r->fairing,
                  "weight of the fairing term (finite differences of order n+1, zero on polynomials of degree <= n) against "
                  "the data term (default 0.1, 0 with --jump; it damps ringing between the samples next to the boundary; 0: "
                  "none; docs/fitting.md, \"Fairing\")");
  cmd->add_option("--jump", r->jump,
                  "sharp features (Hua-He-Qin 4.2): neighbouring points whose normalised values differ by more than J are on two "
                  "sides of a jump; the surface between them becomes a domain interface with knots on it and no control vector "
                  "shared across it (default 0: off; docs/fitting.md)");
  cmd->add_flag("--baselines", r->baselines,
                "also fit what a user would pick instead and compare: a tensor-product B-spline least-squares fit with as many "
                "coefficients, and trilinear and nearest interpolation for grid data; errors at the data points and, for "
                "generated data, against the true field");
  cmd->callback([r] { run_fit(*r, std::cout); });
}

}  // namespace volspline::cli
