#include "experiment/paper.h"

#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "evaluate/norms.h"
#include "experiment/report.h"
#include "experiment/solve.h"
#include "experiment/surface_data.h"
#include "reconstruct/constant.h"
#include "reconstruct/methods.h"
#include "render/ground_map.h"
#include "render/quadtree_figure.h"
#include "solver/solution_io.h"

namespace radrecon {

namespace {

/// The paper's published norms (Hinkenjann & Pietrek, Table 1: grid data), for comparison.
const std::map<std::string, std::array<double, 3>> kPaperTable1 = {
    {"constant", {0.00506, 0.000226, 0.337}},       {"bilinear", {0.00746, 0.000842, 0.329}},
    {"bicubic", {0.0142, 0.00107, 0.31}},           {"shepard", {0.00685, 0.000487, 0.333}},
    {"multiquadric", {0.0113, 0.00087, 0.329}},     {"natural-neighbour", {0.0127, 0.00135, 0.329}},
};

/// The paper's Table 2 (quadtree data).
const std::map<std::string, std::array<double, 3>> kPaperTable2 = {
    {"constant", {0.014, 0.000622, 0.169}},
    {"shepard", {0.0742, 0.00964, 0.302}},
    {"multiquadric", {0.033, 0.00244, 0.412}},
    {"natural-neighbour", {0.0328, 0.00273, 0.329}},
};

class Stopwatch {
 public:
  double lap() {
    auto now = std::chrono::steady_clock::now();
    double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

struct MethodResult {
  std::string name;
  ErrorNorms norms;
};

std::string table_markdown(const std::string& title, const std::vector<MethodResult>& rows,
                           const std::map<std::string, std::array<double, 3>>& paper,
                           const std::string& notes) {
  std::ostringstream md;
  md << "# " << title << "\n\n"
     << "| method | L1 | L2 (MSE) | RMSE | Linf | paper L1 | paper L2 | paper Linf |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const MethodResult& r : rows) {
    md << "| " << r.name << " | " << fmt(r.norms.l1) << " | " << fmt(r.norms.l2) << " | " << fmt(r.norms.rmse)
       << " | " << fmt(r.norms.linf);
    auto it = paper.find(r.name);
    if (it != paper.end())
      md << " | " << fmt(it->second[0]) << " | " << fmt(it->second[1]) << " | " << fmt(it->second[2]) << " |\n";
    else
      md << " | | | |\n";
  }
  md << "\n" << notes << "\n";
  return md.str();
}

nlohmann::json norms_json(const ErrorNorms& n) {
  return {{"L1", n.l1}, {"L2", n.l2}, {"RMSE", n.rmse}, {"Linf", n.linf}};
}

}  // namespace

void run_paper(const PaperOptions& opt) {
  namespace fs = std::filesystem;
  auto say = [&](const std::string& s) {
    if (opt.progress) std::fprintf(stderr, "paper: %s\n", s.c_str());
  };
  Stopwatch clock;
  const Scene scene = paper_scene();
  SolveSettings settings;
  settings.residual = opt.residual;
  auto solve = [&](const std::string& spec, const std::string& label) {
    say("solving " + label + " (" + spec + ")");
    settings.progress_label = opt.progress ? label : "";
    return solve_scene(scene, spec, settings);
  };
  const Solution reference = solve("grid:" + std::to_string(opt.reference_divisions), "reference");
  const double t_reference = clock.lap();
  const Solution grid = solve("grid:" + std::to_string(opt.grid_divisions), "grid16");
  const double t_grid = clock.lap();
  const Solution quadtree = solve("quadtree:" + std::to_string(opt.quadtree_leaves), "quadtree");
  const double t_quadtree = clock.lap();

  const fs::path solutions = opt.out_dir / "solutions";
  write_solution_json(solutions / "reference.json", reference);
  write_solution_json(solutions / "grid16.json", grid);
  write_solution_json(solutions / "quadtree.json", quadtree);
  const double t_write = clock.lap();

  // Evaluation points: the reference cell centres on the ground; reference values: its cells.
  const SurfaceSolution& ref_ground = require_surface(reference, "ground", "reference solution");
  const GridCells ref_cells = grid_cells(ref_ground);
  const int W = ref_cells.nx, H = ref_cells.ny;
  std::vector<Vec2> points;
  points.reserve(static_cast<size_t>(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) points.emplace_back(ref_cells.x0 + (i + 0.5) * ref_cells.dx, ref_cells.y0 + (j + 0.5) * ref_cells.dy);
  const std::vector<double>& ref_values = ref_cells.values;
  double white = 0;
  for (double v : ref_values) white = std::max(white, v);

  const fs::path figures = opt.out_dir / "figures";
  write_png(figures / "fig2_reference_ground.png", radiosity_map(ref_values, W, H, white), true);

  std::vector<double> values(ref_values.size());
  auto evaluate = [&](const Interpolant& interpolant, const std::string& name, const std::string& figure) {
    interpolant.evaluate(points, values);
    write_png(figures / (figure + "_" + name + "_ground.png"), radiosity_map(values, W, H, white), true);
    write_png(figures / (figure + "_" + name + "_difference.png"), difference_map(values, ref_values, W, H, white), false);
    return MethodResult{name, error_norms(values, ref_values)};
  };

  // Table 1: the grid data.
  const GridCells grid_data = grid_cells(require_surface(grid, "ground", "grid solution"));
  const MethodParams params;  // the defaults of methods.h, stated in the tables
  std::vector<MethodResult> table1;
  for (Method m : all_methods())
    table1.push_back(evaluate(*make_grid_interpolant(m, grid_data, params).value(), method_name(m), "fig3"));

  // Table 2: the quadtree data (its leaves; the scattered methods will use their centres).
  const SurfaceSolution& quad_ground = require_surface(quadtree, "ground", "quadtree solution");
  const CellSamples leaves = element_cells(quad_ground);
  const ScatteredSamples centres = element_centres(quad_ground);
  std::vector<MethodResult> table2;
  for (Method m : scattered_methods()) {
    if (m == Method::constant)
      table2.push_back(evaluate(PiecewiseConstant(leaves), "constant", "fig4"));
    else
      table2.push_back(evaluate(*make_scattered_interpolant(m, centres, params).value(), method_name(m), "fig4"));
  }
  write_png(figures / "fig1_quadtree.png",
            quadtree_figure(leaves, 0, 0, std::max(quad_ground.length_u_m, quad_ground.length_v_m), white), false);
  const double t_reconstruct = clock.lap();

  // Views into the scene (Fig. 2-4), every surface reconstructed by the method of the row.
  RenderOptions view;
  view.width = opt.view_width;
  view.height = opt.view_height;
  view.samples_per_axis = opt.view_samples;
  std::vector<std::string> notes;
  std::vector<CameraHits> cameras;
  for (const Camera& c : scene.cameras) cameras.push_back(trace_camera(scene, c, view));
  auto views = [&](const Solution& sol, Method m, const std::string& stem) {
    for (const std::string& side : render_paper_views(scene, cameras, sol, m, params, white, figures, stem))
      notes.push_back(stem + ": " + side + " has too few samples for " + method_name(m) + "; drawn piecewise constant");
  };
  views(reference, Method::constant, "fig2_reference");
  for (Method m : all_methods()) views(grid, m, "fig3_" + method_name(m));
  for (Method m : scattered_methods()) views(quadtree, m, "fig4_" + method_name(m));
  const double t_views = clock.lap();

  nlohmann::json errors;
  for (const MethodResult& r : table1) errors["grid"][r.name] = norms_json(r.norms);
  for (const MethodResult& r : table2) errors["quadtree"][r.name] = norms_json(r.norms);
  auto stats_json = [](const Solution& s) {
    nlohmann::json j = {{"mesh", s.mesh}, {"method", s.stats.method}, {"elements", s.stats.elements},
                        {"residual", s.stats.residual}, {"seconds", s.stats.seconds}};
    if (s.stats.method == "hierarchical") {
      j["links"] = s.stats.links;
      j["epsilon_w"] = s.stats.epsilon_w;
    } else {
      j["shots"] = s.stats.shots;
    }
    return j;
  };
  errors["settings"] = {
      {"reference", stats_json(reference)}, {"grid", stats_json(grid)}, {"quadtree", stats_json(quadtree)},
      {"ground_leaves", quad_ground.elements.size()}, {"residual", opt.residual},
      {"evaluated_at", std::to_string(W) + "x" + std::to_string(H) + " reference cell centres, 3 channels"},
      {"white_w_m2", white}, {"nodal_rule", "mean of the adjacent cells (1, 2 or 4)"},
      {"shepard", describe_params(Method::shepard, params)},
      {"multiquadric", describe_params(Method::multiquadric, params)},
      {"natural-neighbour", describe_params(Method::natural_neighbour, params)}};
  write_text_file(opt.out_dir / "errors.json", errors.dump(2) + "\n");

  const std::string common =
      " Norms in W/m^2 over the " + std::to_string(W) + " x " + std::to_string(H) +
      " reference cell centres (all three channels; the scene is grey). L2 is the mean squared error as in the "
      "paper; RMSE = sqrt(L2). The paper's columns are its published tables (its own scene, whose radiometry "
      "differs), for comparing rankings.";
  std::string settings_text;
  for (Method m : {Method::shepard, Method::multiquadric, Method::natural_neighbour})
    settings_text.append(" ").append(method_name(m)).append(": ").append(describe_params(m, params)).append(".");
  write_text_file(opt.out_dir / "table1.md",
                  table_markdown("Table 1: errors for the reconstruction of grid data", table1, kPaperTable1,
                                 "Grid data: " + grid.mesh + " (" + std::to_string(grid_data.nx) + " x " +
                                     std::to_string(grid_data.ny) + " elements on the ground). Reference: " +
                                     reference.mesh + ". Bilinear and bicubic (natural splines) interpolate nodal "
                                     "values, each the mean of the cells sharing the node (border nodes: of the "
                                     "border cells only); the scattered methods use the cell centres." +
                                     settings_text + common));
  char eps[64];
  std::snprintf(eps, sizeof eps, "%.4g", quadtree.stats.epsilon_w);
  write_text_file(opt.out_dir / "table2.md",
                  table_markdown("Table 2: errors for the reconstruction of quadtree data", table2, kPaperTable2,
                                 "Quadtree data: hierarchical radiosity, " + std::to_string(quad_ground.elements.size()) +
                                     " leaves on the ground (epsilon " + eps + " W, " +
                                     std::to_string(quadtree.stats.links) + " links). Reference: " + reference.mesh +
                                     ". Constant: the value of the leaf containing the point; the scattered "
                                     "methods use the leaf centres." + settings_text + common));
  ReportContent report;
  auto rows = [](const std::vector<MethodResult>& results, const std::map<std::string, std::array<double, 3>>& paper,
                 const std::string& figure) {
    std::vector<ReportRow> out;
    for (const MethodResult& r : results) {
      const auto it = paper.find(r.name);
      const double nan = std::numeric_limits<double>::quiet_NaN();
      out.push_back({r.name, r.norms, figure + "_" + r.name, it != paper.end() ? it->second : std::array<double, 3>{nan, nan, nan}});
    }
    return out;
  };
  report.table1 = rows(table1, kPaperTable1, "fig3");
  report.table2 = rows(table2, kPaperTable2, "fig4");
  report.settings = {
      "Reference: " + reference.mesh + " (" + std::to_string(ref_cells.nx) + " x " + std::to_string(ref_cells.ny) +
          " elements on the ground), progressive refinement to a residual of " + fmt(opt.residual) + " (" +
          std::to_string(reference.stats.shots) + " shots).",
      "Grid data: " + grid.mesh + ", " + std::to_string(grid_data.nx) + " x " + std::to_string(grid_data.ny) +
          " elements on the ground; bilinear and bicubic use nodal values, each the mean of the cells sharing the node.",
      "Quadtree data: hierarchical radiosity, " + std::to_string(quad_ground.elements.size()) + " leaves on the ground, epsilon " +
          fmt(quadtree.stats.epsilon_w) + " W, " + std::to_string(quadtree.stats.links) + " links; the scattered methods use the leaf centres.",
      "Methods:" + settings_text,
      "Norms over the " + std::to_string(W) + " x " + std::to_string(H) +
          " reference cell centres, 3 channels; L2 is the mean squared error, RMSE its root.",
      "Images: display = clamp(B / " + fmt(white) + " W/m^2, 0, 1), sRGB; views with " +
          std::to_string(view.samples_per_axis * view.samples_per_axis) + " rays per pixel; differences 0.5 + 2 (B - B_ref) / " +
          fmt(white) + ", linear."};
  report.notes = notes;
  write_report(opt.out_dir, report);
  const double t_tables = clock.lap();

  char timing[400];
  std::snprintf(timing, sizeof timing,
                "done: reference %.2f s, grid %.2f s, quadtree %.2f s, solutions written %.2f s, reconstruction and "
                "ground figures %.2f s, views %.2f s, tables and report %.2f s; results in %s",
                t_reference, t_grid, t_quadtree, t_write, t_reconstruct, t_views, t_tables, opt.out_dir.string().c_str());
  say(timing);
}

}  // namespace radrecon
