// radrecon cornell: the Cornell box solved, and seen through one camera with every
// reconstruction method, on one HTML page (docs/cornell.md).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/solution_methods.h"
#include "core/error.h"
#include "core/parse.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/output_folder.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"
#include "render/exposure.h"
#include "render/renderer.h"
#include "sampling/solution_reconstruction.h"
#include "solver/solve.h"

namespace radrecon::cli {

namespace {

struct CornellArgs {
  std::string scene = "cornell";
  std::string mesh = "grid:24";
  /// Nearest samples of the local patches of multiquadric and thin-plate (0: one global system
  /// per side, minutes on grid:32 sides of 1000 samples).
  int rbf_k = 32;
  std::string camera;  ///< empty: the scene's first camera
  int width = 320, height = 320;
  int samples = 2;
  double residual = kDefaultResidual;
  std::string out = "out/cornell";
  bool quiet = false;
};

/// One method's picture on the page.
struct Panel {
  std::string method, file, note;
  std::string params;  ///< the parameters in effect (describe_params)
  double seconds = 0;
};

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

/// A white point as a reader takes it in: 4 significant digits (0.9516, not 0.9516331024472886).
std::string format_4g(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

std::string page(const Scene& scene, const Camera& camera, const std::string& mesh, size_t elements,
                 double white, const std::string& white_source, int samples, const std::vector<Panel>& panels) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>radrecon: " << escaped(scene.name)
       << " with every reconstruction method</title>\n<style>body{font-family:sans-serif;max-width:75em;margin:auto}"
          "figure{display:inline-block;margin:0.5em;vertical-align:top}figcaption{font-size:90%}.note{color:#a40}</style></head><body>\n";
  html << "<h1>" << escaped(scene.name) << ": every reconstruction method</h1>\n<p>Solved by " << escaped(mesh) << " ("
       << elements << " elements); camera <code>" << escaped(camera.name) << "</code>, " << samples * samples
       << (samples == 1 ? " ray" : " rays") << " per pixel; one white point for every picture: " << format_4g(white)
       << " W/m<sup>2</sup> (" << escaped(white_source) << "). Written by <code>radrecon cornell</code>; "
          "the scene: docs/cornell.md.</p>\n";
  for (const Panel& p : panels) {
    html << "<figure><img src=\"" << escaped(p.file) << "\" alt=\"" << escaped(p.method) << "\"><figcaption><b>"
         << escaped(p.method) << "</b>" << (p.params.empty() ? "" : " " + escaped(p.params)) << " ("
         << format_number(p.seconds) << " s)";
    if (!p.note.empty()) html << "<br><span class=\"note\">" << escaped(p.note) << "</span>";
    html << "</figcaption></figure>\n";
  }
  html << "</body></html>\n";
  return html.str();
}

/// The file of the output folder that lists the files its run wrote (io/output_folder.h).
constexpr const char* kCornellManifest = ".radrecon-cornell-files";

void run_cornell(const CornellArgs& args) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const auto seconds_since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  refuse_overwriting_inputs(args.out, "--out", scene_input_files(args.scene));
  check_output_folder(args.out, "--out");
  const Scene scene = load_scene(args.scene);
  const Camera* camera = scene.cameras.empty() ? nullptr : &scene.cameras.front();
  if (!args.camera.empty()) {
    camera = nullptr;
    for (const Camera& c : scene.cameras)
      if (c.name == args.camera) camera = &c;
  }
  if (!camera) {
    std::string names;
    for (const Camera& c : scene.cameras) names += (names.empty() ? "" : ", ") + c.name;
    throw UserError(args.camera.empty() ? args.scene : "--camera",
                    (args.camera.empty() ? std::string("the scene has no camera") : "the scene has no camera '" + args.camera + "'") +
                        " (cameras: " + (names.empty() ? "none" : names) + ")");
  }

  // Every file this writes, checked against the inputs before any work: the scene could lie in
  // --out under one of their names. The scene's and camera's names made fit for a file name.
  const std::filesystem::path dir(args.out);
  const std::string stem = file_name_part(scene.name) + "_" + file_name_part(camera->name) + "_";
  // Nor may two of them be one file (symbolic or hard links in an existing folder).
  const std::vector<std::string> inputs = scene_input_files(args.scene);
  std::vector<std::pair<std::string, std::string>> outputs;
  for (const std::string& file : {std::string("solution.json"), std::string("index.html")})
    outputs.emplace_back("--out", (dir / file).string());
  for (Method m : all_methods()) outputs.emplace_back("--out", (dir / (stem + method_name(m) + ".png")).string());
  for (const auto& [where, file] : outputs) refuse_overwriting_inputs(file, where, inputs);
  refuse_shared_outputs(outputs);

  // The pictures' rays are traced at once (render tiles them): their memory, checked before the
  // solve. 57 bytes a ray measured (979 MB at 1024 x 1024 with --samples 4), and the pictures.
  {
    const long long pixels = static_cast<long long>(args.width) * args.height, rays = pixels * args.samples * args.samples;
    const std::string asked = picture_size_text(args.width, args.height, args.samples);
    const std::string advice =
        "use fewer --samples or a smaller --width and --height, or radrecon render, which draws any size in tiles";
    check_limit(Limit::render_rays, rays, "--width", asked + " make", advice);
    constexpr double kBytesPerRay = 64, kBytesPerPixel = 96;
    refuse_beyond_memory("--width", asked, kBytesPerRay * static_cast<double>(rays) + kBytesPerPixel * static_cast<double>(pixels),
                         advice);
  }

  SolveSettings settings;
  settings.residual = args.residual;
  settings.progress_label = args.quiet ? "" : "cornell";
  const Solution solution = solve_scene(scene, args.mesh, settings, "--mesh");
  // The input is checked and solved: an earlier run's files (another scene's or camera's pictures)
  // go now, before this run writes any; a refused run left them as they were.
  OutputFolderRun folder(dir, kCornellManifest, inputs);
  if (const std::string done = folder.summary(); !done.empty() && !args.quiet) std::fprintf(stderr, "cornell: %s\n", done.c_str());
  write_solution_json(dir / "solution.json", solution);
  size_t elements = 0;
  for (const SurfaceSolution& s : solution.surfaces) elements += s.elements.size();
  if (!args.quiet) std::fprintf(stderr, "cornell: solved %s (%zu elements) in %.1f s\n", args.mesh.c_str(), elements, seconds_since(start));

  RenderOptions view;
  view.width = args.width;
  view.height = args.height;
  view.samples_per_axis = args.samples;
  const CameraHits hits = trace_camera(scene, *camera, view);
  const SideSampling sampling{};  // with the solution's barriers (the blocks' feet), as render does

  // One white point for all: the default of `render` on the piecewise constant picture.
  double white = 0;
  std::string white_source;
  {
    const SolutionReconstruction recon(scene, solution, Method::constant, MethodParams{}, "solution", sampling);
    Rendering r{Image(view.width, view.height), std::vector<std::uint8_t>(static_cast<size_t>(view.width) * view.height, 0)};
    shade(scene, hits, [&](SideRef side) { return recon.side(side); }, r);
    // As render's: with no lit surface in sight, the largest radiosity of one in the solution.
    if (const auto p = percentile_white(r, kDefaultWhitePercentile)) {
      white = *p;
      white_source = "the " + format_number(kDefaultWhitePercentile) + "th percentile of the lit surfaces seen, piecewise constant";
    } else if (const auto largest = largest_reflected_radiosity(scene, solution)) {
      white = *largest;
      white_source = "no lit surface in sight: the largest radiosity of the solution's";
    } else {
      white = 1;
      white_source = "no surface of the solution is lit";
    }
  }

  std::vector<Panel> panels;
  for (Method m : all_methods()) {
    const auto t = clock::now();
    Panel panel{method_name(m), stem + method_name(m) + ".png", "", "", 0};
    MethodParams params;
    params.multiquadric_k = args.rbf_k;
    params.thin_plate_k = args.rbf_k;
    panel.params = describe_params(m, params);
    std::optional<Image> linear;  // the method's picture, if it can reconstruct the solution
    try {
      const SolutionReconstruction recon(scene, solution, m, params, "solution", sampling);
      Rendering r{Image(view.width, view.height), std::vector<std::uint8_t>(static_cast<size_t>(view.width) * view.height, 0)};
      shade(scene, hits, [&](SideRef side) { return recon.side(side); }, r);
      linear = std::move(r.image);
      std::string sides;
      const std::vector<Fallback> fallbacks = recon.notable_fallbacks();
      for (const Fallback& f : fallbacks) sides += (sides.empty() ? "" : ", ") + f.side;
      if (!sides.empty()) panel.note = "drawn piecewise constant on " + sides + " (" + fallbacks.front().reason + ")";
      if (r.rays_without_value > 0) {
        char text[160];
        std::snprintf(text, sizeof text, "%zu of the %zu rays (%.1f%%) met points where it gives no value: drawn black",
                      r.rays_without_value, r.rays, 100.0 * static_cast<double>(r.rays_without_value) / static_cast<double>(r.rays));
        panel.note += (panel.note.empty() ? "" : "; ") + std::string(text);
      }
    } catch (const UserError& e) {
      panel.note = std::string("not drawn: ") + e.what();
      panel.file.clear();
    }
    // Outside the try: a picture that cannot be written fails the command, as any output does.
    if (linear) write_png(dir / panel.file, tone_mapped(*linear, white), true);
    panel.seconds = seconds_since(t);
    if (!args.quiet)
      std::fprintf(stderr, "cornell: %s in %.1f s%s%s\n", panel.method.c_str(), panel.seconds,
                   panel.note.empty() ? "" : "; ", panel.note.c_str());
    panels.push_back(panel);
  }
  write_text_file(dir / "index.html", page(scene, *camera, args.mesh, elements, white, white_source, args.samples, panels));
  folder.finish();
  if (!args.quiet)
    std::fprintf(stderr, "cornell: wrote %s in %.1f s\n", (dir / "index.html").string().c_str(), seconds_since(start));
}

}  // namespace

void add_cornell_command(CLI::App& app) {
  auto args = std::make_shared<CornellArgs>();
  CLI::App* cmd = app.add_subcommand(
      "cornell",
      "Solve the Cornell box (or another scene) by progressive refinement and render one camera with every "
      "reconstruction method, one white point for all, to OUT/index.html with the pictures OUT/SCENE_CAMERA_METHOD.png "
      "and the solution OUT/solution.json. The grid methods draw the red wall's triangles piecewise constant. "
      "The scene: docs/cornell.md.");
  cmd->add_option("--scene", args->scene, "Scene JSON file, model file (.obj .gltf .glb .ply with an emitting face), or a built-in scene: 'cornell' or 'paper'")->capture_default_str();
  cmd->add_option("--mesh", args->mesh, "grid:N (progressive refinement; see 'solve --help')")->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera of the scene (default: its first; cornell: published, blocks, corner)");
  cmd->add_option("--width", args->width, "Picture width, pixels")->check(CLI::Range(8, 4096))->capture_default_str();
  cmd->add_option("--height", args->height, "Picture height, pixels")->check(CLI::Range(8, 4096))->capture_default_str();
  cmd->add_option("--samples", args->samples, "Stratified rays per pixel along each axis (N x N rays)")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  cmd->add_option("--residual", args->residual, "Stop when the unshot power falls below this fraction of the emitted power")
      ->check(residual_check())
      ->capture_default_str();
  cmd->add_option("--rbf-k", args->rbf_k,
                  "multiquadric and thin-plate: local patches of this many nearest samples (their k=); 0: one "
                  "global system per side (slow on fine meshes)")
      ->check(number_check(rbf_patch_problem, "0 or an integer in [" + std::to_string(kLeastRbfPatch) + ", " +
                                                   std::to_string(kMostRbfPatch) + "]"))
      ->capture_default_str();
  cmd->add_option("--out", args->out, "Output folder (created if missing)")->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "No progress messages");
  add_limit_options(*cmd, {Limit::elements, Limit::render_rays, Limit::file_bytes});
  cmd->callback([args] {
    if (args->mesh.rfind("grid:", 0) != 0) throw UserError("--mesh", "must be grid:N (progressive refinement)");
    run_cornell(*args);
  });
}

}  // namespace radrecon::cli
