// volspline: the command line. Exit codes: 0 success, 2 bad input or usage, 1 internal failure.
#include <CLI/CLI.hpp>

#include <iostream>
#include <new>

#include "commands.h"
#include "progress_bar.h"
#include "volspline/core/error.h"
#include "volspline/core/version.h"

namespace {

// Erases the progress bar before anything else is said, then prints an error.
int fail(int code, const std::string& message) {
  volspline::cli::finish_reporting();
  std::cerr << message << "\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"volspline: free-form trivariate spline solids", "volspline"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("volspline ") + volspline::kVersion);
  // Options a subcommand does not know fall through to this app, so the global flags below are
  // accepted before and after the subcommand: `volspline -v boundary ...`, `volspline boundary ... -v`.
  // (Inherited by the subcommands added after this line.)
  app.fallthrough();
  volspline::cli::add_info_command(app);
  volspline::cli::add_eval_command(app);
  volspline::cli::add_convert_command(app);
  volspline::cli::add_faces_command(app);
  volspline::cli::add_make_command(app);
  volspline::cli::add_ffd_command(app);
  volspline::cli::add_lattice_command(app);
  volspline::cli::add_jacobian_command(app);
  volspline::cli::add_boundary_command(app);
  volspline::cli::add_blend_command(app);
  volspline::cli::add_view_command(app);
  volspline::cli::add_sweep_envelope_command(app);
  volspline::cli::add_xray_command(app);
  volspline::cli::add_split_tetrahedron_command(app);
  volspline::cli::add_fit_command(app);
  volspline::cli::add_demo_command(app);
  auto& flags = volspline::cli::global_flags();
  auto* verbose = app.add_flag("-v,--verbose", flags.verbose, "print the duration of every phase of the work on stderr");
  app.add_flag("-q,--quiet", flags.quiet, "print nothing on stderr but errors (no progress bar, timings or warnings)")
      ->excludes(verbose);
  // The reporter starts its clock once the command line is parsed, before the subcommand runs.
  app.parse_complete_callback([] { volspline::cli::reporter(); });
  app.footer("-v and -q may also follow the subcommand. Long work shows a progress bar on stderr when it is a terminal.\n"
             "Exit codes: 0 success, 2 bad input or usage, 1 internal failure.");
  try {
    app.parse(argc, argv);
    volspline::cli::finish_reporting();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const volspline::cli::ExitCode& e) {
    volspline::cli::finish_reporting();
    return e.code;
  } catch (const CLI::ParseError& e) {
    volspline::cli::finish_reporting();
    app.exit(e);  // prints the message and usage hint to stderr
    return 2;
  } catch (const volspline::InvalidInput& e) {
    return fail(2, std::string("volspline: error: ") + e.what());
  } catch (const volspline::IoError& e) {
    return fail(2, std::string("volspline: error: ") + e.what());
  } catch (const std::bad_alloc&) {
    return fail(1, "volspline: internal error: out of memory");
  } catch (const std::exception& e) {
    return fail(1, std::string("volspline: internal error: ") + e.what());
  }
  return 0;
}
