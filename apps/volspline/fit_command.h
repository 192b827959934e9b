#pragma once
// The arguments of `volspline fit`, shared with `demo`, whose gallery shows the fit commands
// that make its pictures: the demo runs what the command runs.
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "volspline/simplex/adaptive_refinement.h"
#include "volspline/simplex/volume_fitting.h"

namespace volspline::cli {

struct FitArguments {
  std::string data, out, attributes, stats, png;
  int degree = 2;
  int primary_knots = 0;
  double error = 0;
  long long max_tetrahedra = 0;
  double seconds = 0;
  std::string knots = "fixed";
  bool baselines = false;
  double fairing = ControlVectorFitOptions{}.fairing;
  /// --fairing given (on the command line: fairing_option counts it).
  bool fairing_given = false;
  CLI::Option* fairing_option = nullptr;
  double jump = 0;
  std::string layout = "auto";
  int placement_rounds = KnotOptimisationOptions{}.placement_rounds;
  double spacing_ratio = KnotOptimisationOptions{}.spacing_ratio;
  bool fixed_primary_knots = false;
  bool judge_local_step_at_data = false;
  int knot_sweeps = KnotOptimisationOptions{}.sweeps;
};

/// Does what `volspline fit` does with these arguments, reporting to `out` (warnings to stderr).
/// \throw InvalidInput / IoError as the command reports them.
void run_fit(const FitArguments& arguments, std::ostream& out);

}  // namespace volspline::cli
