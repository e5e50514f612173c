#pragma once
// The paper's figures of views into the scene, and the one-page HTML report.

#include <filesystem>
#include <string>
#include <vector>

#include "evaluate/norms.h"
#include "reconstruct/methods.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "solver/solution.h"

namespace radrecon {

/// Renders every camera of the scene (traced once: `cameras[k]` for scene.cameras[k]) for
/// `solution`, every surface reconstructed by `method`, tone-mapped with `white_w_m2`, to
/// DIR/STEM_CAMERA.png. Returns the sides that fell back to piecewise constant.
std::vector<std::string> render_paper_views(const Scene& scene, const std::vector<CameraHits>& cameras,
                                            const Solution& solution, Method method, const MethodParams& params,
                                            double white_w_m2, const std::filesystem::path& dir, const std::string& stem);

struct ReportRow {
  std::string method;
  ErrorNorms norms;
  std::string figure_stem;  ///< e.g. "fig3_bilinear": its _view, _closeup, _ground, _difference
  std::array<double, 3> paper;  ///< the paper's L1, L2, Linf; NaN if it has none
};

struct ReportContent {
  std::vector<ReportRow> table1, table2;
  std::vector<std::string> settings;  ///< one line each, shown as a list
  std::vector<std::string> notes;     ///< e.g. fallbacks of the renderer
};

/// Writes DIR/report.html: the scene, the data sets and settings, Fig. 1-4 and Tables 1 and 2,
/// with images referenced relative to DIR (figures/...), no network access needed.
void write_report(const std::filesystem::path& dir, const ReportContent& content);

}  // namespace radrecon
