#pragma once
// The subcommands of the command line, one file each. A subcommand parses its arguments, calls
// the library and prints; no mathematics lives here.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>

namespace volspline::cli {

/// Thrown by a subcommand that finished its work but must end with a particular exit code
/// (for example `jacobian --fail-invalid`).
struct ExitCode {
  int code;
};

void add_info_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_faces_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_make_command(CLI::App& app);
/// `make swept-solid` (make_swept_solid.cpp), added by add_make_command.
void add_make_swept_solid_kind(CLI::App* make);
/// `make simplex-spline` (make_simplex_spline.cpp), added by add_make_command.
void add_make_simplex_spline_kind(CLI::App* make);
void add_xray_command(CLI::App& app);
void add_split_tetrahedron_command(CLI::App& app);
void add_ffd_command(CLI::App& app);
void add_lattice_command(CLI::App& app);
void add_jacobian_command(CLI::App& app);
void add_boundary_command(CLI::App& app);
void add_blend_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_sweep_envelope_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_data_command(CLI::App& app);
void add_batch_command(CLI::App& app);
/// `volspline [global options] batch ...` (batch.cpp): replaces this process by the Python module
/// volspline.batch, or returns the exit code of an error (2); nullopt for any other command.
std::optional<int> run_batch_command(int argc, char** argv);

class DemoRun;
/// Writes the boundary-determination examples of `demo` (those it wants) and adds them to its gallery.
void write_boundary_demo(DemoRun& demo);
/// Where the simplex-spline examples of `demo` find their input files.
struct SimplexDemoInputs {
  /// The repository's examples/ (torus-surface.off, skeletons/).
  std::filesystem::path examples = "examples";
  /// The shared data folder holding volumes/bunny00.off (Fig. 6 is skipped without it).
  std::filesystem::path data = "../shared/data";
};
/// The simplex-spline examples of `demo` (demo_simplex.cpp): Hua-He-Qin Figs. 1, 5 and 6.
void write_simplex_demo(DemoRun& demo, const SimplexDemoInputs& inputs);
/// Fitting volume data (demo_fitting.cpp): fire_ug's temperature (skipped without the data
/// folder), Marschner–Lobb's isosurface against the formula's, a jump with fixed and aligned knots.
void write_fitting_demo(DemoRun& demo, const SimplexDemoInputs& inputs);
/// Conkey–Joy Figs. 4-8: swept solids' envelopes, superset beside trimmed (demo_sweeps.cpp).
void write_sweeps_demo(DemoRun& demo, const std::filesystem::path& examples);

}  // namespace volspline::cli
