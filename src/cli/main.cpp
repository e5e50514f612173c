// radrecon: radiosity solutions and their reconstruction by scattered data interpolation.

#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/allocator.h"
#include "core/error.h"
#include "io/atomic_file.h"

int main(int argc, char** argv) {
  radrecon::keep_freed_memory();
  radrecon::remove_temporary_files_on_signals();
  CLI::App app{
      "radrecon: computes radiosity on a scene (progressive refinement on regular grids, hierarchical radiosity "
      "on quadtrees) and reconstructs a smooth radiosity function across each patch (bilinear, bicubic, "
      "Shepard, multiquadric, natural neighbour), judged against a fine reference "
      "(after Hinkenjann & Pietrek, \"Reconstructing Radiosity by Scattered Data Interpolation\")."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "radrecon 0.1.0");
  radrecon::cli::add_solve_command(app);
  radrecon::cli::add_paper_command(app);
  radrecon::cli::add_interpolate_command(app);
  radrecon::cli::add_render_command(app);
  radrecon::cli::add_compare_command(app);
  radrecon::cli::add_cornell_command(app);
  radrecon::cli::add_export_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return radrecon::kUserErrorExitCode;
  } catch (const radrecon::cli::ExitStatus& e) {
    return e.code;
  } catch (const radrecon::UserError& e) {
    std::fprintf(stderr, "radrecon: error: %s\n", e.what());
    return radrecon::kUserErrorExitCode;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "radrecon: error: out of memory; no output was left half-written. Ask for less: a smaller raster, image or mesh, "
                 "fewer samples, or local patches (--param k=...)\n");
    return radrecon::kOutOfMemoryExitCode;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "radrecon: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
