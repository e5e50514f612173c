#include "cli/solution_methods.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "io/scene_json.h"

namespace radrecon::cli {

namespace {

/// Sides whose fallback to piecewise constant is named one by one; the rest are counted.
constexpr size_t kNamedFallbacks = 3;

}  // namespace

Method method_option(const std::string& name) { return method_by_name(name, "--method"); }

std::unique_ptr<SolutionReconstruction> reconstruct_solution(const Scene& scene, const Solution& solution,
                                                             const std::string& solution_path,
                                                             const std::string& method_name_text,
                                                             const std::vector<std::string>& settings, bool no_barriers,
                                                             bool border_samples) {
  const Method method = method_option(method_name_text);
  if (const std::string problem = border_samples ? border_samples_problem(method) : ""; !problem.empty())
    throw UserError("--border-samples", problem);  // as interpolate refuses it, not ignored
  const MethodParams params = parse_params(method, settings, "--param");
  const SideSampling sampling{.barriers = !no_barriers, .border_samples = border_samples};
  auto recon = std::make_unique<SolutionReconstruction>(scene, solution, method, params, solution_path, sampling);
  if (!recon->fallbacks().empty() && recon->fallbacks().size() == solution.surfaces.size())
    throw UserError(solution_path, method_name_text + " cannot reconstruct any side of this solution (" +
                                       recon->fallbacks().front().reason + ")" +
                                       (is_grid_method(method) ? "; the scattered methods (natural-neighbour, shepard, multiquadric, "
                                                                 "linear, ...) and constant take any solution, or solve on grid:N"
                                                               : "; use constant, or a solution it fits"));
  // Sides drawn piecewise constant (fallbacks) are not reconstructed across their barriers.
  const auto fell_back = [&](const std::string& name) {
    return std::any_of(recon->fallbacks().begin(), recon->fallbacks().end(), [&](const Fallback& f) { return f.side == name; });
  };
  if (!no_barriers && !takes_barriers(method))
    for (const SurfaceSolution& side : solution.surfaces)
      if (!side.barriers.empty() && !fell_back(side.name)) {
        std::fprintf(stderr, "radrecon: warning: %s takes no barriers: sides with barriers (e.g. %s) are reconstructed "
                             "across them\n", method_name_text.c_str(), side.name.c_str());
        break;
      }
  // A model of thousands of triangles may have thousands such sides: the first few by name.
  const std::vector<Fallback> fallbacks = recon->notable_fallbacks();
  for (size_t k = 0; k < std::min(fallbacks.size(), kNamedFallbacks); ++k)
    std::fprintf(stderr, "radrecon: warning: %s: %s cannot reconstruct side %s (%s); drawn piecewise constant\n",
                 solution_path.c_str(), method_name_text.c_str(), fallbacks[k].side.c_str(), fallbacks[k].reason.c_str());
  if (fallbacks.size() > kNamedFallbacks)
    std::fprintf(stderr, "radrecon: warning: %s: %zu more sides drawn piecewise constant (%zu of the %zu in all)\n",
                 solution_path.c_str(), fallbacks.size() - kNamedFallbacks, fallbacks.size(), solution.surfaces.size());
  return recon;
}

std::string scene_of(const std::string& scene_option, const Solution& solution) {
  if (!scene_option.empty()) return scene_option;
  return is_builtin_scene(solution.scene) ? solution.scene : "paper";
}

std::optional<double> largest_reflected_radiosity(const Scene& scene, const Solution& solution) {
  double white = 0;
  for (const SurfaceSolution& s : solution.surfaces) {
    const auto idx = scene.find_surface(s.scene_surface);
    if (idx && (scene.surfaces[*idx].emission_w_m2 > 0).any()) continue;
    for (const SolutionElement& e : s.elements) white = std::max(white, e.radiosity_w_m2.maxCoeff());
  }
  return white > 0 ? std::optional<double>(white) : std::nullopt;
}

}  // namespace radrecon::cli
