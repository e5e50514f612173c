// radrecon export: a solved scene as binary glTF with its reconstructed radiosity baked into a
// lightmap (export/gltf.h), and optionally the same atlas as linear EXR.

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/solution_methods.h"
#include "core/check.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/parse.h"
#include "export/gltf.h"
#include "export/lightmap.h"
#include "io/image_io.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"
#include "render/exposure.h"
#include "scene/side.h"

namespace radrecon::cli {

namespace {

struct ExportArgs {
  std::string scene;  ///< empty: scene_of() the solution
  std::string solution;
  std::string method = "natural-neighbour";
  std::vector<std::string> params;
  int texels = 256;
  double white = 0;
  std::string out;
  std::string exr;
  bool no_barriers = false;
  bool border_samples = false;
  bool quiet = false;
};

/// Bytes that export holds at most for a texel of the atlas: the linear atlas (an Rgb, 24) and
/// beside it, one at a time, the white point's brightest channels (8), the .exr's floats (12), or
/// the PNG's 8-bit texels (3) and their encoding, whose buffer grows by doubling (9 more at worst:
/// a PNG of incompressible texels, one doubling past 3 bytes a texel).
constexpr double kExportBytesPerAtlasTexel = sizeof(Rgb) + 12;
/// Bytes that baking adds beside the atlas whatever its size: the reconstruction's caches filled
/// as texels ask (natural-neighbour's triangulations of visible samples, ~60 MB at most), the
/// worker threads (a stack and a malloc arena each: 72 MB of address space, counted under
/// ulimit -v) and the OpenEXR library. 110-115 MB measured beyond the atlas's at --texels 2048
/// and 4096 with --exr on 2 threads (the smallest ulimit -v that runs; docs/export.md).
constexpr double kExportBytesBesideAtlas = 256e6;

/// The memory export needs for an atlas of `size`, bytes: an upper bound of its peak.
double export_memory_bytes(LightmapSize size) { return kExportBytesPerAtlasTexel * size.texels() + kExportBytesBesideAtlas; }

/// The default white: the kDefaultWhitePercentile-th percentile of the brightest channel of the
/// texels of the sides that emit nothing (the lights would set it far too high); 1 if none is lit.
double lightmap_white(const Scene& scene, const LightmapAtlas& atlas) {
  const auto emits = [&](const LightmapTile& t) {
    return (side_emission(scene.surfaces[t.side.surface], t.side.back_side) > 0).any();
  };
  size_t unlit_texels = 0;
  for (const LightmapTile& t : atlas.tiles)
    if (!emits(t)) unlit_texels += static_cast<size_t>(t.width) * t.height;
  std::vector<double> brightest;  // reserved exactly: 8 bytes a texel (grown by doubling, up to 24)
  brightest.reserve(unlit_texels);
  for (const LightmapTile& t : atlas.tiles) {
    if (emits(t)) continue;
    for (int j = 0; j < t.height; ++j)
      for (int i = 0; i < t.width; ++i) brightest.push_back(atlas.radiosity_w_m2.at(t.x0 + i, t.y0 + j).maxCoeff());
  }
  return percentile_white(brightest, kDefaultWhitePercentile).value_or(1.0);
}

void run_export(const ExportArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  const std::string ext = lower_extension(args.out);
  if (ext != ".glb") throw UserError("--out", "writes binary glTF: give a .glb file (got '" + args.out + "')");
  if (!args.exr.empty()) file_format(args.exr, {FileFormat::exr}, "--exr");
  refuse_overwriting_inputs(args.out, "--out", {args.solution});
  check_output_file(args.out, "--out");
  if (!args.exr.empty()) {
    refuse_overwriting_inputs(args.exr, "--exr", {args.solution});
    check_output_file(args.exr, "--exr");
    refuse_shared_outputs({{"--out", args.out}, {"--exr", args.exr}});  // one would overwrite the other
  }
  parse_params(method_option(args.method), args.params, "--param");  // refused before anything is read
  const Solution solution = read_solution_json(args.solution);
  const std::string scene_spec = scene_of(args.scene, solution);
  const std::vector<std::string> scene_files = scene_input_files(scene_spec);
  refuse_overwriting_inputs(args.out, "--out", scene_files);
  if (!args.exr.empty()) refuse_overwriting_inputs(args.exr, "--exr", scene_files);
  const Scene scene = load_scene(scene_spec);
  const auto recon = noting_the_solutions_scene(scene, solution, scene_spec, !args.scene.empty(), [&] {
    return reconstruct_solution(scene, solution, args.solution, args.method, args.params, args.no_barriers,
                                args.border_samples);
  });
  // The memory, checked before the atlas is made (what the reconstruction holds is mapped by now,
  // so counted under a ulimit -v): refused with the most texels that fit.
  const LightmapSize size = lightmap_size(scene, solution, args.texels, "--texels");
  refuse_beyond_memory("--texels", "the lightmap's " + std::to_string(size.width) + "x" + std::to_string(size.height) + " texels",
                       export_memory_bytes(size), [&](double available_bytes) -> std::string {
                         const int most = most_lightmap_texels_below(scene, solution, args.texels, [&](LightmapSize s) {
                           return export_memory_bytes(s) <= available_bytes;
                         });
                         if (most < 2) return "not even --texels 2 fits; free memory or raise ulimit -v";
                         return "use --texels " + std::to_string(most) + " or fewer";
                       });
  Progress progress("export", args.quiet);
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, *recon, args.texels, "--texels", &progress);
  if (atlas.texels_without_value > 0)
    std::fprintf(stderr,
                 "radrecon: warning: %zu of the %zu texels (%.1f%%) lie where %s gives no value (outside the samples' hull "
                 "with outside=none, beyond a radius, or cut off by barriers); they hold 0 (black)\n",
                 atlas.texels_without_value, atlas.texels,
                 100.0 * static_cast<double>(atlas.texels_without_value) / static_cast<double>(atlas.texels), args.method.c_str());
  const double white = args.white > 0 ? args.white : lightmap_white(scene, atlas);
  const nlohmann::json extras = {{"method", args.method}, {"params", args.params}, {"solution", solution.mesh},
                                 {"scene", solution.scene}};
  progress.note("writing the lightmap (" + std::to_string(atlas.radiosity_w_m2.width()) + " x " +
                std::to_string(atlas.radiosity_w_m2.height()) + " texels) as PNG into " + args.out);
  write_lightmapped_glb(args.out, scene, solution, atlas, white, extras);
  if (!args.exr.empty()) write_exr(args.exr, atlas.radiosity_w_m2);
  progress.done();
  if (!args.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "export: wrote %s (%zu sides, lightmap %dx%d at %.4g texels/m, white %.4g W/m^2%s)%s%s in %.2f s\n",
                 args.out.c_str(), atlas.tiles.size(), atlas.radiosity_w_m2.width(), atlas.radiosity_w_m2.height(),
                 atlas.texels_per_metre, white,
                 args.white > 0 ? ", --white" : ": the 99th percentile of the non-emitting sides' texels",
                 args.exr.empty() ? "" : " and ", args.exr.c_str(), seconds);
  }
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Bake a solution's reconstructed radiosity into a lightmap and write the scene as binary glTF 2.0 (.glb) for "
      "Blender, three.js or a game engine: one mesh per surface side, the lightmap its emissive texture (an sRGB PNG "
      "of clamp(B / white, 0, 1)), so viewers show the baked light as it is. docs/export.md.");
  cmd->add_option("--scene", args->scene, "Scene JSON file, mesh file, or a built-in scene: 'paper' or 'cornell'; default: the solution's scene when it is a built-in one, else 'paper'");
  cmd->add_option("--solution", args->solution, "Solution JSON written by 'radrecon solve' for this scene")->required();
  cmd->add_option("--method", args->method, "Reconstruction method (as render's --method)")->capture_default_str();
  cmd->add_option("--param", args->params, "NAME=VALUE method parameter, repeatable (see 'interpolate --help')");
  cmd->add_option("--texels", args->texels,
                  "Lightmap texels along the scene's longest surface edge; every side gets the same density (texels "
                  "per metre)")
      ->check(CLI::Range(2, kMaxLightmapSide - 2 * kLightmapGutter))  // a tile and its gutters in one texture
      ->capture_default_str();
  cmd->add_option("--white", args->white,
                  "The radiosity (W/m^2) shown as white in the lightmap; default: the 99th percentile of the brightest "
                  "channel of the texels of the surfaces that emit nothing")
      ->check(positive_at_most(1e12));
  cmd->add_option("--out", args->out, "The .glb file to write")->required();
  cmd->add_option("--exr", args->exr, "Also write the lightmap's linear radiosity (W/m^2, same layout) as this .exr file");
  cmd->add_flag("--no-barriers", args->no_barriers, "Ignore the solution's barriers (as render's)");
  cmd->add_flag("--border-samples", args->border_samples, "Add border samples (as render's)");
  cmd->add_flag("--quiet", args->quiet, "No messages but warnings");
  cmd->footer(
      "Example:\n"
      "  radrecon solve --scene cornell --mesh grid:32 --out cornell.json\n"
      "  radrecon export --scene cornell --solution cornell.json --method natural-neighbour --out cornell.glb");
  add_limit_options(*cmd, {Limit::file_bytes});
  cmd->callback([args] { run_export(*args); });
}

}  // namespace radrecon::cli
