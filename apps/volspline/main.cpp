// volspline: the command line. Exit codes: 0 success, 2 bad input or usage, 1 internal failure.
#include <CLI/CLI.hpp>

#include <iostream>
#include <new>

#include "commands.h"
#include "volspline/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{"volspline: free-form trivariate spline solids", "volspline"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "volspline 0.1.0");
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
  volspline::cli::add_demo_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const volspline::cli::ExitCode& e) {
    return e.code;
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and usage hint to stderr
    return 2;
  } catch (const volspline::InvalidInput& e) {
    std::cerr << "volspline: error: " << e.what() << "\n";
    return 2;
  } catch (const volspline::IoError& e) {
    std::cerr << "volspline: error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "volspline: internal error: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "volspline: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
