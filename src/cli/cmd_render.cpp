#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "sampling/solution_reconstruction.h"
#include "render/renderer.h"
#include "core/parse.h"
#include "io/image_io.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"

namespace radrecon::cli {

namespace {

struct RenderArgs {
  std::string scene = "paper";
  std::string solution;
  std::string method = "constant";
  std::vector<std::string> params;
  std::string camera;
  std::string size = std::to_string(RenderOptions{}.width) + "x" + std::to_string(RenderOptions{}.height);
  int samples = RenderOptions{}.samples_per_axis;
  double white = 0;
  std::string out;
  bool no_barriers = false;
  bool border_samples = false;
  bool quiet = false;
};

/// Largest width or height of a rendered image, pixels.
constexpr int kMaxImageSide = 8192;
/// At most this many pixels: the linear and the display image take 24 bytes a pixel each.
constexpr long long kMaxImagePixels = static_cast<long long>(kMaxImageSide) * kMaxImageSide;

void run_render(const RenderArgs& args) {
  const FileFormat format = file_format(args.out, {FileFormat::png, FileFormat::pfm, FileFormat::exr}, "--out");
  const auto [width, height] = parse_size(args.size, "--size", kMaxImageSide, kMaxImagePixels);
  if (args.white > 0 && format != FileFormat::png)
    throw UserError("--white", "applies to .png outputs only (.pfm and .exr hold linear radiosity)");
  std::vector<std::string> inputs = {args.solution};
  if (args.scene != "paper") inputs.push_back(args.scene);
  refuse_overwriting_inputs(args.out, "--out", inputs);
  check_output_file(args.out, "--out");
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
  if (!method) {
    std::string names;
    for (Method m : all_methods()) names += (names.empty() ? "" : ", ") + method_name(m);
    throw UserError("--method", "unknown method '" + args.method + "'; valid methods: " + names);
  }
  const MethodParams params = parse_params(*method, args.params, "--param");
  const Solution solution = read_solution_json(args.solution);
  const SideSampling sampling{.barriers = !args.no_barriers, .border_samples = args.border_samples};
  const SolutionReconstruction recon(scene, solution, *method, params, args.solution, sampling);
  if (!recon.fallbacks().empty() && recon.fallbacks().size() == solution.surfaces.size())
    throw UserError(args.solution, args.method + " cannot reconstruct any side of this solution (" +
                                       recon.fallbacks().front().reason + "); use constant, or a solution it fits");
  if (!args.no_barriers && !takes_barriers(*method))
    for (const SurfaceSolution& side : solution.surfaces)
      if (!side.barriers.empty()) {
        std::fprintf(stderr, "radrecon: warning: %s takes no barriers: sides with barriers (e.g. %s) are reconstructed "
                             "across them\n", args.method.c_str(), side.name.c_str());
        break;
      }
  for (const Fallback& f : recon.fallbacks())
    std::fprintf(stderr, "radrecon: warning: %s: %s cannot reconstruct side %s (%s); drawn piecewise constant\n",
                 args.solution.c_str(), args.method.c_str(), f.side.c_str(), f.reason.c_str());
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples_per_axis = args.samples;
  const auto start = std::chrono::steady_clock::now();
  auto last_report = start;
  const RenderProgress progress = [&](double done) {
    const auto now = std::chrono::steady_clock::now();
    if (args.quiet || done >= 1 || now - last_report < std::chrono::seconds(2)) return;
    last_report = now;
    const double elapsed = std::chrono::duration<double>(now - start).count();
    std::fprintf(stderr, "render: %.0f%% of the rows, %.0f s left\n", 100 * done, elapsed * (1 - done) / done);
  };
  const Image img = render(scene, *camera, [&](SideRef side) { return recon.side(side); }, options, progress);
  if (format == FileFormat::pfm) {
    write_pfm(args.out, img);
  } else if (format == FileFormat::exr) {
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
    write_png(args.out, tone_mapped(img, white), true);
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
                  "constant, gouraud (cells); bilinear, bicubic, hermite (grid solutions); shepard, multiquadric, "
                  "thin-plate, natural-neighbour, laplace, sibson-c1, linear, clough-tocher (see 'interpolate --help')")
      ->capture_default_str();
  cmd->add_option("--param", args->params, "NAME=VALUE method parameter, repeatable (see 'interpolate --help')");
  cmd->add_option("--camera", args->camera, "Name of a camera of the scene (paper: view, closeup)")->required();
  cmd->add_option("--size", args->size, "Image size WxH in pixels (each at most " + std::to_string(kMaxImageSide) + ")")->capture_default_str();
  cmd->add_option("--samples", args->samples, "Stratified rays per pixel along each axis (N x N rays)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->add_option("--white", args->white,
                  "PNG: the radiosity (W/m^2) shown as white; default: the largest radiosity of a non-emitting surface")
      ->check(CLI::Range(0.0, 1e12));
  cmd->add_option("--out", args->out, "Image to write: .png (tone-mapped), .pfm or .exr (linear radiosity, W/m^2)")->required();
  cmd->add_flag("--no-barriers", args->no_barriers,
                "Ignore the solution's barriers (by default no sample's influence crosses the lines where surfaces "
                "meet, e.g. the foot of a wall: the paper's leaking light)");
  cmd->add_flag("--border-samples", args->border_samples,
                "scattered methods but constant: add samples on each side's border and along both sides "
                "of its barriers, extrapolated from the nearest samples they see (docs/method.md)");
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace radrecon::cli
