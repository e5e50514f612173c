#pragma once
// Tables 1 and 2 as Markdown beside the paper's published figures, and errors.json.

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "paper/data_sets.h"
#include "paper/evaluation.h"
#include "paper/report.h"

namespace radrecon {

/// A published table: method name -> the paper's L1, L2 (MSE), Linf.
using PublishedTable = std::map<std::string, std::array<double, 3>>;
/// Hinkenjann & Pietrek, Table 1 (grid data) and Table 2 (quadtree data).
const PublishedTable& published_table1();
const PublishedTable& published_table2();

/// What the tables and the report state about one run.
struct PaperRun {
  const PaperOptions& options;
  const PaperDataSets& data;
  const EvaluationGrid& at;
  const MethodParams& params;
  std::vector<MethodResult> table1, table2;
  /// Table 3: the grid and quadtree data with the scene's barriers (empty if not run).
  std::vector<MethodResult> grid_barriers, quadtree_barriers;
  /// The same with border samples too (the interpolating scattered methods).
  std::vector<MethodResult> grid_border, quadtree_border;
};

/// Writes DIR/errors.json, DIR/table1.md, DIR/table2.md and (with barriers) DIR/table3.md.
void write_tables(const std::filesystem::path& dir, const PaperRun& run);

/// How the paper's data sets with barriers are reconstructed, in words; with the light's shadow
/// lines among the barriers too if `shadow_lines` (paper --shadow-barriers).
std::string barrier_rule(bool shadow_lines);
/// How border samples are added, in words.
extern const char* const kBorderRule;
/// What SSIM, gradient L2 and overshoot measure, in words.
extern const char* const kMetricsRule;

/// The report's rows and settings (its notes are the caller's).
ReportContent report_content(const PaperRun& run, int rays_per_pixel);

/// "%.3g" of v; "n/a" for a figure not defined.
std::string format_3g(double v);
std::string format_3g(const std::optional<double>& v);
/// The cells "L1 | L2 | RMSE | Linf | SSIM | gradient L2 | overshoot" of a Markdown table row.
std::string figure_cells(const Figures& figures);

}  // namespace radrecon
