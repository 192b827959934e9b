#pragma once
// The subcommands of the command line, one file each. A subcommand parses its arguments, calls
// the library and prints; no mathematics lives here.
#include <CLI/CLI.hpp>

namespace volspline::cli {

void add_info_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_faces_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_make_command(CLI::App& app);
void add_ffd_command(CLI::App& app);
void add_lattice_command(CLI::App& app);
void add_blend_command(CLI::App& app);

}  // namespace volspline::cli
