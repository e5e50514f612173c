#include "paper/views.h"

#include "io/image_io.h"

namespace radrecon {

std::vector<Fallback> render_paper_views(const Scene& scene, const std::vector<CameraHits>& cameras,
                                         const Solution& solution, Method method, const MethodParams& params,
                                         double white_w_m2, const std::filesystem::path& dir, const std::string& stem) {
  const SolutionReconstruction recon(scene, solution, method, params, "solution " + solution.mesh);
  for (size_t k = 0; k < scene.cameras.size(); ++k) {
    const Image linear = shade(scene, cameras[k], [&](SideRef side) { return recon.side(side); });
    Image display(linear.width(), linear.height());
    for (int y = 0; y < linear.height(); ++y)
      for (int x = 0; x < linear.width(); ++x)
        for (int c = 0; c < 3; ++c) display.at(x, y)[c] = tone_map(linear.at(x, y)[c], white_w_m2);
    write_png(dir / (stem + "_" + scene.cameras[k].name + ".png"), display, true);
  }
  return recon.fallbacks();
}

}  // namespace radrecon
