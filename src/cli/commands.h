#pragma once
// The radrecon subcommands; each adds itself to the application and runs when selected.

#include <CLI/CLI.hpp>

namespace radrecon::cli {

void add_solve_command(CLI::App& app);
void add_paper_command(CLI::App& app);
void add_interpolate_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_cornell_command(CLI::App& app);
void add_export_command(CLI::App& app);

/// Thrown by a command to end the program with `code` (after its output), e.g. compare's 1
/// when a threshold is exceeded.
struct ExitStatus {
  int code;
};

}  // namespace radrecon::cli
