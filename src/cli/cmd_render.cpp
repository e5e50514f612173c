#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "experiment/solution_reconstruction.h"
#include "render/ground_map.h"
#include "render/renderer.h"
#include "solver/solution_io.h"

namespace radrecon::cli {

namespace {

struct RenderArgs {
  std::string scene = "paper";
  std::string solution;
  std::string method = "constant";
  std::vector<std::string> params;
  std::string camera;
  std::string size = "640x480";
  int samples = 3;
  double white = 0;
  std::string out;
  bool quiet = false;
};

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 || h < 1 || w > 8192 || h > 8192)
    throw UserError("--size", "expected WxH with 1 <= W, H <= 8192, got '" + text + "'");
  return {w, h};
}

void run_render(const RenderArgs& args) {
  std::string ext = args.out.size() >= 4 ? args.out.substr(args.out.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".png" && ext != ".pfm" && ext != ".exr")
    throw UserError("--out", "must end in .png (tone-mapped), .pfm or .exr (linear W/m^2)");
  const auto [width, height] = parse_size(args.size);
  const Scene scene = load_scene(args.scene);
  const Camera* camera = nullptr;
  for (const Camera& c : scene.cameras)
    if (c.name == args.camera) camera = &c;
  if (!camera) {
    std::string names;
    for (const Camera& c : scene.cameras) names += (names.empty() ? "" : ", ") + c.name;
    throw UserError("--camera", "the scene has no camera '" + args.camera + "' (cameras: " + (names.empty() ? "none" : names) + ")");
  }
  const auto method = parse_method(args.method);
  if (!method) throw UserError("--method", "unknown method '" + args.method + "'");
  const MethodParams params = parse_params(*method, args.params, "--param");
  const Solution solution = read_solution_json(args.solution);
  const SolutionReconstruction recon(scene, solution, *method, params, args.solution);
  for (const std::string& side : recon.fallbacks())
    std::fprintf(stderr, "radrecon: warning: %s cannot be reconstructed by %s; drawn piecewise constant\n", side.c_str(),
                 args.method.c_str());
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples_per_axis = args.samples;
  const Image img = render(scene, *camera, [&](size_t s, bool back) { return recon.side(s, back); }, options);
  if (ext == ".pfm") {
    write_pfm(args.out, img);
  } else if (ext == ".exr") {
    write_exr(args.out, img);
  } else {
    double white = args.white;
    if (white <= 0) {  // default: the largest radiosity of a reflecting surface in the solution
      for (const SurfaceSolution& s : solution.surfaces) {
        const auto idx = scene.find_surface(s.scene_surface);
        if (idx && (scene.surfaces[*idx].emission_w_m2 > 0).any()) continue;
        for (const SolutionElement& e : s.elements) white = std::max(white, e.radiosity_w_m2.maxCoeff());
      }
      if (white <= 0) white = 1;
    }
    Image display(img.width(), img.height());
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x)
        for (int c = 0; c < 3; ++c) display.at(x, y)[c] = tone_map(img.at(x, y)[c], white);
    write_png(args.out, display, true);
  }
  if (!args.quiet) std::fprintf(stderr, "render: wrote %s (%dx%d, %d rays per pixel)\n", args.out.c_str(), width, height, args.samples * args.samples);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a solution seen through one of the scene's cameras, every surface reconstructed by one method. "
      "PNG: tone-mapped, display = clamp(B / white, 0, 1) with the sRGB curve; PFM, EXR: linear radiosity, W/m^2.");
  cmd->add_option("--scene", args->scene, "Scene JSON file, or 'paper'")->capture_default_str();
  cmd->add_option("--solution", args->solution, "Solution JSON written by 'radrecon solve'")->required();
  cmd->add_option("--method", args->method,
                  "constant, bilinear, bicubic (grid solutions), shepard, multiquadric, natural-neighbour")
      ->capture_default_str();
  cmd->add_option("--param", args->params, "NAME=VALUE method parameter, repeatable (see 'interpolate --help')");
  cmd->add_option("--camera", args->camera, "Name of a camera of the scene (paper: view, closeup)")->required();
  cmd->add_option("--size", args->size, "Image size WxH in pixels")->capture_default_str();
  cmd->add_option("--samples", args->samples, "Stratified rays per pixel along each axis (N x N rays)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->add_option("--white", args->white,
                  "PNG: the radiosity (W/m^2) shown as white; default: the largest radiosity of a non-emitting surface")
      ->check(CLI::Range(0.0, 1e12));
  cmd->add_option("--out", args->out, "Image to write: .png (tone-mapped), .pfm or .exr (linear radiosity, W/m^2)")->required();
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace radrecon::cli
