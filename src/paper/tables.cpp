#include "paper/tables.h"

#include <cstdio>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "io/atomic_file.h"
#include "sampling/surface_samples.h"

namespace radrecon {

const PublishedTable& published_table1() {
  static const PublishedTable table = {
      {"constant", {0.00506, 0.000226, 0.337}},   {"bilinear", {0.00746, 0.000842, 0.329}},
      {"bicubic", {0.0142, 0.00107, 0.31}},       {"shepard", {0.00685, 0.000487, 0.333}},
      {"multiquadric", {0.0113, 0.00087, 0.329}}, {"natural-neighbour", {0.0127, 0.00135, 0.329}},
  };
  return table;
}

const PublishedTable& published_table2() {
  static const PublishedTable table = {
      {"constant", {0.014, 0.000622, 0.169}},
      {"shepard", {0.0742, 0.00964, 0.302}},
      {"multiquadric", {0.033, 0.00244, 0.412}},
      {"natural-neighbour", {0.0328, 0.00273, 0.329}},
  };
  return table;
}

std::string barrier_rule(bool shadow_lines) {
  return std::string(shadow_lines ? "the ground's contact lines with the walls and the direct light's shadow lines (its "
                                    "D1 and D2 discontinuities, --shadow-barriers; docs/method.md)"
                                  : "the ground's contact lines with the walls") +
         " (the solution's barriers): a sample counts for a point only if the segment between them crosses no "
         "barrier; constant is the nearest visible sample, bilinear, bicubic and hermite take each node's value from "
         "the cells the point sees; linear, clough-tocher and gouraud take no barriers and are left out" +
         (shadow_lines ? ". Shadow lines cut the ground into regions, some of which hold no sample: a point there has no "
                         "value, and a method's norms over the ground are then n/a (radiosity is continuous across "
                         "those lines, which is why they are not used by default)"
                       : "");
}

const char* const kMetricsRule =
    "SSIM: mean structural similarity of the ground figure (sRGB display values) with the reference's (Wang et "
    "al. 2004, 11 x 11 Gaussian window, sigma 1.5; 1 = identical). Gradient L2: the mean squared difference of "
    "the finite-difference gradients, (W/m^2/m)^2: it sees Mach bands and ringing. Overshoot: the largest amount "
    "(W/m^2) by which the reconstruction leaves the range of the data samples around a point (its natural "
    "neighbours among the cell or leaf centres; with barriers, among those it sees, and the nearest it sees).";

const char* const kBorderRule =
    "the methods that take points and barriers (shepard, multiquadric, thin-plate, natural-neighbour, laplace, "
    "sibson-c1) also take samples on the ground's border and on both sides of each wall foot (thin-plate on the "
    "border only), at the samples' spacing, each the value at its point of the weighted least-squares plane "
    "through the 6 nearest samples it sees (constant and the grid methods use the data as it is, and are left "
    "out of Tables 3c and 3d)";

std::string format_3g(double v) {
  if (std::isnan(v)) return "n/a";  // as the report's tables spell it (errors.json: null)
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string format_3g(const std::optional<double>& v) { return v ? format_3g(*v) : "n/a"; }

std::string figure_cells(const Figures& f) {
  return format_3g(f.norms.l1) + " | " + format_3g(f.norms.l2) + " | " + format_3g(f.norms.rmse) + " | " +
         format_3g(f.norms.linf) + " | " + format_3g(f.ssim) + " | " + format_3g(f.gradient_l2) + " | " +
         format_3g(f.overshoot);
}

namespace {

std::string table_markdown(const std::string& title, const std::vector<MethodResult>& rows,
                           const PublishedTable& paper,
                           const std::string& notes) {
  std::ostringstream md;
  md << "# " << title << "\n\n"
     << "| method | L1 | L2 (MSE) | RMSE | Linf | SSIM | gradient L2 | overshoot | paper L1 | paper L2 | paper Linf |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const MethodResult& r : rows) {
    md << "| " << r.name << " | " << figure_cells(r.figures);
    auto it = paper.find(r.name);
    if (it != paper.end())
      md << " | " << format_3g(it->second[0]) << " | " << format_3g(it->second[1]) << " | " << format_3g(it->second[2]) << " |\n";
    else
      md << " | | | |\n";
  }
  md << "\n" << notes << "\n";
  return md.str();
}


nlohmann::json stats_json(const Solution& s) {
  nlohmann::json j = {{"mesh", s.mesh}, {"method", s.stats.method}, {"elements", s.stats.elements},
                      {"residual", s.stats.residual}, {"converged", s.stats.converged}, {"seconds", s.stats.seconds}};
  if (s.stats.method == "hierarchical") {
    j["links"] = s.stats.links;
    j["epsilon_w"] = s.stats.epsilon_w;
  } else {
    j["shots"] = s.stats.shots;
  }
  return j;
}

/// " shepard: mu=4, k=all. multiquadric: ... natural-neighbour: ...".
std::string method_settings(const MethodParams& params) {
  std::string text;
  for (Method m : {Method::shepard, Method::multiquadric, Method::thin_plate, Method::natural_neighbour, Method::laplace,
                   Method::sibson_c1, Method::linear, Method::clough_tocher})
    text.append(" ").append(method_name(m)).append(": ").append(describe_params(m, params)).append(".");
  return text;
}

}  // namespace

void write_table3(const std::filesystem::path& dir, const PaperRun& run);

void write_tables(const std::filesystem::path& dir, const PaperRun& run) {
  const PaperDataSets& d = run.data;
  const SurfaceSolution& grid_ground = require_surface(d.grid, "ground", "grid solution");
  const SurfaceSolution& quad_ground = require_surface(d.quadtree, "ground", "quadtree solution");
  const int W = run.at.width, H = run.at.height;
  nlohmann::json errors;
  for (const MethodResult& r : run.table1) errors["grid"][r.name] = figures_json(r.figures);
  for (const MethodResult& r : run.table2) errors["quadtree"][r.name] = figures_json(r.figures);
  for (const MethodResult& r : run.grid_barriers) errors["grid+barriers"][r.name] = figures_json(r.figures);
  for (const MethodResult& r : run.quadtree_barriers) errors["quadtree+barriers"][r.name] = figures_json(r.figures);
  for (const MethodResult& r : run.grid_border) errors["grid+barriers+border"][r.name] = figures_json(r.figures);
  for (const MethodResult& r : run.quadtree_border) errors["quadtree+barriers+border"][r.name] = figures_json(r.figures);
  errors["settings"] = {
      {"reference", stats_json(d.reference)}, {"grid", stats_json(d.grid)}, {"quadtree", stats_json(d.quadtree)},
      {"ground_leaves", quad_ground.elements.size()}, {"residual", run.options.residual},
      {"evaluated_at", std::to_string(W) + "x" + std::to_string(H) + " reference cell centres, 3 channels"},
      {"white_w_m2", run.at.white_w_m2}, {"nodal_rule", "mean of the adjacent cells (1, 2 or 4)"},
      {"shepard", describe_params(Method::shepard, run.params)},
      {"multiquadric", describe_params(Method::multiquadric, run.params)},
      {"natural-neighbour", describe_params(Method::natural_neighbour, run.params)},
      {"thin-plate", describe_params(Method::thin_plate, run.params)},
      {"laplace", describe_params(Method::laplace, run.params)},
      {"sibson-c1", describe_params(Method::sibson_c1, run.params)},
      {"linear", describe_params(Method::linear, run.params)},
      {"clough-tocher", describe_params(Method::clough_tocher, run.params)},
      {"metrics", kMetricsRule}};
  // Only the rules this run used (formats.md: the settings that produced the numbers).
  if (run.options.barriers) errors["settings"]["barriers"] = barrier_rule(run.options.shadow_barriers);
  if (run.options.barriers && run.options.border_samples) errors["settings"]["border_samples"] = kBorderRule;
  write_text_file(dir / "errors.json", errors.dump(2) + "\n");

  const std::string common =
      " Norms over the " + std::to_string(W) + " x " + std::to_string(H) +
      " reference cell centres (all three channels; the scene is grey): L1 and Linf in W/m^2; L2 is the mean squared "
      "error as in the paper, in (W/m^2)^2; RMSE = sqrt(L2), in W/m^2. " + std::string(kMetricsRule) + " The paper's columns are its published tables (its own scene, whose radiometry "
      "differs), for comparing rankings.";
  const std::string settings_text = method_settings(run.params);
  write_text_file(dir / "table1.md",
                  table_markdown("Table 1: errors for the reconstruction of grid data", run.table1, published_table1(),
                                 "Grid data: " + d.grid.mesh + " (" + std::to_string(grid_ground.grid_nu) + " x " +
                                     std::to_string(grid_ground.grid_nv) + " elements on the ground). Reference: " +
                                     d.reference.mesh + ". Bilinear, bicubic (natural splines) and hermite interpolate "
                                     "nodal values, each the mean of the cells sharing the node (border nodes: of the "
                                     "border cells only); gouraud averages the cells at each corner and interpolates "
                                     "linearly over two triangles per cell; the scattered methods use the cell centres." +
                                     settings_text + common));
  char eps[64];
  std::snprintf(eps, sizeof eps, "%.4g", d.quadtree.stats.epsilon_w);
  write_text_file(dir / "table2.md",
                  table_markdown("Table 2: errors for the reconstruction of quadtree data", run.table2, published_table2(),
                                 "Quadtree data: hierarchical radiosity, " + std::to_string(quad_ground.elements.size()) +
                                     " leaves on the ground (epsilon " + eps + " W, " +
                                     std::to_string(d.quadtree.stats.links) + " links). Reference: " + d.reference.mesh +
                                     ". Constant: the value of the leaf containing the point; gouraud: the balanced "
                                     "quadtree triangulated without T-vertices, the leaves averaged at each vertex; the "
                                     "scattered methods use the leaf centres." + settings_text + common));
  if (!run.grid_barriers.empty() || !run.quadtree_barriers.empty()) write_table3(dir, run);
}

namespace {

/// Table 3's rows: with barriers, and the same method without them (Table 1 or 2) beside.
std::string barrier_table(const std::string& title, const std::vector<MethodResult>& with,
                          const std::vector<MethodResult>& without) {
  std::ostringstream md;
  md << "## " << title << "\n\n"
     << "| method | L1 | L2 (MSE) | RMSE | Linf | SSIM | gradient L2 | overshoot | without barriers: L1 | L2 | Linf | SSIM |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const MethodResult& r : with) {
    md << "| " << r.name << " | " << figure_cells(r.figures);
    for (const MethodResult& p : without)
      if (p.name == r.name)
        md << " | " << format_3g(p.figures.norms.l1) << " | " << format_3g(p.figures.norms.l2) << " | "
           << format_3g(p.figures.norms.linf) << " | " << format_3g(p.figures.ssim);
    md << " |\n";
  }
  return md.str() + "\n";
}

}  // namespace

void write_table3(const std::filesystem::path& dir, const PaperRun& run) {
  write_text_file(dir / "table3.md",
                  "# Table 3: errors with the scene's barriers\n\n" +
                      barrier_table("Table 3a: grid data (" + run.data.grid.mesh + ")", run.grid_barriers, run.table1) +
                      barrier_table("Table 3b: quadtree data (" + run.data.quadtree.mesh + ")", run.quadtree_barriers, run.table2) +
                      (run.grid_border.empty()
                           ? std::string()
                           : barrier_table("Table 3c: grid data with border samples", run.grid_border, run.table1) +
                                 barrier_table("Table 3d: quadtree data with border samples", run.quadtree_border, run.table2)) +
                      "Barriers: " + barrier_rule(run.options.shadow_barriers) + "." +
                      (run.grid_border.empty() ? std::string() : std::string(" Border samples: ") + kBorderRule + ".") +
                      " Same data, methods, settings and norms as Tables 1 and 2.\n");
}

ReportContent report_content(const PaperRun& run, int rays_per_pixel) {
  const PaperDataSets& d = run.data;
  const SurfaceSolution& grid_ground = require_surface(d.grid, "ground", "grid solution");
  const SurfaceSolution& quad_ground = require_surface(d.quadtree, "ground", "quadtree solution");
  const double white = run.at.white_w_m2;
  auto rows = [](const std::vector<MethodResult>& results, const PublishedTable& paper, const std::string& figure) {
    std::vector<ReportRow> out;
    for (const MethodResult& r : results) {
      const auto it = paper.find(r.name);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      const std::optional<Method> m = parse_method(r.name);
      out.push_back({r.name, r.figures, figure + "_" + r.name,
                     it != paper.end() ? it->second : std::array<double, 3>{nan, nan, nan}, m && is_paper_method(*m)});
    }
    return out;
  };
  ReportContent report;
  report.reference_grid = std::to_string(run.at.width) + " x " + std::to_string(run.at.height);
  report.barrier_rule = barrier_rule(run.options.shadow_barriers);
  report.white_w_m2 = white;
  report.rays_per_pixel = rays_per_pixel;
  report.table1 = rows(run.table1, published_table1(), "fig3");
  report.table2 = rows(run.table2, published_table2(), "fig4");
  const PublishedTable none;
  report.grid_barriers = rows(run.grid_barriers, none, "fig5");
  report.quadtree_barriers = rows(run.quadtree_barriers, none, "fig6");
  report.grid_border = rows(run.grid_border, none, "fig7");
  report.quadtree_border = rows(run.quadtree_border, none, "fig8");
  report.settings = {
      "Reference: " + d.reference.mesh + " (" + std::to_string(run.at.width) + " x " + std::to_string(run.at.height) +
          " elements on the ground), progressive refinement to a residual of " + format_3g(run.options.residual) + " (" +
          std::to_string(d.reference.stats.shots) + " shots).",
      "Grid data: " + d.grid.mesh + ", " + std::to_string(grid_ground.grid_nu) + " x " + std::to_string(grid_ground.grid_nv) +
          " elements on the ground; bilinear and bicubic use nodal values, each the mean of the cells sharing the node.",
      "Quadtree data: hierarchical radiosity, " + std::to_string(quad_ground.elements.size()) + " leaves on the ground (" +
          d.quadtree.mesh + ": refined with epsilon " + format_3g(d.quadtree.stats.epsilon_w) +
          " W, the splits of largest estimate kept up to that count), " + std::to_string(d.quadtree.stats.links) +
          " links; the scattered methods use the leaf centres.",
      "Methods:" + method_settings(run.params),
      "Norms over the " + std::to_string(run.at.width) + " x " + std::to_string(run.at.height) +
          " reference cell centres, 3 channels: L1 and Linf in W/m^2; L2 is the mean squared error, in (W/m^2)^2, RMSE its "
          "root.",
      kMetricsRule,
      "Images: display = clamp(B / " + format_3g(white) + " W/m^2, 0, 1), sRGB; views with " + std::to_string(rays_per_pixel) +
          " rays per pixel; differences 0.5 + 2 (B - B_ref) / " + format_3g(white) + ", linear."};
  return report;
}

}  // namespace radrecon
