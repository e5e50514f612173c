#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <new>
#include <string>

#include "cli/commands.h"
#include "cli/solution_methods.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/progress.h"
#include "core/tolerances.h"
#include "io/image_io.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"
#include "render/exposure.h"
#include "render/renderer.h"
#include "sampling/solution_reconstruction.h"

namespace radrecon::cli {

namespace {

struct RenderArgs {
  std::string scene;  ///< empty: scene_of() the solution
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
/// At most this many pixels: the linear image takes 24 bytes a pixel (1.6 GB at this size).
constexpr long long kMaxImagePixels = static_cast<long long>(kMaxImageSide) * kMaxImageSide;

/// Refuses a render whose rays or memory are beyond what can be done, with advice, before any
/// work. `output_bytes_per_pixel`: what writing the format holds beside the linear image.
void check_render_size(const RenderOptions& options, double output_bytes_per_pixel) {
  const long long pixels = static_cast<long long>(options.width) * options.height;
  const long long per_pixel = static_cast<long long>(options.samples_per_axis) * options.samples_per_axis;
  const std::string asked = picture_size_text(options.width, options.height, options.samples_per_axis);
  check_limit(Limit::render_rays, pixels * per_pixel, "--size", asked + " make",
              "use fewer --samples (--samples 1 casts one ray a pixel) or a smaller --size");
  refuse_beyond_memory("--size", asked,
                       static_cast<double>(render_memory_bytes(options)) + output_bytes_per_pixel * pixels,
                       "use a smaller --size (memory grows with the pixels, not with --samples)");
}

std::string white_text(double white) {
  char text[64];
  std::snprintf(text, sizeof text, "white %.4g W/m^2", white);
  return text;
}

/// Renders and writes the picture (the white point of a PNG as the options say).
void render_and_write(const RenderArgs& args, const Scene& scene, const Camera& camera, const Solution& solution,
                      const SolutionReconstruction& recon, const RenderOptions& options, FileFormat format,
                      const RenderProgress& progress) {
  Rendering rendering = render(scene, camera, [&](SideRef side) { return recon.side(side); }, options, progress);
  Image& img = rendering.image;
  if (rendering.rays_without_value > 0)
    std::fprintf(stderr,
                 "radrecon: warning: %zu of the %zu rays (%.1f%%) met points where %s gives no value (outside the "
                 "samples' hull with outside=none, beyond a radius, cut off by barriers, or in a region excluded as hidden); they are drawn black\n",
                 rendering.rays_without_value, rendering.rays,
                 100.0 * static_cast<double>(rendering.rays_without_value) / static_cast<double>(rendering.rays),
                 args.method.c_str());
  // Radiosity below 0: a method that overshoots between samples (clough-tocher, the RBFs, the
  // natural-neighbour family beside barrier samples) can swing below the data; said, as solve
  // says of the negative values it clamps (an outside-in trial found -0.14 W/m^2 unannounced).
  // Round-off below 0 (a sum of zeros' weights) is not counted: tol::kRenderNegativeRelative.
  double largest = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) largest = std::max(largest, img.at(x, y).maxCoeff());
  size_t negative = 0;
  double lowest = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const double m = img.at(x, y).minCoeff();
      negative += m < -tol::kRenderNegativeRelative * largest;
      lowest = std::min(lowest, m);
    }
  if (negative > 0)
    std::fprintf(stderr,
                 "radrecon: warning: %zu pixels hold radiosity below 0 (down to %.3g W/m^2): %s overshoots the samples "
                 "there (docs/method.md, the methods' ranges)%s\n",
                 negative, lowest, args.method.c_str(),
                 format == FileFormat::png ? "; the PNG shows them black" : "; written as they are");
  std::string white_note;
  if (format == FileFormat::pfm) {
    write_pfm(args.out, img);
  } else if (format == FileFormat::exr) {
    write_exr(args.out, img);
  } else {
    double white = args.white;
    if (white > 0) {
      white_note = white_text(white) + " (--white)";
    } else if (const auto p = percentile_white(rendering, kDefaultWhitePercentile)) {
      white = *p;
      white_note = white_text(white) + " (the " + format_number(kDefaultWhitePercentile) + "th percentile of the lit surfaces seen)";
    } else if (const auto largest = largest_reflected_radiosity(scene, solution)) {
      // No reflecting surface in sight: the largest radiosity of one in the solution.
      white = *largest;
      white_note = white_text(white) + " (no lit surface in sight: the largest of the solution's)";
    } else {
      white = 1;
      white_note = white_text(white) + " (no surface of the solution is lit: every reflecting surface is black)";
    }
    rendering.reflecting = {};
    // Tone-mapped in place: the display image takes no second 24 bytes a pixel.
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x)
        for (int c = 0; c < 3; ++c) img.at(x, y)[c] = tone_map(img.at(x, y)[c], white);
    write_png(args.out, img, true);
  }
  if (!args.quiet && !white_note.empty()) std::fprintf(stderr, "render: %s\n", white_note.c_str());
}

void run_render(const RenderArgs& args) {
  const FileFormat format = file_format(args.out, {FileFormat::png, FileFormat::pfm, FileFormat::exr}, "--out");
  const auto [width, height] = parse_size(args.size, "--size", kMaxImageSide, kMaxImagePixels);
  if (args.white > 0 && format != FileFormat::png)
    throw UserError("--white", "applies to .png outputs only (.pfm and .exr hold linear radiosity)");
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.samples_per_axis = args.samples;
  // Beside the linear image: PNG its bytes (3) and the default white's values (8); PFM nothing
  // (written from the image in batches); EXR its floats (12) and the library's buffers (4).
  check_render_size(options, format == FileFormat::png ? 11 : format == FileFormat::pfm ? 0 : 16);
  refuse_overwriting_inputs(args.out, "--out", {args.solution});
  check_output_file(args.out, "--out");
  parse_params(method_option(args.method), args.params, "--param");  // refused before the solution is read
  const Solution solution = read_solution_json(args.solution);
  const std::string scene_spec = scene_of(args.scene, solution);
  refuse_overwriting_inputs(args.out, "--out", scene_input_files(scene_spec));
  const Scene scene = load_scene(scene_spec);
  const Camera* camera = noting_the_solutions_scene(scene, solution, scene_spec, !args.scene.empty(), [&] {
    for (const Camera& c : scene.cameras)
      if (c.name == args.camera) return &c;
    std::string names;
    for (const Camera& c : scene.cameras) names += (names.empty() ? "" : ", ") + c.name;
    throw UserError("--camera", "the scene has no camera '" + args.camera + "' (cameras: " + (names.empty() ? "none" : names) + ")");
  });
  const std::unique_ptr<SolutionReconstruction> recon_ptr = noting_the_solutions_scene(scene, solution, scene_spec, !args.scene.empty(), [&] {
    return reconstruct_solution(scene, solution, args.solution, args.method, args.params, args.no_barriers,
                                args.border_samples);
  });
  const SolutionReconstruction& recon = *recon_ptr;
  const auto start = std::chrono::steady_clock::now();
  Progress reporter("render", args.quiet);
  const RenderProgress progress = [&](double done) { reporter.update(done, "the pixels"); };
  try {
    render_and_write(args, scene, *camera, solution, recon, options, format, progress);
    reporter.done();
  } catch (const std::bad_alloc&) {
    throw UserError("--size", "out of memory for " + std::to_string(width) + "x" + std::to_string(height) + " pixels at " +
                                  std::to_string(args.samples * args.samples) +
                                  (args.samples == 1 ? " ray" : " rays") + " each (nothing was written): use a smaller --size, or fewer --samples");
  }
  if (!args.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int rays = args.samples * args.samples;
    std::fprintf(stderr, "render: wrote %s (%dx%d, %d %s per pixel) in %.1f s\n", args.out.c_str(), width, height, rays,
                 rays == 1 ? "ray" : "rays", seconds);
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Render a solution seen through one of the scene's cameras, every surface reconstructed by one method. "
      "PNG: tone-mapped, display = clamp(B / white, 0, 1) with the sRGB curve; PFM, EXR: linear radiosity, W/m^2.");
  cmd->add_option("--scene", args->scene, "Scene JSON file, model file (.obj .gltf .glb .ply with an emitting face), or a built-in scene: 'paper' or 'cornell' (docs/cornell.md); default: the solution's scene when it is a built-in one, else 'paper'");
  cmd->add_option("--solution", args->solution, "Solution JSON written by 'radrecon solve'")->required();
  cmd->add_option("--method", args->method,
                  "constant, gouraud (cells); bilinear, bicubic, hermite (grid solutions); shepard, multiquadric, "
                  "thin-plate, natural-neighbour, laplace, sibson-c1, linear, clough-tocher (see 'interpolate --help')")
      ->capture_default_str();
  cmd->add_option("--param", args->params, "NAME=VALUE method parameter, repeatable (see 'interpolate --help')");
  cmd->add_option("--camera", args->camera, "Name of a camera of the scene (paper: view, closeup; cornell: published, blocks, corner)")->required();
  cmd->add_option("--size", args->size,
                  "Image size WxH in pixels (each at most " + std::to_string(kMaxImageSide) + "; width x height x rays per pixel at most --max-rays; memory: about 25 bytes a pixel, whatever --samples)")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples, "Stratified rays per pixel along each axis (N x N rays)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->add_option("--white", args->white,
                  "PNG: the radiosity (W/m^2) shown as white; default: the 99th percentile of the brightest channel "
                  "of the pixels that see only lit, non-emitting surfaces (lights, background and sides drawn black "
                  "do not count; 1% of those pixels may clip)")
      ->check(positive_at_most(1e12));
  cmd->add_option("--out", args->out, "Image to write: .png (tone-mapped), .pfm or .exr (linear radiosity, W/m^2)")->required();
  cmd->add_flag("--no-barriers", args->no_barriers,
                "Ignore the solution's barriers (by default no sample's influence crosses the lines where surfaces "
                "meet, e.g. the foot of a wall: the paper's leaking light)");
  cmd->add_flag("--border-samples", args->border_samples,
                "scattered methods but constant: add samples on each side's border and along both sides "
                "of its barriers, extrapolated from the nearest samples they see (docs/method.md)");
  cmd->add_flag("--quiet", args->quiet, "No progress messages (by default a line on stderr at most every 2 s, updated in place on a terminal)");
  add_limit_options(*cmd, {Limit::render_rays, Limit::file_bytes});
  cmd->callback([args] { run_render(*args); });
}

}  // namespace radrecon::cli
