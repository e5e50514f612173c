#include "cli/commands.h"
#include "paper/paper.h"

namespace radrecon::cli {

void add_paper_command(CLI::App& app) {
  auto opt = std::make_shared<PaperOptions>();
  auto out = std::make_shared<std::string>(opt->out_dir.string());
  auto quiet = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "paper",
      "Run the whole paper experiment on the built-in scene: the 400x400 reference, the 16x16 grid data and "
      "the 286-leaf quadtree data (hierarchical radiosity), every reconstruction method, Tables 1 and 2 and the "
      "figures; and the same data with the scene's barriers (the walls' feet on the ground): Table 3.");
  cmd->add_option("--out", *out, "Output folder")->capture_default_str();
  cmd->add_option("--reference", opt->reference_divisions, "Reference grid on the ground (elements per edge)")
      ->check(CLI::Range(16, 2000))
      ->capture_default_str();
  cmd->add_option("--residual", opt->residual, "Progressive refinement stops below this unshot fraction")
      ->check(residual_check())
      ->capture_default_str();
  auto no_barriers = std::make_shared<bool>(false);
  CLI::Option* skip = cmd->add_flag("--no-barriers", *no_barriers,
                                     "Skip the data sets with the scene's barriers (grid+barriers, quadtree+barriers: "
                                     "Table 3, Fig. 5 and 6)");
  // Both act on Table 3's data sets, which --no-barriers leaves out: refused together, not ignored.
  cmd->add_flag("--border-samples", opt->border_samples,
                "Table 3 also with border samples (grid+barriers+border, quadtree+barriers+border: Fig. 7 and 8)")
      ->excludes(skip);
  cmd->add_flag("--shadow-barriers", opt->shadow_barriers,
                "Table 3 with the direct light's D1/D2 lines among the barriers too (an experiment; "
                "docs/method.md)")
      ->excludes(skip);
  cmd->add_flag("--quiet", *quiet, "No progress messages");
  cmd->callback([opt, out, quiet, no_barriers] {
    opt->out_dir = *out;
    opt->barriers = !*no_barriers;
    opt->progress = !*quiet;
    run_paper(*opt, "--out");
  });
}

}  // namespace radrecon::cli
