// radrecon: radiosity solutions and their reconstruction by scattered data interpolation.

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <exception>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/allocator.h"
#include "core/error.h"
#include "core/parse.h"
#include "io/atomic_file.h"

namespace {

/// Whether this CPU runs the instruction set the program was built for (CMake RADRECON_ARCH):
/// else it would die of an illegal instruction somewhere; it says so instead. Best effort: a
/// static initialiser, run before main(), could still meet such an instruction first.
bool cpu_runs_this_build() {
#if defined(__x86_64__)
  __builtin_cpu_init();
#if defined(__AVX512F__)
  if (!__builtin_cpu_supports("avx512f") || !__builtin_cpu_supports("avx512bw") ||
      !__builtin_cpu_supports("avx512dq") || !__builtin_cpu_supports("avx512vl"))
    return false;
#endif
#if defined(__AVX2__)
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return false;
#endif
#endif
  return true;
}

}  // namespace

namespace {

/// The words CLI11 could not place, worded as every refusal is ("radrecon: error: WHERE: WHAT"),
/// those before the command radrecon's own, those after it the command's; CLI11's own `what`
/// when there are none. `missing`: a required option or command CLI11 found missing ("" if
/// none), said after them (a misspelt option leaves the one it meant missing), or alone when
/// nothing is misspelt. Returns the exit code.
int refuse_extras(const CLI::App& app, const std::string& what, std::string missing) {
  std::vector<std::string> extras = app.remaining(false);
  std::string command = "radrecon";
  if (extras.empty())
    for (const CLI::App* sub : app.get_subcommands()) {
      command += " " + sub->get_name();
      extras = sub->remaining(false);
    }
  std::string words;
  for (const std::string& word : extras) words += (words.empty() ? "" : " ") + word;
  if (words.empty() && !missing.empty()) {
    std::fprintf(stderr, "radrecon: error: %s\nRun with --help for more information.\n", missing.c_str());
    return radrecon::kUserErrorExitCode;
  }
  if (words.empty()) words = what;
  if (missing.size() > 1 && std::isupper(static_cast<unsigned char>(missing[0])) &&
      !std::isupper(static_cast<unsigned char>(missing[1])))
    missing[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(missing[0])));  // "A subcommand ..."
  std::fprintf(stderr, "radrecon: error: %s: not an option or argument of '%s' ('%s --help' lists them)%s\n", words.c_str(),
               command.c_str(), command.c_str(), missing.empty() ? "" : ("; and " + missing).c_str());
  return radrecon::kUserErrorExitCode;
}

/// Checks on every option's text before CLI11 converts it or any check of the command's own
/// runs, each refusal worded as every refusal is ("radrecon: error: --opt: ..."): an empty value,
/// which would otherwise mean the default silently (--barriers "$UNSET" ran without barriers);
/// and a number option's text that is no number at all (CLI11's words, "Could not convert:
/// --nodata = abc" or "Value abc not in range 1 to 100000", name no rule), or one that is not
/// decimal ("0x10", which CLI11 read as 16). A number out of an option's range, or a fraction for
/// a count, is left to the option's own check; so are nan and inf.
void check_option_texts(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* option : command->get_options()) {
      if (option->get_type_size() == 0) continue;  // a flag
      const std::string type = option->get_type_name();
      const bool whole = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
      if (whole || type.rfind("FLOAT", 0) == 0)
        option->transform(CLI::Validator(
            [whole](std::string& text) {
              double number = 0;
              if (text.empty()) return std::string();
              if (!CLI::detail::lexical_cast(text, number)) return "must be a number, got '" + text + "'";
              // CLI11 reads C's forms too, a hexadecimal "0x10" as 16 and " 4" as 4: decimal alone,
              // as radrecon reads numbers everywhere (core/parse.h); nan and inf pass to the option's
              // own check.
              double decimal = 0;
              if (radrecon::parse_double(text, decimal) == radrecon::NumberStatus::not_a_number)
                return "must be a decimal number, got '" + text + "'";
              if (!whole) return std::string();
              // CLI11 said "Value 2.5 not in range 1 to 16", and the same of "3.0" and "1e1".
              if (!std::isfinite(number) || number != std::floor(number)) return "must be a whole number, got '" + text + "'";
              if (std::abs(number) < 1e18) text = std::to_string(static_cast<long long>(number));  // "3.0", "1e1": their digits
              return std::string();
            },
            ""));
      // transform() puts a check first: this one runs before the number's.
      const bool has_default = !option->get_required() && option->nonpositional();
      option->transform(CLI::Validator(
          [has_default](std::string& text) {
            if (!text.empty()) return std::string();
            return std::string("must not be empty") + (has_default ? " (leave the option out for its default)" : "");
          },
          ""));
    }
}

/// Whether what the command printed on stdout (compare's figures) reached it: a full disk,
/// /dev/full or a closed stdout show only when the buffer is written, here if not before. Says so
/// if not. Not for --help and --version, whose output is CLI11's.
bool stdout_written() {
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int error = errno;
  if (flushed && !std::ferror(stdout)) return true;
  const std::string said = error != 0 ? radrecon::output_error("standard output", error).what()
                                      : std::string("standard output: cannot write");
  std::fprintf(stderr, "radrecon: error: %s\n", said.c_str());
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (!cpu_runs_this_build()) {
    std::fprintf(stderr,
                 "radrecon: error: this build uses instructions this CPU lacks (built with -march for %s); "
                 "rebuild here, or with cmake -DRADRECON_ARCH=x86-64-v3 (any AVX2 CPU) or -DRADRECON_ARCH= (any x86-64)\n",
#if defined(__AVX512F__)
                 "AVX-512"
#else
                 "AVX2"
#endif
    );
    return radrecon::kUserErrorExitCode;
  }
  radrecon::keep_freed_memory();
  radrecon::remove_temporary_files_on_signals();
  // A file-size limit (ulimit -f) met by a write: the write fails with EFBIG, which every writer
  // reports and cleans up after, instead of SIGXFSZ ending the process silently with the
  // temporary files left. The command line only: the Python module leaves its host's signals be.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "radrecon: computes radiosity on a scene (progressive refinement on regular grids, hierarchical radiosity "
      "on quadtrees) and reconstructs a smooth radiosity function across each patch (bilinear, bicubic, "
      "Shepard, multiquadric, natural neighbour), judged against a fine reference "
      "(after Hinkenjann & Pietrek, \"Reconstructing Radiosity by Scattered Data Interpolation\")."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "radrecon 0.1.0");
  // A run that names its command first builds that one alone: building every command's options,
  // validators and help texts is a millisecond of start-up (docs/benchmarks.md). Anything else
  // (--help, --version, no command, a misspelt one) gets them all.
  struct Command {
    std::string_view name;
    void (*add)(CLI::App&);
  };
  namespace cli = radrecon::cli;
  constexpr std::array<Command, 7> kCommands = {{{"solve", cli::add_solve_command},
                                                 {"paper", cli::add_paper_command},
                                                 {"interpolate", cli::add_interpolate_command},
                                                 {"render", cli::add_render_command},
                                                 {"compare", cli::add_compare_command},
                                                 {"cornell", cli::add_cornell_command},
                                                 {"export", cli::add_export_command}}};
  const std::string_view first = argc > 1 ? argv[1] : "";
  const auto named = std::find_if(kCommands.begin(), kCommands.end(), [&](const Command& c) { return c.name == first; });
  if (named != kCommands.end()) named->add(app);
  else
    for (const Command& c : kCommands) c.add(app);
  check_option_texts(app);
  if (named == kCommands.end() && !first.empty() && first.front() != '-') {
    // A misspelt command with --help after it would otherwise print the general help and exit 0.
    std::string names;
    for (const Command& c : kCommands) names += (names.empty() ? "" : ", ") + std::string(c.name);
    std::fprintf(stderr, "radrecon: error: %.*s: not a command; the commands are %s ('radrecon --help' says what each does)\n",
                 static_cast<int>(first.size()), first.data(), names.c_str());
    return radrecon::kUserErrorExitCode;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    return refuse_extras(app, e.what(), "");
  } catch (const CLI::RequiredError& e) {
    // A misspelt option (--ouy) leaves the one it meant missing: the misspelling first.
    return refuse_extras(app, "", e.what());
  } catch (const CLI::ParseError& e) {
    // As every refusal is worded (docs/cli.md): "radrecon: error: WHERE: WHAT".
    std::fprintf(stderr, "radrecon: error: %s\nRun with --help for more information.\n", e.what());
    return radrecon::kUserErrorExitCode;
  } catch (const radrecon::cli::ExitStatus& e) {
    return stdout_written() ? e.code : radrecon::kUserErrorExitCode;
  } catch (const radrecon::UserError& e) {
    std::fprintf(stderr, "radrecon: error: %s\n", e.what());
    return radrecon::kUserErrorExitCode;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "radrecon: error: out of memory; no output was left half-written. Ask for less: a smaller raster, image, "
                 "lightmap (--texels) or mesh, fewer samples, or local patches (--param k=...)\n");
    return radrecon::kOutOfMemoryExitCode;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "radrecon: error: %s\n", e.what());
    return 1;
  }
  return stdout_written() ? 0 : radrecon::kUserErrorExitCode;
}
