#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "mesh/grid_mesh.h"
#include "solver/progressive.h"
#include "solver/solution_io.h"

namespace radrecon::cli {

namespace {

struct SolveArgs {
  std::string scene = "paper";
  std::string mesh = "grid:16";
  std::string out;
  double residual = 1e-4;
  int patches = 2;
  bool quiet = false;
};

int parse_positive_int(const std::string& text, const std::string& field) {
  size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || used == 0 || v < 1 || v > 100000)
    throw UserError(field, "expected an integer in [1, 100000], got '" + text + "'");
  return static_cast<int>(v);
}

void run_solve(const SolveArgs& args) {
  const Scene scene = load_scene(args.scene);
  const auto colon = args.mesh.find(':');
  const std::string kind = args.mesh.substr(0, colon);
  if (colon == std::string::npos)
    throw UserError("--mesh", "expected grid:N, quadtree:LEAVES or quadtree-eps:E, got '" + args.mesh + "'");
  if (kind == "quadtree" || kind == "quadtree-eps")
    throw UserError("--mesh", "hierarchical radiosity on quadtrees is not implemented yet");
  if (kind != "grid")
    throw UserError("--mesh", "unknown mesh kind '" + kind + "' (expected grid, quadtree or quadtree-eps)");
  const int n = parse_positive_int(args.mesh.substr(colon + 1), "--mesh grid:N");
  const Mesh mesh = make_grid_mesh(scene, GridMeshOptions{n, args.patches});
  if (!args.quiet)
    std::fprintf(stderr, "solve: %s, %zu elements on %zu surface sides\n", args.mesh.c_str(), mesh.element_count(),
                 mesh.surfaces.size());
  ProgressiveOptions po;
  po.residual = args.residual;
  po.progress_label = args.quiet ? "" : "solve";
  const Solution sol = solve_progressive(scene, mesh, po, "grid:" + std::to_string(n));
  write_solution_json(args.out, sol);
  if (!args.quiet) std::fprintf(stderr, "solve: wrote %s\n", args.out.c_str());
}

}  // namespace

void add_solve_command(CLI::App& app) {
  auto args = std::make_shared<SolveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Solve the radiosity of a scene by progressive refinement and write the solution as JSON "
      "(per surface side: elements with their (u,v) rectangle, centre, area and radiosity in W/m^2).");
  cmd->add_option("--scene", args->scene, "Scene JSON file, or 'paper' for the built-in scene")
      ->capture_default_str();
  cmd->add_option("--mesh", args->mesh,
                  "grid:N = N elements along the longest surface edge of the scene, the other surfaces "
                  "with elements of the same size (capped by a surface's mesh.max_divisions)")
      ->capture_default_str();
  cmd->add_option("--out", args->out, "Solution file to write (JSON)")->required();
  cmd->add_option("--residual", args->residual,
                  "Stop when the unshot power falls below this fraction of the emitted power")
      ->check(CLI::Range(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--patches", args->patches,
                  "Shooting patches along the longest edge (patches group elements; receivers are elements)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  cmd->callback([args] { run_solve(*args); });
}

}  // namespace radrecon::cli
