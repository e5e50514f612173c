#pragma once
// The one-page HTML report of the paper experiment: the scene, the settings, Fig. 1-4 and
// Tables 1 and 2.

#include <filesystem>
#include <string>
#include <array>
#include <vector>

#include "evaluate/metrics.h"

namespace radrecon {

struct ReportRow {
  std::string method;
  Figures figures;         ///< norms, SSIM, gradient_L2, overshoot
  std::string figure_stem;  ///< e.g. "fig3_bilinear": its _view, _closeup, _ground, _difference
  std::array<double, 3> paper;  ///< the paper's L1, L2, Linf; NaN if it has none
  bool views = true;            ///< the _view and _closeup images exist (the paper's methods)
};

struct ReportContent {
  std::vector<ReportRow> table1, table2;
  std::vector<ReportRow> grid_barriers, quadtree_barriers;  ///< Table 3; empty if not run
  std::vector<ReportRow> grid_border, quadtree_border;      ///< with border samples too
  std::vector<std::string> settings;  ///< one line each, shown as a list
  std::vector<std::string> notes;     ///< e.g. fallbacks of the renderer
  std::string reference_grid = "400 x 400";  ///< the reference solution's ground elements, "W x H"
  std::string barrier_rule;  ///< how Table 3's barriers are taken, in words (barrier_rule())
  double white_w_m2 = 1;              ///< the radiosity every picture shows as white
  int rays_per_pixel = 1;             ///< of the views
};

/// Writes DIR/report.html: the scene, the data sets and settings, the figures (labelled, with
/// colour scales), a view comparing any two pictures, and the tables with the paper's rankings
/// beside ours; images referenced relative to DIR (figures/...), no network access needed.
void write_report(const std::filesystem::path& dir, const ReportContent& content);

}  // namespace radrecon
