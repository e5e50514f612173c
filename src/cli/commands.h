#pragma once
// The radrecon subcommands; each adds itself to the application and runs when selected.

#include <functional>
#include <initializer_list>
#include <string>

#include <CLI/CLI.hpp>

#include "core/limits.h"

namespace radrecon::cli {

void add_solve_command(CLI::App& app);
void add_paper_command(CLI::App& app);
void add_interpolate_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_cornell_command(CLI::App& app);
void add_export_command(CLI::App& app);

/// Adds the --max-* options of `limits` to a command (core/limits.h, docs/hostile.md).
void add_limit_options(CLI::App& cmd, std::initializer_list<Limit> limits);

/// Bytes this process may still allocate: the physical memory, or less under a limit on its
/// address space (ulimit -v) less what it maps already.
size_t memory_available_bytes();
/// "123 MB", rounded up.
std::string megabytes(double bytes);
/// A picture's size as render and cornell name it: "640x480 pixels at 9 rays each".
std::string picture_size_text(int width, int height, int samples_per_axis);
/// Refuses what `asked` names (a picture: picture_size_text(); a lightmap's texels) needing
/// `needed_bytes` when that exceeds memory_available_bytes(): UserError naming `option`, with
/// `advice`.
void refuse_beyond_memory(const std::string& option, const std::string& asked, double needed_bytes,
                          const std::string& advice);
/// The same, the advice made only when refused, from the bytes available (e.g. the most that fit).
void refuse_beyond_memory(const std::string& option, const std::string& asked, double needed_bytes,
                          const std::function<std::string(double available_bytes)>& advice);

/// A check for an option that takes a positive number of at most `most` (a white point: zero
/// would divide by zero, so it is refused rather than read as "the default").
CLI::Validator positive_at_most(double most);

/// A check for a number option by one of the library's own "why not" functions (empty: fine),
/// e.g. residual_problem(): the option is refused as the library refuses the value elsewhere, NaN
/// included (CLI11's ranges let it through). `description` shows in --help.
CLI::Validator number_check(std::function<std::string(double)> problem, const std::string& description);
/// --residual (solve, paper, cornell): residual_problem()'s values.
CLI::Validator residual_check();
/// --far-field-error: far_field_error_problem()'s values.
CLI::Validator far_field_error_check();

/// Thrown by a command to end the program with `code` (after its output), e.g. compare's 1
/// when a threshold is exceeded.
struct ExitStatus {
  int code;
};

}  // namespace radrecon::cli
