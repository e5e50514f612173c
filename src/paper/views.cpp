#include "paper/views.h"

#include "io/image_io.h"

namespace radrecon {

PaperViews render_paper_views(const Scene& scene, const std::vector<CameraHits>& cameras, const Solution& solution,
                              Method method, const MethodParams& params, const SideSampling& sampling, double white_w_m2,
                              const std::filesystem::path& dir, const std::string& stem, const std::string& only_camera) {
  const SolutionReconstruction recon(scene, solution, method, params, "solution " + solution.mesh, sampling);
  PaperViews drawn;
  for (size_t k = 0; k < scene.cameras.size(); ++k) {
    if (!only_camera.empty() && scene.cameras[k].name != only_camera) continue;
    const RenderOptions& view = cameras[k].options;
    Rendering r{Image(view.width, view.height), std::vector<std::uint8_t>(static_cast<size_t>(view.width) * view.height, 0)};
    shade(scene, cameras[k], [&](SideRef side) { return recon.side(side); }, r);
    drawn.rays_without_value += r.rays_without_value;
    drawn.rays += r.rays;
    write_png(dir / (stem + "_" + scene.cameras[k].name + ".png"), tone_mapped(r.image, white_w_m2), true);
  }
  drawn.fallbacks = recon.notable_fallbacks();
  return drawn;
}

}  // namespace radrecon
