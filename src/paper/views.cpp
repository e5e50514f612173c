#include "paper/views.h"

#include "io/image_io.h"

namespace radrecon {

std::vector<Fallback> render_paper_views(const Scene& scene, const std::vector<CameraHits>& cameras,
                                         const Solution& solution, Method method, const MethodParams& params,
                                         const SideSampling& sampling, double white_w_m2, const std::filesystem::path& dir, const std::string& stem,
                                         const std::string& only_camera) {
  const SolutionReconstruction recon(scene, solution, method, params, "solution " + solution.mesh, sampling);
  for (size_t k = 0; k < scene.cameras.size(); ++k) {
    if (!only_camera.empty() && scene.cameras[k].name != only_camera) continue;
    const Image linear = shade(scene, cameras[k], [&](SideRef side) { return recon.side(side); });
    write_png(dir / (stem + "_" + scene.cameras[k].name + ".png"), tone_mapped(linear, white_w_m2), true);
  }
  return recon.notable_fallbacks();
}

}  // namespace radrecon
