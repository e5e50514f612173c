#pragma once
// The views into the scene of the paper's Fig. 2-4: every camera of the scene, every surface
// side reconstructed by one method.

#include <filesystem>
#include <string>
#include <vector>

#include "reconstruct/methods.h"
#include "render/renderer.h"
#include "sampling/solution_reconstruction.h"
#include "scene/scene.h"
#include "solver/solution.h"

namespace radrecon {

/// What render_paper_views() drew besides its pictures.
struct PaperViews {
  /// The sides the method could not serve (drawn piecewise constant) with the reasons, but for
  /// those where that is exact (notable_fallbacks()).
  std::vector<Fallback> fallbacks;
  /// Rays that met a point where the method gives no value (drawn black), of all rays traced.
  std::size_t rays_without_value = 0, rays = 0;
};

/// Shades every camera of the scene (traced once: `cameras[k]` for scene.cameras[k]) for
/// `solution`, every side reconstructed by `method` (with its barriers if `sampling` says so),
/// tone-mapped with `white_w_m2`, to DIR/STEM_CAMERA.png (only the camera named `only_camera`,
/// unless it is empty).
PaperViews render_paper_views(const Scene& scene, const std::vector<CameraHits>& cameras, const Solution& solution,
                              Method method, const MethodParams& params, const SideSampling& sampling, double white_w_m2,
                              const std::filesystem::path& dir, const std::string& stem, const std::string& only_camera = "");

}  // namespace radrecon
