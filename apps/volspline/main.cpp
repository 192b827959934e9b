// volspline: the command line. Exit codes: 0 success, 2 bad input or usage, 1 internal failure.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <iostream>
#include <new>
#include <optional>

#include "commands.h"
#include "progress_bar.h"
#include "volspline/core/error.h"
#include "volspline/core/resource_limits.h"
#include "volspline/core/version.h"
#include "volspline/io/atomic_file.h"

namespace {

// Erases the progress bar before anything else is said, then prints an error.
int fail(int code, const std::string& message) {
  volspline::cli::finish_reporting();
  std::cerr << message << "\n";
  return code;
}

// Output written to standard output is part of the result: a failure to write it (a full disk,
// /dev/full, a closed pipe) must not end with exit code 0. `failed_errno` is the error a failed
// write reported, or 0 to find out by flushing.
int check_standard_output(int code, int failed_errno = 0) {
  std::cout.exceptions(std::ios::goodbit);
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  if (failed_errno == 0 && !flushed) failed_errno = errno;
  if (flushed && !std::ferror(stdout) && std::cout.good() && failed_errno == 0) return code;
  std::string reason = failed_errno != 0 ? volspline::write_failure_reason(failed_errno) : "write failed";
  std::fputs(("volspline: error: cannot write standard output: " + reason + "\n").c_str(), stderr);
  return code == 0 ? 2 : code;
}

}  // namespace

int main(int argc, char** argv) {
  // `batch` belongs to the Python module volspline.batch, which parses its own arguments.
  if (const auto code = volspline::cli::run_batch_command(argc, argv)) return *code;
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
  volspline::cli::add_data_command(app);
  volspline::cli::add_demo_command(app);
  volspline::cli::add_batch_command(app);
  auto& flags = volspline::cli::global_flags();
  app.add_option_function<std::string>(
         "--memory-limit", [](const std::string& text) { volspline::set_memory_limit(volspline::parse_byte_count(text, "--memory-limit")); },
         "refuse requests estimated to need more memory than this (such as 8G or 512M; default 4G or $VOLSPLINE_MEMORY_LIMIT); "
         "model files larger than a quarter of it are not read")
      ->type_name("BYTES");
  app.add_option_function<std::string>(
         "--work-limit", [](const std::string& text) { volspline::set_work_limit(volspline::parse_operation_count(text, "--work-limit")); },
         "refuse requests estimated to need more floating-point operations than this (default 1e11, about a minute, "
         "or $VOLSPLINE_WORK_LIMIT)")
      ->type_name("COUNT");
  auto* verbose = app.add_flag("-v,--verbose", flags.verbose, "print the duration of every phase of the work on stderr");
  app.add_flag("-q,--quiet", flags.quiet, "print nothing on stderr but errors (no progress bar, timings or warnings)")
      ->excludes(verbose);
  // The reporter starts its clock once the command line is parsed, before the subcommand runs.
  app.parse_complete_callback([] { volspline::cli::reporter(); });
  app.footer("-v and -q may also follow the subcommand. Long work shows a progress bar on stderr when it is a terminal.\n"
             "Exit codes: 0 success, 2 bad input or usage, 1 internal failure.");
  // Every file a command writes waits as a temporary file until the command has succeeded; then
  // all are renamed together (io/atomic_file.h). SIGINT and SIGTERM remove the temporary files.
  volspline::remove_temporary_files_on_signals();
  std::optional<volspline::OutputTransaction> outputs;
  outputs.emplace();
  std::cout.exceptions(std::ios::badbit);
  try {
    volspline::cli::remember_command_line(argc, argv);
    app.parse(argc, argv);
    // Standard output is checked first: a command whose printed result was lost has failed, and
    // its files are not committed either.
    if (const int code = check_standard_output(0); code != 0) {
      outputs.reset();
      volspline::cli::finish_reporting();
      return code;
    }
    outputs->commit();
    volspline::cli::finish_reporting();
  } catch (const CLI::CallForHelp& e) {
    std::cout.exceptions(std::ios::goodbit);
    return check_standard_output(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    std::cout.exceptions(std::ios::goodbit);
    return check_standard_output(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    std::cout.exceptions(std::ios::goodbit);
    return check_standard_output(app.exit(e));
  } catch (const volspline::cli::ExitCode& e) {
    // A deliberate exit code (jacobian --fail) after the work was done: its outputs stand.
    try {
      outputs->commit();
    } catch (const volspline::Error& commit_error) {
      return fail(2, std::string("volspline: error: ") + commit_error.what());
    }
    volspline::cli::finish_reporting();
    return check_standard_output(e.code);
  } catch (const CLI::ParseError& e) {
    volspline::cli::finish_reporting();
    std::cout.exceptions(std::ios::goodbit);
    app.exit(e);  // prints the message and usage hint to stderr
    return 2;
  } catch (const std::ios_base::failure& e) {
    const int error = errno;
    outputs.reset();
    if (!std::cout.bad()) return fail(1, std::string("volspline: internal error: ") + e.what());
    volspline::cli::finish_reporting();
    return check_standard_output(2, error != 0 ? error : EIO);
  } catch (const volspline::InvalidInput& e) {
    return fail(2, std::string("volspline: error: ") + e.what());
  } catch (const volspline::IoError& e) {
    return fail(2, std::string("volspline: error: ") + e.what());
  } catch (const std::bad_alloc&) {
    return fail(1, "volspline: internal error: out of memory");
  } catch (const std::exception& e) {
    return fail(1, std::string("volspline: internal error: ") + e.what());
  }
  return check_standard_output(0);
}
