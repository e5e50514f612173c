#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "solver/solve.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"

namespace radrecon::cli {

namespace {

struct SolveArgs {
  std::string scene = "paper";
  std::string mesh = "grid:" + std::to_string(GridMeshOptions{}.divisions);
  std::string out;
  double residual = kDefaultResidual;
  int patches = SolveSettings{}.patches;
  double far_field_error = kDefaultFarFieldError;
  std::string clusters = "on";
  std::string leaves_on;
  bool shadow_barriers = false;
  bool quiet = false;
};

void run_solve(const SolveArgs& args, const CLI::App& cmd) {
  // Options that only one kind of mesh uses are refused with the other, not silently ignored.
  std::vector<std::string> grid_only_given;
  for (const char* option : {"--residual", "--patches", "--far-field-error", "--clusters"})
    if (cmd.count(option) > 0) grid_only_given.emplace_back(option);
  refuse_unused_options(args.mesh, grid_only_given, cmd.count("--leaves-on") > 0 ? "--leaves-on" : "");
  refuse_overwriting_inputs(args.out, "--out", scene_input_files(args.scene));
  check_output_file(args.out, "--out");
  const Scene scene = load_scene(args.scene);
  SolveSettings settings;
  settings.residual = args.residual;
  settings.patches = args.patches;
  settings.far_field_error = args.far_field_error;
  settings.clusters = args.clusters == "on";
  settings.leaves_on = args.leaves_on;
  settings.leaves_on_where = "--leaves-on";
  settings.progress_label = args.quiet ? "" : "solve";
  settings.shadow_barriers = args.shadow_barriers;
  const Solution sol = solve_scene(scene, args.mesh, settings, "--mesh");
  if (!args.quiet) {
    // Where the power went, summed over the channels (the file has them per channel).
    const SolveStats& st = sol.stats;
    const double emitted = st.emitted_w.sum();
    if (emitted > 0)
      std::fprintf(stderr, "solve: of %.4g W emitted, %.1f%% absorbed, %.2g%% unshot, %.2g%% escaped (left the scene through "
                           "an opening or onto a surface's back, or lost to discretisation; stats in the file)\n",
                   emitted, 100 * st.absorbed_w.sum() / emitted, 100 * st.unshot_w.sum() / emitted,
                   100 * st.escaped_w.sum() / emitted);
  }
  write_solution_json(args.out, sol);
  if (!args.quiet) std::fprintf(stderr, "solve: wrote %s\n", args.out.c_str());
}

}  // namespace

void add_solve_command(CLI::App& app) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Solve the radiosity of a scene, by progressive refinement on regular grids (grid:N) or by hierarchical "
      "radiosity on quadtrees (quadtree:LEAVES, quadtree-eps:E), and write the solution as JSON (per surface "
      "side: elements with their (u,v) rectangle, centre, area and radiosity in W/m^2). Missing output folders "
      "are created.");
  cmd->add_option("--scene", args->scene, "Scene JSON file, model file (.obj .gltf .glb .ply with an emitting face; docs/formats.md, Meshes), or a built-in scene: 'paper' (the paper experiment) or 'cornell' (the Cornell box, docs/cornell.md)")
      ->capture_default_str();
  cmd->add_option("--mesh", args->mesh,
                  "grid:N: progressive refinement, elements of 1/N of the scene's longest surface extent (a quad's longer "
                  "mean edge, a triangle's longest edge), "
                  "on every surface (a triangle's cells about as wide as a square's diagonal; capped by a surface's "
                  "mesh.max_divisions); "
                  "quadtree-eps:E: hierarchical radiosity, links refined while their error estimate (the power they may carry wrongly) exceeds E watts; "
                  "quadtree:LEAVES: hierarchical radiosity with exactly LEAVES (= 1 + 3k) leaves on one side "
                  "(see --leaves-on)")
      ->capture_default_str();
  cmd->add_option("--leaves-on", args->leaves_on,
                  "Surface side that quadtree:LEAVES counts (default: 'ground' if present, else 'floor', else the largest surface)");
  cmd->add_option("--out", args->out, "Solution file to write (JSON)")->required();
  cmd->add_option("--residual", args->residual,
                  "grid: stop when the unshot power falls below this fraction of the emitted power")
      ->check(residual_check())
      ->capture_default_str();
  cmd->add_option("--patches", args->patches,
                  "grid: shooting patches along the longest edge (patches group elements; receivers are elements); "
                  "default 4, the fastest for the Cornell box and a model of 11,000 triangles, and within the "
                  "noise of the fastest (3) for the paper scene (docs/benchmarks.md)")
      ->check(CLI::Range(1, kMostPatches));
  cmd->add_option("--far-field-error", args->far_field_error,
                  "grid: a block of a shooting patch shoots as one source only while its error estimate is at most "
                  "this fraction of the receiver's irradiance; 0: beyond 2.5 of its diagonals instead, with no "
                  "bound (docs/method.md)")
      ->check(far_field_error_check())
      ->capture_default_str();
  cmd->add_option("--clusters", args->clusters,
                  "grid: with 256 or more sides of one element (a model's triangles), shoot them in clusters of up "
                  "to 256, each subtree far from a receiver as its sides' sources past one shadow ray to its "
                  "centre, a side near it with exact shadows (on), or each alone with exact shadows (off; "
                  "docs/method.md)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_flag("--shadow-barriers", args->shadow_barriers,
                "Also list the direct light's D1/D2 lines (umbra and penumbra boundaries cast by occluder edges) "
                "among each side's barriers; experimental (docs/method.md)");
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  add_limit_options(*cmd, {Limit::elements, Limit::leaves, Limit::links, Limit::file_bytes});
  cmd->callback([args, cmd] { run_solve(*args, *cmd); });
}

}  // namespace radrecon::cli
